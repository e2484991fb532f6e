// Shards of an evaluation's trials (issue 35): "K/N" parsing, which trials a shard owns, and
// that the shards of a run own every trial exactly once.
#include <gtest/gtest.h>

#include "gridloc/engine/evaluation/shard.hpp"
#include "gridloc/grids/error.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

TEST(Shard, ParsesOneBasedKOfN) {
  const Shard shard = parse_shard("2/8");
  EXPECT_EQ(shard.index, 1);
  EXPECT_EQ(shard.count, 8);
  EXPECT_EQ(shard.to_string(), "2/8");
  EXPECT_TRUE(shard.owns(1));
  EXPECT_TRUE(shard.owns(9));
  EXPECT_FALSE(shard.owns(2));
}

TEST(Shard, TheShardsOfARunOwnEveryTrialOnce) {
  for (int count = 1; count <= 5; ++count) {
    for (int trial = 0; trial < 23; ++trial) {
      int owners = 0;
      for (int k = 1; k <= count; ++k) {
        owners += parse_shard(std::to_string(k) + "/" + std::to_string(count)).owns(trial);
      }
      EXPECT_EQ(owners, 1) << "trial " << trial << " of " << count << " shards";
    }
  }
}

TEST(Shard, BadTextIsRefusedNamingTheOption) {
  for (const char* text : {"0/2", "3/2", "1/0", "-1/2", "a/2", "1/b", "12", "", "1/2/3", "1 /2"}) {
    test::expect_error([&] { parse_shard(text, "--shard"); }, {"--shard", "K/N"});
  }
  test::expect_error([] { validate(Shard{3, 2}); }, {"shard", "K <= N"});
}

}  // namespace
}  // namespace gridloc
