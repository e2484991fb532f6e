// Tests of grids/src/polygon_map.cpp: the polygon map format, its checks and rasterization.
#include "gridloc/grids/polygon_map.hpp"

#include <gtest/gtest.h>

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

TEST(PolygonMap, BundledPolygonMapsLoad) {
  for (const char* name : {"room_rect", "room_l", "room_furnished", "office"}) {
    const PolygonMap m = load_polygon_map(test::maps_dir() + "/polygons/" + name + ".yaml");
    const OccupancyMap g = rasterize_polygon_map(m);
    int free = 0;
    for (const CellState c : g.cells) free += c == CellState::Free ? 1 : 0;
    EXPECT_GT(free, 5000) << name;
  }
}

}  // namespace
}  // namespace gridloc
