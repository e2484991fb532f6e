// `gridloc localize` and `gridloc eval` with the likelihood-field global grid: the model
// runs, --global-model is an alias, and bad --field-* values are one-line errors naming the
// option.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "cli_support.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using namespace test;

const std::string kMap = map_path("room_rect");

TEST(FieldCli, LocalizeOnTheFieldFindsThePose) {
  TempDir dir;
  const std::string readings = (dir.path() / "r.json").string();
  ASSERT_EQ(
      run_cli(dir, "simulate --map " + quote(kMap) + " --pose 2.0,1.5,0.5 --out " + quote(readings))
          .status,
      0);
  const CliRun r = run_cli(dir, "localize --map " + quote(kMap) + " --readings " + quote(readings) +
                                    " --prior 2.3,1.3,0.3 --global-model field --field-sigma 0.1"
                                    " --field-cutoff 0.1");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_LT(std::hypot(j["pose"]["x"].get<double>() - 2.0, j["pose"]["y"].get<double>() - 1.5),
            0.1);
}

TEST(FieldCli, BadFieldValuesNameTheOption) {
  TempDir dir;
  expect_cli_error(run_cli(dir, "eval --quiet --trials 1 --global-model field --field-sigma -1"),
                   {"--field-sigma", "sigma_m"});
  expect_cli_error(run_cli(dir, "eval --quiet --trials 1 --field-cutoff nan"), {"--field-cutoff"});
  expect_cli_error(run_cli(dir, "eval --quiet --trials 1 --field-free 0.5"), {"--field-free"});
  expect_cli_error(run_cli(dir, "eval --quiet --trials 1 --global-model blurred"),
                   {"thinned, raw or field", "blurred"});
}

}  // namespace
}  // namespace gridloc
