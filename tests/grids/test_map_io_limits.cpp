// Tests of grids/src/map_io.cpp's image decoding within limits: its PGM/PNG decoders against
// OpenCV's, maxval scaling, bit depths, declared sizes, damaged files, coordinates, oversized
// YAML and directories, each refused with one error naming the file.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "gridloc/grids/map_io.hpp"
#include "map_io_cases.hpp"
#include "png_bytes.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using namespace map_io_test;

/// The image of a bundled map, as OpenCV decodes it.
cv::Mat bundled_image(const std::string& name) {
  return cv::imread(test::maps_dir() + "/" + name + ".pgm", cv::IMREAD_UNCHANGED);
}

/// The rows (from the top) of the bundled room_rect map's image.
std::vector<std::vector<std::uint8_t>> room_rows() {
  const cv::Mat img = bundled_image("room_rect");
  std::vector<std::vector<std::uint8_t>> rows;
  for (int r = 0; r < img.rows; ++r) {
    rows.emplace_back(img.ptr<std::uint8_t>(r), img.ptr<std::uint8_t>(r) + img.cols);
  }
  return rows;
}

TEST(MapIoLimits, BundledMapsLoadAsOpenCvDecodesThem) {
  // The PGM decoder of gridloc and OpenCV's agree on every bundled map, pixel for pixel.
  for (const char* name :
       {"room_rect", "room_l", "room_furnished", "room_symmetric", "apartment_small"}) {
    const OccupancyMap m = load_ros_map(test::map_path(name));
    const cv::Mat img = bundled_image(name);
    ASSERT_EQ(m.width(), img.cols) << name;
    ASSERT_EQ(m.height(), img.rows) << name;
    for (int r = 0; r < img.rows; ++r) {
      for (int c = 0; c < img.cols; ++c) {
        const int v = img.at<std::uint8_t>(r, c);
        const CellState want = v < 90 ? O : v > 204 && v != 205 ? F : U;
        ASSERT_EQ(m.at(c, img.rows - 1 - r), want) << name << " pixel " << r << ", " << c;
      }
    }
  }
}

TEST(MapIoLimits, PngAndPgmOfTheSamePixelsGiveTheSameMap) {
  TempDir dir;
  const auto rows = room_rows();
  std::string pgm_text =
      "P5\n" + std::to_string(rows[0].size()) + " " + std::to_string(rows.size()) + "\n255\n";
  for (const auto& row : rows) pgm_text.append(row.begin(), row.end());
  const OccupancyMap from_pgm = load_image(dir, "a.pgm", pgm_text);
  std::vector<std::uint8_t> encoded;
  cv::Mat copy(static_cast<int>(rows.size()), static_cast<int>(rows[0].size()), CV_8UC1);
  for (int r = 0; r < copy.rows; ++r)
    std::copy(rows[r].begin(), rows[r].end(), copy.ptr<std::uint8_t>(r));
  ASSERT_TRUE(cv::imencode(".png", copy, encoded));
  const OccupancyMap from_png =
      load_image(dir, "b.png", std::string(encoded.begin(), encoded.end()));
  EXPECT_EQ(from_png.cells, from_pgm.cells);
  const OccupancyMap from_stored_png = load_image(dir, "c.png", test::grey_png(rows));
  EXPECT_EQ(from_stored_png.cells, from_pgm.cells);
  EXPECT_EQ(from_pgm.cells, load_ros_map(test::map_path("room_rect")).cells);
}

TEST(MapIoLimits, AsciiPgmAndPpmLoadLikeBinaryPgm) {
  TempDir dir;
  const std::vector<std::uint8_t> v = {0, 254, 205, 254};
  const OccupancyMap binary = load_row(dir, v, "");
  EXPECT_EQ(load_image(dir, "a.pgm", "P2\n# comment\n4 1\n255\n0 254\n205 254\n").cells,
            binary.cells);
  EXPECT_EQ(load_image(dir, "a.ppm",
                       std::string("P6\n4 1\n255\n\0\0\0\xfe\xfe\xfe\xcd\xcd\xcd\xfe\xfe\xfe", 23))
                .cells,
            binary.cells);
}

TEST(MapIoLimits, MaxvalBelow255IsScaledAsMapServerDoes) {
  TempDir dir;
  // v * 255 / maxval: 100 -> 255 (free), 0 -> 0 (occupied), 50 -> 127 (p = 0.50: unknown).
  const OccupancyMap m = load_image(dir, "m.pgm", std::string("P5\n3 1\n100\n\x64\x00\x32", 15));
  EXPECT_EQ(row_states(m), (std::vector<CellState>{F, O, U}));
}

TEST(MapIoLimits, PixelAboveMaxvalNamesThePixel) {
  TempDir dir;
  expect_error([&] { load_image(dir, "m.pgm", "P2\n2 2\n100\n1 2\n3 101\n"); },
               {"m.pgm", "row 1, column 1", "101", "maxval 100"});
}

TEST(MapIoLimits, SixteenBitImagesAreRejected) {
  TempDir dir;
  expect_error([&] { load_image(dir, "m.pgm", "P5\n1 1\n65535\n\xff\xff"); }, {"m.pgm", "16-bit"});
  std::string png = test::grey_png({{1}});
  png[8 + 8 + 8] = 16;  // IHDR bit depth (the CRC is checked after the header)
  expect_error([&] { load_image(dir, "m.png", png); }, {"m.png", "8-bit"});
}

TEST(MapIoLimits, DeclaredSizeIsCheckedBeforeDecoding) {
  TempDir dir;
  // 20000 x 20000 declared by a few bytes: refused before any pixel is allocated.
  expect_error([&] { load_image(dir, "big.pgm", "P5\n20000 20000\n255\n\xfe"); },
               {"big.pgm", "20000 x 20000", "--max-cells"});
  expect_error(
      [&] { load_image(dir, "big.png", "\x89PNG\r\n\x1a\n" + test::png_ihdr(20000, 20000)); },
      {"big.png", "20000 x 20000", "--max-cells"});
  ResourceLimits small;
  small.max_memory_mb = 1.0;
  expect_error([&] { load_image(dir, "m.pgm", "P5\n1000 1000\n255\n", small); },
               {"m.pgm", "--max-memory-mb"});
}

TEST(MapIoLimits, EmptyOrTallHeadersAreOneError) {
  TempDir dir;
  expect_error([&] { load_image(dir, "m.pgm", std::string("P5\n1 2000000\n255\n\0", 18)); },
               {"m.pgm", "truncated", "1 x 2000000"});
  expect_error([&] { load_image(dir, "m.pgm", "P5\n10 0\n255\n"); }, {"m.pgm", "side of 0"});
  expect_error([&] { load_image(dir, "m.pgm", "P5\n10 5\n0\n"); }, {"m.pgm", "maxval of 0"});
  expect_error([&] { load_image(dir, "m.pgm", "P5\n10"); }, {"m.pgm", "lacks its height"});
  expect_error([&] { load_image(dir, "m.png", "\x89PNG\r\n\x1a\n" + test::png_ihdr(0, 10)); },
               {"m.png", "side of 0"});
}

TEST(MapIoLimits, TruncatedAndDamagedImagesPrintNothing) {
  TempDir dir;
  const std::string png = test::grey_png(room_rows());
  std::string damaged = png;
  damaged[png.size() / 2] ^= 0x55;
  testing::internal::CaptureStderr();
  expect_error([&] { load_image(dir, "cut.png", png.substr(0, png.size() / 2)); },
               {"cut.png", "truncated"});
  expect_error([&] { load_image(dir, "end.png", png.substr(0, png.size() - 12)); },
               {"end.png", "truncated"});
  expect_error([&] { load_image(dir, "bad.png", damaged); }, {"bad.png", "CRC"});
  expect_error([&] { load_image(dir, "cut.pgm", "P5\n10 10\n255\n" + std::string(50, '\xfe')); },
               {"cut.pgm", "truncated", "50 bytes"});
  expect_error([&] { load_image(dir, "cut2.pgm", "P2\n2 2\n255\n1 2 3"); },
               {"cut2.pgm", "truncated"});
  expect_error([&] { load_image(dir, "junk.png", "\x89PNG\r\n\x1a\n"); }, {"junk.png", "IHDR"});
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(MapIoLimits, PngWithWrongRowCountIsRefused) {
  TempDir dir;
  // Image data for 2 rows where the header declares 3.
  const std::string data =
      test::png_chunk("IDAT", test::zlib_stored(std::string("\0\1\2\0\3\4", 6)));
  const std::string png =
      "\x89PNG\r\n\x1a\n" + test::png_ihdr(2, 3) + data + test::png_chunk("IEND", "");
  expect_error([&] { load_image(dir, "m.png", png); }, {"m.png", "truncated"});
  const std::string bad_filter =
      test::png_chunk("IDAT", test::zlib_stored(std::string("\7\1\2", 3)));
  expect_error(
      [&] {
        load_image(
            dir, "f.png",
            "\x89PNG\r\n\x1a\n" + test::png_ihdr(2, 1) + bad_filter + test::png_chunk("IEND", ""));
      },
      {"f.png", "row filter"});
}

TEST(MapIoLimits, CoordinatesBeyondTheLimitAreRefused) {
  TempDir dir;
  dir.write("m.pgm", pgm(4, 2, std::vector<std::uint8_t>(8, 254)));
  const std::string res = dir.write("r.yaml", yaml("m.pgm", "", "1e300"));
  expect_error([&] { load_ros_map(res); }, {res, "resolution", "--max-coordinate-m"});
  const std::string origin = dir.write("o.yaml", yaml("m.pgm", "", "0.05", "[1e300, 1e300, 0]"));
  expect_error([&] { load_ros_map(origin); }, {origin, "origin", "--max-coordinate-m"});
  // 4 px at 3e5 m reach 1.2e6 m: the corner, not the resolution, is beyond 1e6 m.
  const std::string corner = dir.write("c.yaml", yaml("m.pgm", "", "3e5"));
  expect_error([&] { load_ros_map(corner); }, {corner, "corner", "--max-coordinate-m"});
  ResourceLimits wide;
  wide.max_coordinate_m = 2e6;
  EXPECT_EQ(load_ros_map(corner, wide).width(), 4);
}

TEST(MapIoLimits, OversizedYamlIsRefusedBeforeParsing) {
  TempDir dir;
  const std::string p = dir.write("m.yaml", yaml("m.pgm") + std::string(kMaxMapYamlBytes, '#'));
  expect_error([&] { load_ros_map(p); }, {p, "too large for a map_server YAML"});
}

TEST(MapIoLimits, DirectoriesAreNamed) {
  TempDir dir;
  std::filesystem::create_directory(dir.file("d.yaml"));
  expect_error([&] { load_ros_map(dir.file("d.yaml")); }, {"d.yaml", "is a directory"});
  std::filesystem::create_directory(dir.file("img.pgm"));
  const std::string p = dir.write("m.yaml", yaml("img.pgm"));
  expect_error([&] { load_ros_map(p); }, {"img.pgm", "is a directory"});
}

}  // namespace
}  // namespace gridloc
