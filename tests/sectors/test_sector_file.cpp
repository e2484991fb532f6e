// Tests of engine/src/sectors/sector_file.cpp: sectors saved and loaded are the sectors
// computed (the same estimates from them), and a file for another map, other options or a
// broken file is refused naming it.
#include "gridloc/engine/sectors/sector_file.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "gridloc/engine/sectors/estimator.hpp"
#include "gridloc/grids/error.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

PolygonMap l_room() {
  return make_polygon_map({{0, 0}, {7, 0}, {7, 3}, {3, 3}, {3, 6}, {0, 6}},
                          {{{5.0, 1.0}, {5.0, 1.5}, {5.5, 1.5}, {5.5, 1.0}}});
}

void expect_same(const SectorMap& a, const SectorMap& b) {
  ASSERT_EQ(a.sectors.size(), b.sectors.size());
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.sector_of, b.sector_of);
  EXPECT_EQ(a.grid.width, b.grid.width);
  EXPECT_EQ(a.grid.origin, b.grid.origin);
  for (std::size_t k = 0; k < a.sectors.size(); ++k) {
    const Sector &s = a.sectors[k], &t = b.sectors[k];
    EXPECT_EQ(s.label, t.label) << k;
    EXPECT_EQ(s.features, t.features) << k;
    EXPECT_EQ(s.visible, t.visible) << k;
    EXPECT_EQ(s.representative, t.representative) << k;
    EXPECT_EQ(s.area_m2, t.area_m2) << k;
    EXPECT_EQ(s.ambiguous, t.ambiguous) << k;
    EXPECT_EQ(s.n_min_two, t.n_min_two) << k;
  }
}

TEST(SectorFile, SavedSectorsLoadAsComputedAndLocalizeAlike) {
  test::TempDir dir;
  const PolygonMap map = l_room();
  const SectorOptions options;
  const SectorMap computed = compute_sectors(map, options);
  const std::string path = dir.file("sectors.json");
  save_sectors(computed, options, path);
  SectorMap loaded = load_sectors(path, map, options);
  expect_same(computed, loaded);
  const SectorEstimator fresh(map), saved(std::move(loaded));
  SearchWindow everywhere;
  everywhere.center = {3.5, 3.0, 0.0};
  everywhere.half_xy = 4.0;
  everywhere.half_theta = std::numbers::pi;
  for (const Pose2& truth : {Pose2{1.5, 1.5, 0.3}, Pose2{6.0, 2.0, -1.0}, Pose2{1.2, 4.8, 2.0}}) {
    const Observation scan{{}, polygon_scan(map, truth, 360, 20.0)};
    const Estimate a = fresh.estimate(scan, everywhere), b = saved.estimate(scan, everywhere);
    EXPECT_EQ(a.verdict, b.verdict);
    EXPECT_EQ(a.pose.x, b.pose.x);
    EXPECT_EQ(a.pose.y, b.pose.y);
    EXPECT_EQ(a.pose.theta, b.pose.theta);
  }
}

TEST(SectorFile, AnotherMapOtherOptionsOrABrokenFileAreRefused) {
  test::TempDir dir;
  const PolygonMap map = l_room();
  const SectorOptions options;
  const std::string path = dir.file("sectors.json");
  save_sectors(compute_sectors(map, options), options, path);
  const PolygonMap other = make_polygon_map({{0, 0}, {7, 0}, {7, 3}, {3, 3}, {3, 6}, {0, 6}}, {});
  const auto message = [&](const std::string& file, const PolygonMap& m, const SectorOptions& o) {
    try {
      load_sectors(file, m, o);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(path, other, options),
            path + ": the sectors were computed on another polygon map");
  SectorOptions finer = options;
  finer.cell_m = 0.025;
  EXPECT_EQ(message(path, map, finer),
            path + ": the sectors were computed with cell_m 0.05, not 0.025");
  const std::string broken =
      dir.write("broken.json", "{\"format\": \"gridloc visibility sectors 1\"");
  EXPECT_EQ(message(broken, map, options).rfind(broken + ": malformed sectors file", 0), 0u);
  EXPECT_EQ(message(dir.file("missing.json"), map, options),
            dir.file("missing.json") + ": sectors file not found");
  EXPECT_EQ(message(dir.path().string(), map, options),
            dir.path().string() + ": is a directory, not a sectors file");
  ResourceLimits tiny;
  tiny.max_file_mb = 1e-4;
  EXPECT_THROW(load_sectors(path, map, options, tiny), Error);
}

}  // namespace
}  // namespace gridloc
