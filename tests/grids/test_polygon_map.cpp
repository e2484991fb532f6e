// Tests of grids/src/polygon_map.cpp: the polygon map format, its checks and rasterization.
#include "gridloc/grids/polygon_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

#include "test_support.hpp"

namespace gridloc {
namespace {

Polygon rect(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

CellState state_at(const OccupancyMap& m, double x, double y) {
  const Cell c = m.geometry.cell_of(x - m.geometry.origin.x(), y - m.geometry.origin.y());
  return m.at(c.ix, c.iy);
}

TEST(PolygonMap, ReadsOrientsAndRasterizes) {
  test::TempDir dir;
  // A clockwise boundary and a counter-clockwise obstacle: stored the other way round.
  const std::string path = dir.write("room.yaml",
                                     "# a 4 x 3 m room with a box\n"
                                     "resolution: 0.1\n"
                                     "boundary: [[0, 0], [0, 3], [4, 3], [4, 0], [0, 0]]\n"
                                     "obstacles:\n"
                                     "  - [[1, 1], [2, 1], [2, 2], [1, 2], [1, 1]]\n");
  EXPECT_TRUE(is_polygon_map_file(path));
  const PolygonMap m = load_polygon_map(path);
  ASSERT_EQ(m.boundary.size(), 4u);
  ASSERT_EQ(m.obstacles.size(), 1u);
  EXPECT_GT(signed_area2(m.boundary), 0.0);
  EXPECT_LT(signed_area2(m.obstacles[0]), 0.0);
  EXPECT_EQ(m.resolution, 0.1);
  EXPECT_EQ(polygon_edges(m).size(), 8u);

  const OccupancyMap g = rasterize_polygon_map(m);
  EXPECT_EQ(g.geometry.resolution, 0.1);
  EXPECT_EQ(state_at(g, 3.0, 2.5), CellState::Free);
  EXPECT_EQ(state_at(g, 1.5, 1.5), CellState::Occupied);   // inside the box
  EXPECT_EQ(state_at(g, 0.02, 1.5), CellState::Occupied);  // on the west wall
  EXPECT_EQ(state_at(g, 2.0, 3.02), CellState::Occupied);  // on the north wall
  EXPECT_EQ(state_at(g, -0.3, 1.5), CellState::Unknown);   // outside
  // Every free cell's 4 neighbours are free or occupied: the walls close the room.
  for (int y = 1; y + 1 < g.height(); ++y) {
    for (int x = 1; x + 1 < g.width(); ++x) {
      if (g.at(x, y) != CellState::Free) continue;
      for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        EXPECT_NE(g.at(x + dx, y + dy), CellState::Unknown) << x << "," << y;
      }
    }
  }
}

TEST(PolygonMap, BadRingsAreNamed) {
  test::TempDir dir;
  const auto load = [&](const std::string& text) {
    return [&dir, text] { load_polygon_map(dir.write("p.yaml", text)); };
  };
  test::expect_error(load("boundary: [[0, 0], [4, 0], [4, 3], [0, 3]]\n"),
                     {"boundary", "not closed", "(0, 0)"});
  test::expect_error(load("boundary: [[0, 0], [4, 3], [4, 0], [0, 3], [0, 0]]\n"),
                     {"boundary", "not simple", "cross"});
  test::expect_error(load("boundary: [[0, 0], [4, 0], [0, 0]]\n"), {"boundary", "at least 3"});
  test::expect_error(load("boundary: [[0, 0], [4, 0], [8, 0], [0, 0]]\n"), {"boundary"});
  test::expect_error(load("boundary: [[0, 0], [4, 0], [4, 3], [0, x], [0, 0]]\n"),
                     {"boundary vertex 3", "two numbers"});
  test::expect_error(load("boundary: [[0, 0], [4, 0], [4, 3], [0, 3], [0, 0]]\n"
                          "obstacles:\n  - [[3, 1], [5, 1], [5, 2], [3, 2], [3, 1]]\n"),
                     {"obstacle 0", "not strictly inside"});
  test::expect_error(load("boundary: [[0, 0], [4, 0], [4, 3], [0, 3], [0, 0]]\n"
                          "obstacles:\n  - [[1, 1], [2, 1], [2, 2], [1, 2], [1, 1]]\n"
                          "  - [[1.5, 1.5], [2.5, 1.5], [2.5, 2.5], [1.5, 2.5], [1.5, 1.5]]\n"),
                     {"obstacle 1", "overlaps obstacle 0"});
  test::expect_error(load("resolution: 0\nboundary: [[0, 0], [4, 0], [4, 3], [0, 0]]\n"),
                     {"resolution"});
  test::expect_error(load("image: map.pgm\nresolution: 0.05\n"), {"no 'boundary' key"});
  test::expect_error([&] { load_polygon_map(dir.file("none.yaml")); }, {"not found"});
  EXPECT_FALSE(is_polygon_map_file(test::map_path("room_l")));  // a map_server map
  test::expect_error([] { make_polygon_map(rect(0, 0, 4, 3), {rect(0, 1, 1, 2)}); },
                     {"obstacle 0"});
}

// Fuzz regression (issue 14 item 3): a valid map 1e12 m wide overflowed the int cast of its
// cell count before the size check (UB; then "cannot create std::vector larger than
// max_size()"). It must get the size check's error.
TEST(PolygonMap, HugeMapIsRefusedBeforeItsCellCountOverflows) {
  test::TempDir dir;
  const std::string path =
      dir.write("p.yaml", "boundary: [[0, 0], [1e12, 0], [0, 1e12], [0, 0]]\n");
  test::expect_error([&] { load_polygon_map(path); }, {"--max-coordinate-m"});
  ResourceLimits wide;
  wide.max_coordinate_m = 1e13;
  const PolygonMap m = load_polygon_map(path, wide);
  test::expect_error([&] { rasterize_polygon_map(m, 0.0, 0.5, wide); },
                     {"2e+13 x 2e+13", "--max-cells"});
}

TEST(PolygonMap, BundledPolygonMapsLoad) {
  for (const char* name : {"room_rect", "room_l", "room_furnished", "office"}) {
    const PolygonMap m = load_polygon_map(test::maps_dir() + "/polygons/" + name + ".yaml");
    const OccupancyMap g = rasterize_polygon_map(m);
    int free = 0;
    for (const CellState c : g.cells) free += c == CellState::Free ? 1 : 0;
    EXPECT_GT(free, 5000) << name;
  }
}

// ---- limits (issue 14) --------------------------------------------------------------------

/// A polygon with n vertices on a circle of radius 10 m about (10, 10).
Polygon circle(int n) {
  Polygon p;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * 3.141592653589793 * i / n;
    p.emplace_back(10.0 + 10.0 * std::cos(a), 10.0 + 10.0 * std::sin(a));
  }
  return p;
}

TEST(PolygonMapLimits, VerticesAreCountedBeforeTheChecks) {
  ResourceLimits limits;
  limits.max_vertices = 20;
  EXPECT_EQ(make_polygon_map(circle(12), {rect(8, 8, 9, 9)}, 0.05, limits).boundary.size(), 12u);
  test::expect_error([&] { make_polygon_map(circle(18), {rect(8, 8, 9, 9)}, 0.05, limits); },
                     {"22 vertices", "--max-vertices"});
  test::TempDir dir;
  std::ostringstream text;
  text << std::setprecision(17) << "boundary: [";
  for (const auto& v : circle(30)) text << "[" << v.x() << ", " << v.y() << "], ";
  text << "[20, 10]]\n";
  const std::string p = dir.write("p.yaml", text.str());
  test::expect_error([&] { load_polygon_map(p, limits); }, {p, "30 vertices", "--max-vertices"});
}

TEST(PolygonMapLimits, CoordinatesBeyondTheLimitAreRefused) {
  test::expect_error([&] { make_polygon_map(rect(0, 0, 1e12, 1e12), {}); },
                     {"boundary vertex 1", "--max-coordinate-m"});
  test::expect_error([&] { make_polygon_map(rect(0, 0, 10, 10), {rect(1, 1, 2, 2e7)}); },
                     {"obstacle 0", "--max-coordinate-m"});
}

TEST(PolygonMapLimits, RasterSizeIsCheckedBeforeTheCast) {
  ResourceLimits wide;
  wide.max_coordinate_m = 1e13;
  const PolygonMap huge = make_polygon_map(rect(0, 0, 1e12, 1e12), {}, 0.05, wide);
  test::expect_error([&] { rasterize_polygon_map(huge, 0.0, 0.5, wide); },
                     {"rasterized", "--max-cells"});
  wide.max_cells = 1e30;  // past the cell limit: the int range still holds
  test::expect_error([&] { rasterize_polygon_map(huge, 0.0, 0.5, wide); }, {"too long"});
}

TEST(PolygonMapLimits, ScanlineRasterMatchesThePointTest) {
  // Every cell that is not a wall cell holds what inside() says of its centre.
  const PolygonMap m =
      make_polygon_map(circle(40), {rect(6, 6, 9, 8), {{12, 12}, {15, 12.5}, {13, 15}}}, 0.05);
  for (double res : {0.013, 0.05, 0.3}) {
    const OccupancyMap r = rasterize_polygon_map(m, res);
    for (int iy = 0; iy < r.height(); ++iy) {
      for (int ix = 0; ix < r.width(); ++ix) {
        const Eigen::Vector2d c = r.geometry.origin + r.geometry.cell_center(ix, iy);
        bool in_obstacle = false;
        for (const auto& o : m.obstacles) in_obstacle = in_obstacle || inside(o, c);
        const CellState want = !inside(m.boundary, c) ? CellState::Unknown
                               : in_obstacle          ? CellState::Occupied
                                                      : CellState::Free;
        if (r.at(ix, iy) != CellState::Occupied) {
          ASSERT_EQ(r.at(ix, iy), want) << "cell " << ix << ", " << iy << " at " << res;
        }
      }
    }
  }
}

TEST(PolygonMapWriter, RoundTripsRingsResolutionAndComment) {
  test::TempDir dir;
  // Coordinates that only 17 digits keep, an obstacle, a two-line comment.
  const PolygonMap map =
      make_polygon_map(rect(0.1, -0.2, 4.0 / 3.0, 3.0), {rect(0.5, 0.5, 1.0, 1.0 + 1e-9)}, 0.07);
  const std::string path = dir.file("saved.yaml");
  save_polygon_map(map, path, "first line\nsecond line");
  EXPECT_TRUE(is_polygon_map_file(path));
  const PolygonMap back = load_polygon_map(path);
  EXPECT_EQ(back.boundary, map.boundary);
  EXPECT_EQ(back.obstacles, map.obstacles);
  EXPECT_EQ(back.resolution, map.resolution);
  std::ifstream in(path);
  std::string first, second, third;
  std::getline(in, first);
  std::getline(in, second);
  std::getline(in, third);
  EXPECT_EQ(first.rfind("# gridloc polygon map", 0), 0u);
  EXPECT_EQ(second, "# first line");
  EXPECT_EQ(third, "# second line");
}

TEST(PolygonMapWriter, WithoutObstaclesAndErrors) {
  test::TempDir dir;
  const PolygonMap map = make_polygon_map(rect(0, 0, 2, 1), {});
  const std::string path = dir.file("plain.yaml");
  save_polygon_map(map, path);
  const PolygonMap back = load_polygon_map(path);
  EXPECT_EQ(back.boundary, map.boundary);
  EXPECT_TRUE(back.obstacles.empty());
  const std::string missing = dir.file("no_such_folder/map.yaml");
  test::expect_error([&] { save_polygon_map(map, missing); }, {missing, "cannot open"});
  test::expect_error([&] { save_polygon_map(PolygonMap{}, path); }, {path, "boundary is empty"});
}

TEST(PolygonMapLimits, FileSizeIsBoundedByTheVertexLimit) {
  // YAML parsing takes ~65 bytes of memory per byte: the file is checked before it is parsed.
  test::TempDir dir;
  ResourceLimits limits;
  limits.max_vertices = 10;
  const std::string small = "boundary: [[0, 0], [4, 0], [4, 3], [0, 3], [0, 0]]\n";
  const std::string p = dir.write("p.yaml", small + std::string(2 << 20, '#'));
  test::expect_error([&] { load_polygon_map(p, limits); }, {p, "bytes", "--max-vertices"});
  EXPECT_TRUE(is_polygon_map_file(p, limits));  // larger than any map_server YAML
  EXPECT_EQ(load_polygon_map(dir.write("q.yaml", small), limits).boundary.size(), 4u);
}

TEST(PolygonMapLimits, DirectoryIsNamed) {
  test::TempDir dir;
  std::filesystem::create_directory(dir.file("p.yaml"));
  test::expect_error([&] { load_polygon_map(dir.file("p.yaml")); }, {"p.yaml", "is a directory"});
  EXPECT_FALSE(is_polygon_map_file(dir.file("p.yaml")));
}

}  // namespace
}  // namespace gridloc
