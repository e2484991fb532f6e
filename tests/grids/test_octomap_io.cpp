// Tests of grids/src/octomap_io.cpp: OctoMap trees (.bt, .ot) sliced to a height band and
// projected onto 2-D occupancy maps; and `gridloc localize` on a .bt map.
#include "gridloc/grids/octomap_io.hpp"

#include <gtest/gtest.h>
#include <octomap/ColorOcTree.h>
#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/sonar_ring.hpp"
#include "gridloc/sensors/sonar_sim.hpp"
#ifdef GRIDLOC_CLI_PATH
#include "cli_support.hpp"
#endif
#include "test_support.hpp"

namespace gridloc {
namespace {

using test::expect_error;
using test::TempDir;

constexpr double kRes = 0.1;  // the test tree's leaf size (m)

/// Marks the leaves of index box [x0, x1) x [y0, y1) x [z0, z1) (leaf i spans
/// [i * res, (i + 1) * res)) occupied or free, one update each.
void fill(octomap::OcTree& tree, int x0, int x1, int y0, int y1, int z0, int z1, bool occupied) {
  const double r = tree.getResolution();
  for (int x = x0; x < x1; ++x) {
    for (int y = y0; y < y1; ++y) {
      for (int z = z0; z < z1; ++z) {
        tree.updateNode(
            octomap::point3d(static_cast<float>((x + 0.5) * r), static_cast<float>((y + 0.5) * r),
                             static_cast<float>((z + 0.5) * r)),
            occupied);
      }
    }
  }
}

/// The scene, in leaf indices (0.1 m): free space in the band (z 0.1..0.6 m) over
/// x [-0.5, 1.0) y [-0.3, 1.0); a wall at x [1.0, 1.1) from the floor to 1 m; a 0.4 m occupied
/// cube at x [1.6, 2.0) y [0, 0.4) z [0, 0.4) (one pruned leaf); a floor (z [-0.1, 0)) under
/// x [-0.5, 1.0) y [-0.3, 1.5); table tops at z [0.9, 1.0), one over free space, one over
/// nothing; free space above the band (z [0.7, 0.8)) and free space just below it (z [0, 0.1),
/// touching the band's lower face) over x [1.2, 1.5).
void build_scene(octomap::OcTree& tree) {
  fill(tree, -5, 10, -3, 10, 1, 6, false);  // free, in the band
  fill(tree, 10, 11, -3, 10, 0, 10, true);  // wall
  fill(tree, 16, 20, 0, 4, 0, 4, true);     // cube: prunes into one 0.4 m leaf
  fill(tree, -5, 10, -3, 15, -1, 0, true);  // floor, below the band
  fill(tree, 2, 5, 2, 5, 9, 10, true);      // table top over free space
  fill(tree, 2, 5, 11, 13, 9, 10, true);    // table top over nothing
  fill(tree, 12, 15, 6, 9, 7, 8, false);    // free, above the band
  fill(tree, 12, 15, 0, 3, 0, 1, false);    // free, below the band (touches z = 0.1)
}

/// The scene's expected cell at leaf column (x, y) for the default band.
CellState expected_scene(int x, int y) {
  if ((x == 10 && y >= -3 && y < 10) || (x >= 16 && x < 20 && y >= 0 && y < 4)) {
    return CellState::Occupied;
  }
  if (x >= -5 && x < 10 && y >= -3 && y < 10) return CellState::Free;
  return CellState::Unknown;
}

// The scene's bounding box in x-y: x [-0.5, 2.0), y [-0.3, 1.5): 25 x 18 leaf columns.
constexpr int kX0 = -5, kY0 = -3, kWidth = 25, kHeight = 18;

char letter(CellState s) {
  return s == CellState::Occupied ? '#' : s == CellState::Free ? '.' : '?';
}

/// The map as text, top row first, for readable failure messages.
std::string picture(const OccupancyMap& m) {
  std::string s;
  for (int iy = m.height() - 1; iy >= 0; --iy) {
    for (int ix = 0; ix < m.width(); ++ix) s += letter(m.at(ix, iy));
    s += '\n';
  }
  return s;
}

class OctomapIo : public ::testing::Test {
 protected:
  void SetUp() override {
    octomap::OcTree tree(kRes);
    build_scene(tree);
    bt_ = dir_.file("scene.bt");
    ot_ = dir_.file("scene.ot");
    ASSERT_TRUE(tree.writeBinary(bt_));
    ASSERT_TRUE(tree.write(ot_));
  }

  /// Expects the default-band map of the scene at the tree's resolution.
  static void expect_scene(const OccupancyMap& m) {
    EXPECT_DOUBLE_EQ(m.geometry.resolution, kRes);
    EXPECT_NEAR(m.geometry.origin.x(), kX0 * kRes, 1e-9);
    EXPECT_NEAR(m.geometry.origin.y(), kY0 * kRes, 1e-9);
    EXPECT_EQ(m.geometry.yaw, 0.0);
    ASSERT_EQ(m.width(), kWidth);
    ASSERT_EQ(m.height(), kHeight);
    int wrong = 0;
    for (int iy = 0; iy < kHeight; ++iy) {
      for (int ix = 0; ix < kWidth; ++ix) {
        const CellState want = expected_scene(ix + kX0, iy + kY0);
        if (m.at(ix, iy) != want) ++wrong;
        EXPECT_EQ(letter(m.at(ix, iy)), letter(want)) << "cell " << ix << "," << iy;
      }
    }
    EXPECT_EQ(wrong, 0) << picture(m);
  }

  TempDir dir_;
  std::string bt_, ot_;
};

TEST_F(OctomapIo, BinaryTreeGivesTheExpectedCells) {
  expect_scene(load_octomap(bt_));
}

TEST_F(OctomapIo, FullTreeGivesTheSameCells) {
  const OccupancyMap bt = load_octomap(bt_);
  const OccupancyMap ot = load_octomap(ot_);
  expect_scene(ot);
  EXPECT_EQ(ot.cells, bt.cells);
}

TEST_F(OctomapIo, TheWallTheTableAndTheFloorByName) {
  const OccupancyMap m = load_octomap(bt_);
  const auto at = [&](double x, double y) {
    const Cell c = m.geometry.cell_of(x - m.geometry.origin.x(), y - m.geometry.origin.y());
    return m.at(c.ix, c.iy);
  };
  EXPECT_EQ(at(1.05, 0.55), CellState::Occupied);  // the wall
  EXPECT_EQ(at(0.35, 0.35), CellState::Free);      // under the table top: free, not occupied
  EXPECT_EQ(at(0.35, 1.15), CellState::Unknown);   // table top over nothing: absent
  EXPECT_EQ(at(0.35, 1.35), CellState::Unknown);   // floor only: absent
  EXPECT_EQ(at(1.35, 0.75), CellState::Unknown);   // free above the band only
  EXPECT_EQ(at(1.35, 0.15), CellState::Unknown);   // free touching the band's face only
  EXPECT_EQ(at(1.95, 0.05), CellState::Occupied);  // the cube's far corner
}

TEST_F(OctomapIo, PrunedLeafCoversAllItsCells) {
  // The cube is a single 0.4 m leaf in the tree ...
  octomap::OcTree tree(kRes);
  ASSERT_TRUE(tree.readBinary(bt_));
  int big = 0;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (std::abs(it.getSize() - 0.4) < 1e-6 && std::abs(it.getX() - 1.8) < 1e-4 &&
        std::abs(it.getY() - 0.2) < 1e-4 && std::abs(it.getZ() - 0.2) < 1e-4) {
      EXPECT_TRUE(tree.isNodeOccupied(*it));
      ++big;
    }
  }
  ASSERT_EQ(big, 1) << "the cube did not prune into one leaf";
  // ... and its 4 x 4 cells are all occupied, exactly those.
  const OccupancyMap m = load_octomap(bt_);
  for (int x = 15; x <= 20; ++x) {
    for (int y = -1; y <= 4; ++y) {
      if (!m.geometry.contains(x - kX0, y - kY0)) continue;
      const bool inside = x >= 16 && x < 20 && y >= 0 && y < 4;
      EXPECT_EQ(m.at(x - kX0, y - kY0) == CellState::Occupied, inside) << x << "," << y;
    }
  }
}

TEST_F(OctomapIo, CoarserCellsTakeTheStrongestVoxelUnderThem) {
  OctomapSlice s;
  s.resolution = 0.2;
  const OccupancyMap fine = load_octomap(bt_);
  const OccupancyMap m = load_octomap(bt_, s);
  EXPECT_DOUBLE_EQ(m.geometry.resolution, 0.2);
  EXPECT_NEAR(m.geometry.origin.x(), -0.5, 1e-9);
  EXPECT_NEAR(m.geometry.origin.y(), -0.3, 1e-9);
  ASSERT_EQ(m.width(), 13);  // ceil(2.5 / 0.2)
  ASSERT_EQ(m.height(), 9);  // 1.8 / 0.2
  for (int iy = 0; iy < m.height(); ++iy) {
    for (int ix = 0; ix < m.width(); ++ix) {
      CellState want = CellState::Unknown;
      for (int dy = 0; dy < 2; ++dy) {
        for (int dx = 0; dx < 2; ++dx) {
          if (!fine.geometry.contains(2 * ix + dx, 2 * iy + dy)) continue;
          const CellState f = fine.at(2 * ix + dx, 2 * iy + dy);
          if (f == CellState::Occupied) want = f;
          if (f == CellState::Free && want == CellState::Unknown) want = f;
        }
      }
      EXPECT_EQ(letter(m.at(ix, iy)), letter(want)) << "cell " << ix << "," << iy;
    }
  }
}

TEST_F(OctomapIo, FinerCellsSplitTheVoxels) {
  OctomapSlice s;
  s.resolution = 0.05;
  const OccupancyMap fine = load_octomap(bt_);
  const OccupancyMap m = load_octomap(bt_, s);
  ASSERT_EQ(m.width(), 2 * kWidth);
  ASSERT_EQ(m.height(), 2 * kHeight);
  for (int iy = 0; iy < m.height(); ++iy) {
    for (int ix = 0; ix < m.width(); ++ix) {
      EXPECT_EQ(letter(m.at(ix, iy)), letter(fine.at(ix / 2, iy / 2))) << ix << "," << iy;
    }
  }
}

TEST_F(OctomapIo, TheBandDecidesWhatIsSeen) {
  // At table height the table tops and the wall are seen, the cube (below 0.4 m) is not.
  OctomapSlice table;
  table.z_min = 0.85;
  table.z_max = 0.95;
  const OccupancyMap t = load_octomap(bt_, table);
  EXPECT_EQ(t.at(3 - kX0, 3 - kY0), CellState::Occupied);
  EXPECT_EQ(t.at(3 - kX0, 12 - kY0), CellState::Occupied);
  EXPECT_EQ(t.at(10 - kX0, 0 - kY0), CellState::Occupied);
  EXPECT_EQ(t.at(17 - kX0, 1 - kY0), CellState::Unknown);
  EXPECT_EQ(t.at(0 - kX0, 0 - kY0), CellState::Unknown);  // no free voxel that high
  // A band reaching below z = 0 sees the floor.
  OctomapSlice floor;
  floor.z_min = -0.2;
  floor.z_max = 0.05;
  const OccupancyMap f = load_octomap(bt_, floor);
  EXPECT_EQ(f.at(0 - kX0, 13 - kY0), CellState::Occupied);
  EXPECT_EQ(f.at(13 - kX0, 1 - kY0), CellState::Free);  // the free voxels below 0.1 m
  // The geometry is the tree's, whatever the band.
  EXPECT_EQ(f.geometry.origin, t.geometry.origin);
  EXPECT_EQ(f.width(), kWidth);
  EXPECT_EQ(f.height(), kHeight);
}

TEST_F(OctomapIo, ExtensionIsCaseInsensitive) {
  EXPECT_TRUE(is_octomap_path("a/b/map.BT"));
  EXPECT_TRUE(is_octomap_path("map.ot"));
  EXPECT_FALSE(is_octomap_path("map.yaml"));
  EXPECT_FALSE(is_octomap_path("bt"));
  const std::string upper = dir_.file("SCENE.BT");
  std::filesystem::copy_file(bt_, upper);
  EXPECT_EQ(load_octomap(upper).cells, load_octomap(bt_).cells);
}

TEST_F(OctomapIo, ErrorsNameTheFileAndTheFault) {
  const std::string missing = dir_.file("missing.bt");
  expect_error([&] { load_octomap(missing); }, {missing, "not found"});

  const std::string folder = dir_.file("folder.bt");
  std::filesystem::create_directory(folder);
  expect_error([&] { load_octomap(folder); }, {folder, "is a directory"});

  const std::string yaml = dir_.write("map.yaml", "image: x.pgm\n");
  expect_error([&] { load_octomap(yaml); }, {yaml, ".bt", ".ot", "'.yaml'"});

  const std::string garbage = dir_.write("garbage.bt", "hello\n");
  expect_error([&] { load_octomap(garbage); }, {garbage, "not an OctoMap binary (.bt) file"});
  const std::string garbage_ot = dir_.write("garbage.ot", "hello\n");
  expect_error([&] { load_octomap(garbage_ot); }, {garbage_ot, "not an OctoMap full (.ot) file"});

  // A full tree saved as .bt has the wrong first line.
  const std::string swapped = dir_.file("swapped.bt");
  std::filesystem::copy_file(ot_, swapped);
  expect_error([&] { load_octomap(swapped); }, {swapped, "not an OctoMap binary"});

  octomap::ColorOcTree color(kRes);
  color.updateNode(octomap::point3d(0.05f, 0.05f, 0.35f), true);
  const std::string color_ot = dir_.file("color.ot");
  ASSERT_TRUE(color.write(color_ot));
  expect_error([&] { load_octomap(color_ot); }, {color_ot, "ColorOcTree", "not an OcTree"});

  octomap::OcTree empty(kRes);
  const std::string empty_bt = dir_.file("empty.bt");
  ASSERT_TRUE(empty.writeBinary(empty_bt));
  expect_error([&] { load_octomap(empty_bt); }, {empty_bt, "empty"});
  const std::string empty_ot = dir_.file("empty.ot");
  ASSERT_TRUE(empty.write(empty_ot));
  expect_error([&] { load_octomap(empty_ot); }, {empty_ot, "empty"});

  OctomapSlice s;
  s.z_min = 0.6;
  s.z_max = 0.6;
  expect_error([&] { load_octomap(bt_, s); }, {bt_, "z_min (0.6 m) must be below z_max (0.6 m)"});
  s.z_min = 0.7;
  expect_error([&] { load_octomap(bt_, s); }, {bt_, "z_min (0.7 m)"});
  s = {};
  s.z_max = std::numeric_limits<double>::quiet_NaN();
  expect_error([&] { load_octomap(bt_, s); }, {bt_, "z_max nan"});
  s = {};
  s.z_min = std::numeric_limits<double>::quiet_NaN();
  expect_error([&] { load_octomap(bt_, s); }, {bt_, "z_min nan"});
  s = {};
  s.resolution = -0.1;
  expect_error([&] { load_octomap(bt_, s); }, {bt_, "resolution", "-0.1"});
  s.resolution = std::numeric_limits<double>::quiet_NaN();
  expect_error([&] { load_octomap(bt_, s); }, {bt_, "resolution", "nan"});
  s = {};
  s.z_min = 5.0;
  s.z_max = 6.0;
  expect_error([&] { load_octomap(bt_, s); },
               {bt_, "no known voxel overlaps the band z in [5, 6] m", "span z in [-0.1, 1] m"});
  s = {};
  s.resolution = 1e-4;
  expect_error([&] { load_octomap(bt_, s); }, {bt_, "2-D map at 0.0001 m", "cells", "--max-cells"});
}

TEST_F(OctomapIo, TruncatedBinaryTreeIsAnError) {
  std::ifstream in(bt_, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string whole = ss.str();
  const std::string cut = dir_.write("cut.bt", whole.substr(0, whole.size() / 2));
  // (octomap itself would print "ERROR: Tree size mismatch ..." to stderr; the loader checks
  // the data first, so octomap never reads it: see test_octomap_check.cpp.)
  expect_error([&] { load_octomap(cut); }, {cut, "truncated"});
}

#ifdef GRIDLOC_CLI_PATH

using test::CliRun;
using test::quote;
using test::run_cli;

/// Turns a 2-D map into an OctoMap at its resolution: occupied cells become a 1 m high
/// wall, free cells free voxels in the default band over an occupied floor, unknown cells
/// nothing.
octomap::OcTree extrude(const OccupancyMap& map) {
  const double r = map.geometry.resolution;
  octomap::OcTree tree(r);
  const int band_lo = static_cast<int>(std::lround(0.1 / r));
  const int band_hi = static_cast<int>(std::lround(0.6 / r));
  const int top = static_cast<int>(std::lround(1.0 / r));
  for (int iy = 0; iy < map.height(); ++iy) {
    for (int ix = 0; ix < map.width(); ++ix) {
      const Eigen::Vector2d c = map.geometry.cell_center(ix, iy) + map.geometry.origin;
      const int x = static_cast<int>(std::floor(c.x() / r));
      const int y = static_cast<int>(std::floor(c.y() / r));
      if (map.at(ix, iy) == CellState::Occupied) {
        fill(tree, x, x + 1, y, y + 1, 0, top, true);
      } else if (map.at(ix, iy) == CellState::Free) {
        fill(tree, x, x + 1, y, y + 1, band_lo, band_hi, false);
        fill(tree, x, x + 1, y, y + 1, -1, 0, true);
      }
    }
  }
  return tree;
}

TEST(OctomapCli, LocalizeRunsOnABinaryTree) {
  TempDir dir;
  const OccupancyMap flat = load_ros_map(test::map_path("room_rect"));
  ASSERT_EQ(flat.geometry.yaw, 0.0);
  octomap::OcTree tree = extrude(flat);
  const std::string bt = dir.file("room.bt");
  ASSERT_TRUE(tree.writeBinary(bt));

  // The slice gives back the 2-D map, cell for cell, within the tree's box.
  const OccupancyMap sliced = load_octomap(bt);
  EXPECT_DOUBLE_EQ(sliced.geometry.resolution, flat.geometry.resolution);
  int known = 0, flat_known = 0;
  for (int iy = 0; iy < sliced.height(); ++iy) {
    for (int ix = 0; ix < sliced.width(); ++ix) {
      const Eigen::Vector2d c = sliced.geometry.cell_center(ix, iy) + sliced.geometry.origin;
      const Cell f =
          flat.geometry.cell_of(c.x() - flat.geometry.origin.x(), c.y() - flat.geometry.origin.y());
      ASSERT_TRUE(flat.geometry.contains(f.ix, f.iy)) << ix << "," << iy;
      ASSERT_EQ(letter(sliced.at(ix, iy)), letter(flat.at(f.ix, f.iy))) << ix << "," << iy;
      known += sliced.at(ix, iy) != CellState::Unknown;
    }
  }
  for (CellState s : flat.cells) flat_known += s != CellState::Unknown;
  EXPECT_EQ(known, flat_known);

  // Readings simulated on the sliced map, localized by the tool on the tree.
  const Pose2 truth{2.0, 1.5, 0.5};
  const auto ranges = simulate_sonar(sliced, load_sonar_ring(test::ring_path()), truth);
  const std::string readings =
      dir.write("r.json", nlohmann::json{{"ranges_m", ranges}}.dump() + "\n");
  const std::string args = "localize --map " + quote(bt) + " --readings " + quote(readings) +
                           " --prior 2.4,1.2,0.1 --octomap-z-min 0.1 --octomap-z-max 0.6";
  const CliRun run = run_cli(dir, args);
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(run.err, "");  // octomap's progress notes do not reach the console
  const std::string& out = run.out;
  const auto j = nlohmann::json::parse(out);
  const double dx = j["pose"]["x"].get<double>() - truth.x;
  const double dy = j["pose"]["y"].get<double>() - truth.y;
  const double dtheta = normalize_angle(j["pose"]["theta"].get<double>() - truth.theta);
  EXPECT_LT(std::hypot(dx, dy), 0.10) << out;
  EXPECT_LT(std::abs(rad2deg(dtheta)), 7.0) << out;

  // A bad band is the tool's one-line error, exit code 2, with no console output of octomap.
  const std::string bad = "localize --map " + quote(bt) + " --readings " + quote(readings) +
                          " --prior 2.4,1.2,0.1 --octomap-z-min 0.7 --octomap-z-max 0.2";
  test::expect_cli_error(run_cli(dir, bad), "z_min (0.7 m) must be below z_max (0.2 m)");
  const std::string garbage = dir.write("garbage.bt", "hello\n");
  const CliRun g = run_cli(dir, "simulate --pose 1,1,0 --map " + quote(garbage));
  EXPECT_EQ(g.status, 2);
  EXPECT_EQ(std::count(g.err.begin(), g.err.end(), '\n'), 1) << g.err;
}

// `--map -` reads a tree from standard input, a .bt told from a .ot by its first line (there
// is no name to tell them by): the same readings as from the tree's file.
TEST(OctomapCli, TreesFromStandardInput) {
  TempDir dir;
  octomap::OcTree tree = extrude(load_ros_map(test::map_path("room_rect")));
  const std::string ot = dir.file("room.ot"), bt = dir.file("room.bt");
  ASSERT_TRUE(tree.write(ot));  // before writeBinary, which prunes
  ASSERT_TRUE(tree.writeBinary(bt));
  for (const std::string& file : {bt, ot}) {
    const std::string simulate = "simulate --pose 2,1.5,0.5 --map ";
    const CliRun from_file = run_cli(dir, simulate + quote(file));
    ASSERT_EQ(from_file.status, 0) << from_file.err;
    const CliRun piped = run_cli(dir, simulate + "- < " + quote(file));
    ASSERT_EQ(piped.status, 0) << file << ": " << piped.err;
    EXPECT_EQ(piped.out, from_file.out) << file;
  }
}

#endif  // GRIDLOC_CLI_PATH

}  // namespace
}  // namespace gridloc
