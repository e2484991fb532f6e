// Tests of sensors/src/slam_relations.cpp: the SLAM benchmark's relations and their pairing
// with the scans of a CARMEN log.
#include "gridloc/sensors/slam_relations.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "test_support.hpp"

namespace gridloc {
namespace {

TEST(SlamRelations, ReadsAndPairsByTimestamp) {
  test::TempDir dir;
  const std::string path = dir.write("r.relations",
                                     "# t1 t2 x y z roll pitch yaw\n"
                                     "110.0 112.001 0.5 -0.25 0 0 0 0.3\n"
                                     "110.0 111.5 1 1 0 0 0 0\n"
                                     "112.0 110.0005 -0.5 0.25 0 0 0 -0.3\n");
  const std::vector<SlamRelation> rel = load_slam_relations(path);
  ASSERT_EQ(rel.size(), 3u);
  EXPECT_EQ(rel[0].t1, 110.0);
  EXPECT_EQ(rel[0].motion.x, 0.5);
  EXPECT_EQ(rel[0].motion.y, -0.25);
  EXPECT_EQ(rel[0].motion.theta, 0.3);  // yaw, the 8th field
  EXPECT_EQ(rel[0].line, 2u);
  // Scans at relative times 10 and 12 (out of order), offset 100 s.
  std::istringstream log_text(
      "FLASER 2 1 1 0 0 0 0 0 0 12.000 h 12.000\n"
      "FLASER 2 1 1 0 0 0 0 0 0 10.000 h 10.000\n");
  const CarmenLog log = parse_carmen_log(log_text, "log");
  const std::vector<RelationPair> pairs = pair_relations(rel, log, 100.0);
  ASSERT_EQ(pairs.size(), 2u);  // 111.5 falls on no scan
  EXPECT_EQ(pairs[0].first, 1u);
  EXPECT_EQ(pairs[0].second, 0u);
  EXPECT_EQ(pairs[1].first, 0u);
  EXPECT_EQ(pairs[1].second, 1u);
  // A tighter tolerance still allows half the last printed digit (0.5 ms here): 112.001 is
  // 1 ms off, 110.0005 only 0.5 ms.
  const std::vector<RelationPair> tight = pair_relations(rel, log, 100.0, 0.0001);
  ASSERT_EQ(tight.size(), 1u);
  EXPECT_EQ(tight[0].relation.line, 4u);
  // A log printed to 0.1 s is matched to within 0.05 s.
  std::istringstream coarse_text(
      "FLASER 2 1 1 0 0 0 0 0 0 11.5 h 11.5\n"
      "FLASER 2 1 1 0 0 0 0 0 0 10.0 h 10.0\n");
  const CarmenLog coarse = parse_carmen_log(coarse_text, "coarse");
  EXPECT_EQ(coarse.lasers[0].timestamp_resolution, 0.1);
  ASSERT_EQ(pair_relations(rel, coarse, 100.0).size(), 1u);  // 110.0 -> 111.5
  // Two relation times that land on one coarse scan give no pair: 110.0 and 110.04 both read
  // as the scan at 10.0.
  const std::vector<SlamRelation> same = {{110.0, 110.04, {0.3, 0, 0}, 1}};
  EXPECT_TRUE(pair_relations(same, coarse, 100.0).empty());
}

TEST(SlamRelations, Errors) {
  test::TempDir dir;
  const std::string missing = dir.file("none.relations");
  test::expect_error([&] { load_slam_relations(missing); }, {missing, "not found"});
  const std::string short_line = dir.write("a.relations", "1 2 3\n");
  test::expect_error([&] { load_slam_relations(short_line); }, {":1", "8 numbers", "got 3"});
  const std::string text = dir.write("b.relations", "\n1 2 3 4 5 6 7 yaw\n");
  test::expect_error([&] { load_slam_relations(text); }, {":2", "field 8", "'yaw'"});
  const std::string nan = dir.write("c.relations", "1 2 nan 4 5 6 7 8\n");
  test::expect_error([&] { load_slam_relations(nan); }, {"field 3", "finite"});
}

// The Intel lab relations against the corrected Intel log: with full-precision times 90 have
// both ends on its 910 scans (../shared/datasets/xiaofeng419_SLAM-2D-LIDAR-SCAN/NOTES.txt).
TEST(SlamRelations, PairsTheIntelRelationsWithItsScans) {
  const std::string dir =
      std::string(GRIDLOC_TEST_SHARED_DIR) + "/datasets/xiaofeng419_SLAM-2D-LIDAR-SCAN";
  if (!std::filesystem::exists(dir + "/intel.relations")) {
    GTEST_SKIP() << "../shared is absent (" << dir << "): real-data test skipped";
  }
  const auto relations = load_slam_relations(dir + "/intel.relations");
  EXPECT_EQ(relations.size(), 2984u);
  const CarmenLog log = load_carmen_log(dir + "/intel.gfs.log");
  const auto pairs = pair_relations(relations, log, 976052857.337311);
  // The log prints 6 significant digits (times past 1000 s to 0.01 s), so the pairing allows
  // half that: 118 pairs, more than the 90 that full-precision times give (NOTES.txt).
  EXPECT_GE(pairs.size(), 90u);
  EXPECT_LE(pairs.size(), 130u);
  for (const RelationPair& p : pairs) {
    EXPECT_NE(p.first, p.second);
    const LaserRecord& a = log.lasers[p.first];
    const LaserRecord& b = log.lasers[p.second];
    EXPECT_LE(std::abs(a.timestamp + 976052857.337311 - p.relation.t1),
              std::max(0.002, 0.5 * a.timestamp_resolution) + 1e-6);
    EXPECT_LE(std::abs(b.timestamp + 976052857.337311 - p.relation.t2),
              std::max(0.002, 0.5 * b.timestamp_resolution) + 1e-6);
  }
}

}  // namespace
}  // namespace gridloc

namespace gridloc {
namespace {

// Issue 14: the file is checked where it enters; a line cannot grow without end.
TEST(SlamRelations, InputLimits) {
  test::TempDir dir;
  test::expect_error([&] { load_slam_relations(dir.path().string()); },
                     {dir.path().string(), "is a directory", "relations file"});
  const std::string p = dir.write("r.relations", "1 2 3 4 5 6 7 8\n");
  ResourceLimits tiny_file;
  tiny_file.max_file_mb = 1e-6;
  test::expect_error([&] { load_slam_relations(p, tiny_file); }, {p, "--max-file-mb"});
  ResourceLimits tiny_memory;
  tiny_memory.max_memory_mb = 1e-6;
  test::expect_error([&] { load_slam_relations(p, tiny_memory); }, {p, "--max-memory-mb"});
  const std::string long_line = dir.write("long.relations", std::string(70000, '1'));
  test::expect_error([&] { load_slam_relations(long_line); }, {"long.relations:1", "longer than"});
}

}  // namespace
}  // namespace gridloc
