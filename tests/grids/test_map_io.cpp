// Tests of grids/src/map_io.cpp: ROS map_server YAML + image loading and saving.
#include "gridloc/grids/map_io.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <string>
#include <vector>

#include "map_io_cases.hpp"
#include "png_bytes.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using namespace map_io_test;

TEST(MapIo, ImageRowZeroIsTheTopRowOfTheGrid) {
  TempDir dir;
  // 4 x 3 image, free except a black pixel at image (row 0, col 1) and a grey one at
  // image (row 2, col 3).
  std::vector<std::uint8_t> px(12, 254);
  px[0 * 4 + 1] = 0;
  px[2 * 4 + 3] = 205;
  dir.write("m.pgm", pgm(4, 3, px));
  const OccupancyMap m = load_ros_map(dir.write("m.yaml", yaml("m.pgm")));
  ASSERT_EQ(m.width(), 4);
  ASSERT_EQ(m.height(), 3);
  EXPECT_EQ(m.geometry.resolution, 0.5);
  for (int iy = 0; iy < 3; ++iy) {
    for (int ix = 0; ix < 4; ++ix) {
      const CellState want = (ix == 1 && iy == 2) ? O : (ix == 3 && iy == 0) ? U : F;
      EXPECT_EQ(m.at(ix, iy), want) << "cell (" << ix << ", " << iy << ")";
    }
  }
}

// The YAML as text: the file's map, its image found in the folder given; errors name the
// text by the name given; a text over the map_server YAML bound is refused.
TEST(MapIo, TextOfAYamlLoadsAsItsFile) {
  TempDir dir;
  std::vector<std::uint8_t> px(12, 254);
  px[5] = 0;
  dir.write("m.pgm", pgm(4, 3, px));
  const OccupancyMap from_file = load_ros_map(dir.write("m.yaml", yaml("m.pgm")));
  const OccupancyMap from_text = load_ros_map_text(yaml("m.pgm"), "piped", dir.path().string());
  EXPECT_EQ(from_text.cells, from_file.cells);
  EXPECT_EQ(from_text.width(), from_file.width());
  EXPECT_EQ(from_text.geometry.resolution, from_file.geometry.resolution);
  expect_error([&] { load_ros_map_text(yaml("m.pgm"), "piped", dir.file("elsewhere")); },
               {"piped", "m.pgm", "not found"});
  expect_error([&] { load_ros_map_text(yaml("m.pgm", "mode: fancy\n"), "piped", "."); },
               {"piped", "mode"});
  expect_error(
      [&] {
        load_ros_map_text(yaml("m.pgm") + "#" + std::string(kMaxMapYamlBytes, ' ') + "\n", "piped",
                          dir.path().string());
      },
      {"piped", "too large"});
}

TEST(MapIo, OffsetOriginPlacesCellCentres) {
  TempDir dir;
  std::vector<std::uint8_t> px(12, 254);
  px[0 * 4 + 1] = 0;  // -> cell (1, 2)
  dir.write("m.pgm", pgm(4, 3, px));
  const OccupancyMap m =
      load_ros_map(dir.write("m.yaml", yaml("m.pgm", "", "0.25", "[1.5, -2.0, 0.0]")));
  const GridGeometry& g = m.geometry;
  EXPECT_EQ(g.origin.x(), 1.5);
  EXPECT_EQ(g.origin.y(), -2.0);
  EXPECT_EQ(g.yaw, 0.0);
  const Eigen::Vector2d c = g.cell_center(1, 2);
  const Pose2 w = g.to_world_frame({c.x(), c.y(), 0.0});
  EXPECT_NEAR(w.x, 1.5 + 1.5 * 0.25, 1e-12);
  EXPECT_NEAR(w.y, -2.0 + 2.5 * 0.25, 1e-12);
  // And back: the world point lands in the occupied cell.
  const Pose2 back = g.to_grid_frame({1.5 + 0.3, -2.0 + 0.6, 0.0});
  const Cell cell = g.cell_of(back.x, back.y);
  EXPECT_EQ(cell, (Cell{1, 2}));
  EXPECT_EQ(m.at(cell.ix, cell.iy), O);
}

TEST(MapIo, YawedOriginRotatesTheGridAboutItsCorner) {
  TempDir dir;
  std::vector<std::uint8_t> px(12, 254);
  px[0 * 4 + 1] = 0;  // -> cell (1, 2)
  dir.write("m.pgm", pgm(4, 3, px));
  const OccupancyMap m =
      load_ros_map(dir.write("m.yaml", yaml("m.pgm", "", "0.5", "[1.0, 2.0, 1.5707963267948966]")));
  const GridGeometry& g = m.geometry;
  EXPECT_NEAR(g.yaw, std::numbers::pi / 2, 1e-15);
  // Cell (1, 2) has its centre at (0.75, 1.25) in the grid frame; a +90 deg yaw sends grid
  // +x to world +y and grid +y to world -x.
  const Eigen::Vector2d c = g.cell_center(1, 2);
  EXPECT_NEAR(c.x(), 0.75, 1e-12);
  EXPECT_NEAR(c.y(), 1.25, 1e-12);
  const Pose2 w = g.to_world_frame({c.x(), c.y(), 0.0});
  EXPECT_NEAR(w.x, 1.0 - 1.25, 1e-12);
  EXPECT_NEAR(w.y, 2.0 + 0.75, 1e-12);
  EXPECT_NEAR(w.theta, std::numbers::pi / 2, 1e-12);
  const Pose2 gp = g.to_grid_frame({-0.25, 2.75, 0.0});
  EXPECT_EQ(g.cell_of(gp.x, gp.y), (Cell{1, 2}));
  EXPECT_NEAR(gp.theta, -std::numbers::pi / 2, 1e-12);

  // Round trips for a few poses, both ways.
  for (const Pose2 p : {Pose2{0.3, -1.7, 0.4}, Pose2{-4.0, 2.5, -3.0}, Pose2{1.0, 2.0, 3.1}}) {
    const Pose2 q = g.to_world_frame(g.to_grid_frame(p));
    EXPECT_NEAR(q.x, p.x, 1e-12);
    EXPECT_NEAR(q.y, p.y, 1e-12);
    EXPECT_NEAR(normalize_angle(q.theta - p.theta), 0.0, 1e-12);
    const Pose2 r = g.to_grid_frame(g.to_world_frame(p));
    EXPECT_NEAR(r.x, p.x, 1e-12);
    EXPECT_NEAR(r.y, p.y, 1e-12);
    EXPECT_NEAR(normalize_angle(r.theta - p.theta), 0.0, 1e-12);
  }
}

TEST(MapIo, TrinaryThresholdsFollowMapServer) {
  TempDir dir;
  // occupancy p = (255 - v) / 255; defaults occupied p > 0.65, free p < 0.196.
  // v = 89 -> 0.651 occupied; 90 -> 0.647 unknown; 205 -> 0.196 unknown; 206 -> 0.192 free.
  const OccupancyMap m = load_row(dir, {0, 89, 90, 205, 206, 254, 255}, "");
  EXPECT_EQ(row_states(m), (std::vector<CellState>{O, O, U, U, F, F, F}));
}

TEST(MapIo, CustomThresholds) {
  TempDir dir;
  // occupied p > 0.5 (v <= 127), free p < 0.4 (v >= 154).
  const OccupancyMap m =
      load_row(dir, {127, 128, 152, 154}, "occupied_thresh: 0.5\nfree_thresh: 0.4\n");
  EXPECT_EQ(row_states(m), (std::vector<CellState>{O, U, U, F}));
}

TEST(MapIo, NegateInvertsPixels) {
  TempDir dir;
  // Negated: v -> 255 - v, so black is free, white occupied, 205 (p = 0.804) occupied,
  // and 100 (-> 155, p = 0.392) unknown.
  for (const std::string negate : {"negate: 1\n", "negate: true\n"}) {
    const OccupancyMap m = load_row(dir, {0, 254, 205, 100}, negate);
    EXPECT_EQ(row_states(m), (std::vector<CellState>{F, O, O, U})) << negate;
  }
  const OccupancyMap plain = load_row(dir, {0, 254, 205, 100}, "negate: 0\n");
  EXPECT_EQ(row_states(plain), (std::vector<CellState>{O, F, U, U}));
}

TEST(MapIo, ScaleModeEqualsTrinaryOnGreyImages) {
  TempDir dir;
  const std::vector<std::uint8_t> v = {0, 50, 89, 90, 150, 205, 206, 254};
  const OccupancyMap trinary = load_row(dir, v, "mode: trinary\n");
  const OccupancyMap scale = load_row(dir, v, "mode: scale\n");
  EXPECT_EQ(row_states(trinary), row_states(scale));
  EXPECT_EQ(row_states(scale), (std::vector<CellState>{O, O, O, U, U, U, F, F}));
}

TEST(MapIo, RawModeReadsPercent) {
  TempDir dir;
  // Raw: the pixel is the occupancy in percent; > 100 is unknown.
  const OccupancyMap m = load_row(dir, {0, 19, 20, 65, 66, 100, 101, 255}, "mode: raw\n");
  EXPECT_EQ(row_states(m), (std::vector<CellState>{F, F, U, U, O, O, U, U}));
}

TEST(MapIo, ScaleModePngAlphaMarksUnknown) {
  TempDir dir;
  // BGRA: opaque black, transparent black, opaque white, transparent white, opaque grey.
  cv::Mat img(1, 5, CV_8UC4);
  img.at<cv::Vec4b>(0, 0) = {0, 0, 0, 255};
  img.at<cv::Vec4b>(0, 1) = {0, 0, 0, 0};
  img.at<cv::Vec4b>(0, 2) = {255, 255, 255, 255};
  img.at<cv::Vec4b>(0, 3) = {255, 255, 255, 0};
  img.at<cv::Vec4b>(0, 4) = {150, 150, 150, 255};
  ASSERT_TRUE(cv::imwrite(dir.file("a.png"), img));
  const OccupancyMap m = load_ros_map(dir.write("a.yaml", yaml("a.png", "mode: scale\n")));
  EXPECT_EQ(row_states(m), (std::vector<CellState>{O, U, F, U, U}));
}

TEST(MapIo, SaveAndLoadRoundTrip) {
  TempDir dir;
  GridGeometry g;
  g.resolution = 0.05;
  g.origin = {-1.25, 3.5};
  g.width = 7;
  g.height = 5;
  OccupancyMap m(g, F);
  m.at(0, 0) = O;
  m.at(6, 4) = U;
  m.at(3, 2) = O;
  m.at(2, 4) = U;
  save_ros_map(m, dir.file("saved.yaml"));
  const OccupancyMap back = load_ros_map(dir.file("saved.yaml"));
  EXPECT_EQ(back.width(), 7);
  EXPECT_EQ(back.height(), 5);
  EXPECT_NEAR(back.geometry.resolution, 0.05, 1e-12);
  EXPECT_NEAR(back.geometry.origin.x(), -1.25, 1e-12);
  EXPECT_NEAR(back.geometry.origin.y(), 3.5, 1e-12);
  EXPECT_EQ(back.cells, m.cells);
}

/// The bytes of the file at `path`.
std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(MapIo, SavedPgmIsWhatOpenCvWroteAndLoadsBack) {
  // save_ros_map writes its PGM itself (issue 18): the header OpenCV's imwrite wrote, the
  // image rows from the top in map_server's greys, and the same cells when loaded.
  TempDir dir;
  GridGeometry g;
  g.resolution = 0.1;
  g.width = 37;
  g.height = 23;
  OccupancyMap m(g, U);
  std::mt19937 rng(18);
  for (CellState& cell : m.cells) cell = std::array{F, O, U}[rng() % 3];
  save_ros_map(m, dir.file("saved.yaml"));
  const std::string pgm_bytes = file_bytes(dir.file("saved.pgm"));
  const std::string header = "P5\n37 23\n255\n";
  ASSERT_EQ(pgm_bytes.size(), header.size() + 37 * 23);
  EXPECT_EQ(pgm_bytes.substr(0, header.size()), header);
  const cv::Mat img = cv::imread(dir.file("saved.pgm"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(img.type(), CV_8UC1);
  ASSERT_EQ(img.cols, 37);
  ASSERT_EQ(img.rows, 23);
  for (int r = 0; r < img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) {
      const CellState s = m.at(c, img.rows - 1 - r);
      const int want = s == O ? 0 : s == F ? 254 : 205;
      ASSERT_EQ(img.at<std::uint8_t>(r, c), want) << "pixel " << r << ", " << c;
    }
  }
  EXPECT_EQ(load_ros_map(dir.file("saved.yaml")).cells, m.cells);
}

TEST(MapIoErrors, UnwritableImageNamesThePgm) {
  TempDir dir;
  const OccupancyMap m = test::filled_map(3, 2, F, 0.1);
  const std::string yaml_path = dir.file("no_such_folder/m.yaml");
  expect_error([&] { save_ros_map(m, yaml_path); },
               {"no_such_folder/m.pgm", "cannot write the image"});
}

// save_ros_map writes the YAML at round-trip precision (it once wrote 6 significant digits:
// an origin of 1234.56789 came back as 1234.57 and a yaw of pi/2 as 1.5708).
TEST(MapIo, SaveKeepsFullPrecision) {
  TempDir dir;
  GridGeometry g;
  g.resolution = 0.05;
  g.origin = {1234.56789, -0.123456789};
  g.yaw = std::numbers::pi / 2;
  g.width = 3;
  g.height = 2;
  save_ros_map(OccupancyMap(g, F), dir.file("saved.yaml"));
  const OccupancyMap back = load_ros_map(dir.file("saved.yaml"));
  EXPECT_EQ(back.geometry.origin.x(), 1234.56789);
  EXPECT_EQ(back.geometry.origin.y(), -0.123456789);
  EXPECT_EQ(back.geometry.yaw, std::numbers::pi / 2);
}

TEST(MapIo, BundledRoomRect) {
  const OccupancyMap m = load_ros_map(test::map_path("room_rect"));
  EXPECT_EQ(m.width(), 146);
  EXPECT_EQ(m.height(), 116);
  EXPECT_EQ(m.geometry.resolution, 0.05);
  EXPECT_EQ(m.geometry.origin, Eigen::Vector2d(-0.5, -0.5));
  auto at_world = [&](double x, double y) {
    const Pose2 p = m.geometry.to_grid_frame({x, y, 0.0});
    const Cell c = m.geometry.cell_of(p.x, p.y);
    return m.at(c.ix, c.iy);
  };
  // Interior from x = 0.15 to 6.15 m and y = 0.15 to 4.65 m, 0.15 m walls, unknown outside.
  EXPECT_EQ(at_world(3.0, 2.0), F);
  EXPECT_EQ(at_world(0.075, 2.0), O);
  EXPECT_EQ(at_world(0.175, 2.0), F);
  EXPECT_EQ(at_world(3.0, 4.675), O);
  EXPECT_EQ(at_world(3.0, 4.625), F);
  EXPECT_EQ(at_world(-0.3, 2.0), U);
  EXPECT_EQ(at_world(1.2, 4.2), O);  // the desk
}

// ---- bad input -------------------------------------------------------------------------

TEST(MapIoErrors, MissingYamlFile) {
  TempDir dir;
  const std::string p = dir.file("nope.yaml");
  expect_error([&] { load_ros_map(p); }, {p, "not found"});
}

TEST(MapIoErrors, MissingImageFile) {
  TempDir dir;
  const std::string p = dir.write("m.yaml", yaml("missing.pgm"));
  expect_error([&] { load_ros_map(p); }, {p, "missing.pgm", "not found"});
}

TEST(MapIoErrors, UndecodableImage) {
  TempDir dir;
  dir.write("junk.pgm", "this is not an image");
  const std::string p = dir.write("m.yaml", yaml("junk.pgm"));
  expect_error([&] { load_ros_map(p); }, {"junk.pgm"});
}

TEST(MapIoErrors, MalformedYaml) {
  TempDir dir;
  const std::string p = dir.write("m.yaml", "image: m.pgm\nresolution: [0.05\norigin: {\n");
  expect_error([&] { load_ros_map(p); }, {p, "malformed YAML"});
}

TEST(MapIoErrors, NotAMapping) {
  TempDir dir;
  const std::string p = dir.write("m.yaml", "- 1\n- 2\n");
  expect_error([&] { load_ros_map(p); }, {p});
}

TEST(MapIoErrors, UnknownKey) {
  TempDir dir;
  dir.write("m.pgm", pgm(1, 1, {254}));
  const std::string p = dir.write("m.yaml", yaml("m.pgm", "resolutoin: 0.1\n"));
  expect_error([&] { load_ros_map(p); }, {p, "unknown key", "resolutoin"});
}

TEST(MapIoErrors, MissingRequiredKeys) {
  TempDir dir;
  for (const std::string key : {"image", "resolution", "origin"}) {
    std::string text;
    if (key != "image") text += "image: m.pgm\n";
    if (key != "resolution") text += "resolution: 0.1\n";
    if (key != "origin") text += "origin: [0, 0, 0]\n";
    const std::string p = dir.write("m.yaml", text);
    expect_error([&] { load_ros_map(p); }, {p, "missing key", key});
  }
}

TEST(MapIoErrors, WrongTypeResolution) {
  TempDir dir;
  const std::string p = dir.write("m.yaml", yaml("m.pgm", "", "\"abc\""));
  expect_error([&] { load_ros_map(p); }, {p, "resolution", "abc"});
}

TEST(MapIoErrors, ZeroAndNegativeResolution) {
  TempDir dir;
  for (const std::string r : {"0", "0.0", "-0.05", ".nan"}) {
    const std::string p = dir.write("m.yaml", yaml("m.pgm", "", r));
    expect_error([&] { load_ros_map(p); }, {p, "resolution", "positive"});
  }
}

TEST(MapIoErrors, BadOrigin) {
  TempDir dir;
  for (const std::string o : {"[0, 0]", "0.5", "[0, 0, 0, 0]", "[0, x, 0]", "[0, .inf, 0]"}) {
    const std::string p = dir.write("m.yaml", yaml("m.pgm", "", "0.1", o));
    expect_error([&] { load_ros_map(p); }, {p, "origin"});
  }
}

TEST(MapIoErrors, BadMode) {
  TempDir dir;
  const std::string p = dir.write("m.yaml", yaml("m.pgm", "mode: fancy\n"));
  expect_error([&] { load_ros_map(p); }, {p, "mode", "fancy"});
}

TEST(MapIoErrors, BadNegate) {
  TempDir dir;
  const std::string p = dir.write("m.yaml", yaml("m.pgm", "negate: 2\n"));
  expect_error([&] { load_ros_map(p); }, {p, "negate", "2"});
}

TEST(MapIoErrors, BadThresholds) {
  TempDir dir;
  const std::string inverted =
      dir.write("a.yaml", yaml("m.pgm", "occupied_thresh: 0.2\nfree_thresh: 0.6\n"));
  expect_error([&] { load_ros_map(inverted); }, {inverted, "free_thresh", "occupied_thresh"});
  const std::string above = dir.write("b.yaml", yaml("m.pgm", "occupied_thresh: 1.5\n"));
  expect_error([&] { load_ros_map(above); }, {above, "occupied_thresh"});
  const std::string typed = dir.write("c.yaml", yaml("m.pgm", "free_thresh: low\n"));
  expect_error([&] { load_ros_map(typed); }, {typed, "free_thresh", "low"});
}

// ---- limits and image faults (issue 14) ---------------------------------------------------

// A non-scalar key is a gridloc::Error naming the file (it once escaped as
// YAML::TypedBadConversion, an "internal error" with exit code 1).
TEST(MapIoErrors, NonScalarKeyThrowsGridlocError) {
  TempDir dir;
  const std::string p = dir.write("m.yaml", "? [a, b]\n: 1\n" + yaml("m.pgm"));
  expect_error([&] { load_ros_map(p); }, {p, "key"});
}

}  // namespace
}  // namespace gridloc
