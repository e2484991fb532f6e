// Resource limits (issue 14): the shared checks every input goes through.
#include "gridloc/grids/limits.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "test_support.hpp"

namespace gridloc {
namespace {

TEST(ResourceLimits, DefaultsAreValidAndEachFieldIsChecked) {
  EXPECT_NO_THROW(ResourceLimits{}.validate());
  ResourceLimits limits;
  limits.max_cells = 0.0;
  test::expect_error([&] { limits.validate(); }, {"max_cells", "positive"});
  limits = {};
  limits.max_memory_mb = NAN;
  test::expect_error([&] { limits.validate(); }, {"max_memory_mb"});
  limits = {};
  limits.max_coordinate_m = -1.0;
  test::expect_error([&] { limits.validate(); }, {"max_coordinate_m"});
}

TEST(ResourceLimits, GridCellsNameTheLimitAndItsOption) {
  ResourceLimits limits;
  limits.max_cells = 1000.0;
  EXPECT_EQ(check_grid_cells(10.0, 100.0, limits, "map image"), 1000.0);
  test::expect_error([&] { check_grid_cells(20000.0, 20000.0, limits, "map image"); },
                     {"map image (20000 x 20000)", "4e+08 cells", "limit of 1000", "--max-cells"});
  test::expect_error([&] { check_grid_cells(0.0, 5.0, limits, "search grid"); },
                     {"search grid", "empty"});
  test::expect_error([&] { check_grid_cells(NAN, 5.0, limits, "search grid"); }, {"search grid"});
  limits.max_cells = 1e30;
  test::expect_error([&] { check_grid_cells(1e12, 1.0, limits, "polygon map"); },
                     {"polygon map", "too long"});
}

TEST(ResourceLimits, MemoryEstimateNamesTheOption) {
  ResourceLimits limits;
  limits.max_memory_mb = 100.0;
  EXPECT_NO_THROW(check_memory(100.0 * 1024 * 1024, limits, "the global grids"));
  test::expect_error([&] { check_memory(5e9, limits, "the global grids"); },
                     {"the global grids would need about", "MB", "--max-memory-mb"});
}

TEST(ResourceLimits, InputFilesMustBeRegularAndSmallEnough) {
  test::TempDir dir;
  const std::string file = dir.write("scan.csv", std::string(3 * 1024 * 1024, 'x'));
  ResourceLimits limits;
  EXPECT_EQ(check_input_file(file, "scan file", limits), 3u * 1024 * 1024);
  EXPECT_EQ(read_input_file(file, "scan file", limits).size(), 3u * 1024 * 1024);
  limits.max_file_mb = 2.0;
  test::expect_error([&] { check_input_file(file, "scan file", limits); },
                     {file, "scan file is 3 MB, more than the limit of 2 MB", "--max-file-mb"});
  test::expect_error([&] { check_input_file(dir.path().string(), "readings file", limits); },
                     {"is a directory, not a readings file"});
  test::expect_error([&] { check_input_file(dir.file("none"), "sonar ring", limits); },
                     {"sonar ring not found"});
  test::expect_error([&] { check_input_file("/dev/null", "map image", limits); },
                     {"/dev/null", "not a regular file"});
}

}  // namespace
}  // namespace gridloc
