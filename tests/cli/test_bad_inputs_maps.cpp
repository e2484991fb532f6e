// The bad-input table (issue 14), maps: map images that declare huge or empty sizes, are
// truncated or damaged; map YAML numbers beyond the coordinate limit; polygon maps too large
// or with too many vertices; directories given as maps; maps too small for the search.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "bad_input_table.hpp"
#include "png_bytes.hpp"

namespace gridloc::test {
namespace {

/// A valid readings file of the bundled 14-sonar ring, for cases about the map.
const std::pair<std::string, std::string> kReadings = {
    "readings.json",
    R"({"ranges_m": [0.9, 2.7, 4.1, 5.0, 2.6, 2.6, 1.4, 0.3, 0.3, 0.3, 0.3, 0.5, 0.5, 6.0]})"};

/// A map YAML naming `image`, with the given resolution and origin.
std::pair<std::string, std::string> map_yaml(const std::string& image,
                                             const std::string& resolution = "0.05",
                                             const std::string& origin = "[0, 0, 0]") {
  return {"m.yaml",
          "image: " + image + "\nresolution: " + resolution + "\norigin: " + origin + "\n"};
}

const std::string kLocalize = "localize --global --map {dir}/m.yaml --readings {dir}/readings.json";

/// A free 40 x 30 PGM (2 x 1.5 m at 5 cm).
std::string room_pgm() {
  return "P5\n40 30\n255\n" + std::string(40 * 30, '\xfe');
}

/// A square polygon map of side `side` m (its boundary only).
std::string square_polygon(const std::string& side) {
  return "boundary: [[0, 0], [" + side + ", 0], [" + side + ", " + side + "], [0, " + side +
         "], [0, 0]]\n";
}

/// A polygon map whose boundary has `n` vertices on a circle.
std::string many_vertices(int n) {
  std::ostringstream text;
  text << "boundary: [";
  for (int i = 0; i <= n; ++i) {
    const double a = 2.0 * 3.141592653589793 * (i % n) / n;
    text << "[" << 10 + 10 * std::cos(a) << ", " << 10 + 10 * std::sin(a) << "]"
         << (i < n ? ", " : "]\n");
  }
  return text.str();
}

std::string valid_png() {
  return grey_png(std::vector<std::vector<std::uint8_t>>(30, std::vector<std::uint8_t>(40, 254)));
}

const std::vector<BadInputCase> kMapCases = {
    // 1. the declared size is checked before anything is decoded
    {"HugePgmHeader",
     {kReadings, map_yaml("big.pgm"), {"big.pgm", "P5\n20000 20000\n255\n\xfe\xfe"}},
     kLocalize,
     {"big.pgm", "20000 x 20000", "--max-cells"}},
    {"HugePngHeader",
     {kReadings, map_yaml("big.png")},
     kLocalize,
     {"big.png", "20000 x 20000", "--max-cells"},
     [](const TempDir& dir) {
       dir.write("big.png", "\x89PNG\r\n\x1a\n" + png_ihdr(20000, 20000));
     }},
    {"ImageOverMemoryLimit",
     {kReadings, map_yaml("m.pgm"), {"m.pgm", "P5\n2000 2000\n255\n"}},
     "--max-memory-mb 2 " + kLocalize,
     {"m.pgm", "--max-memory-mb"}},
    // 2. what OpenCV threw: a side over 2^20, a side of 0
    {"TallPgm18Bytes",
     {kReadings, map_yaml("tall.pgm"), {"tall.pgm", std::string("P5\n1 2000000\n255\n\0", 18)}},
     kLocalize,
     {"tall.pgm", "truncated"}},
    {"ZeroHeightPgm",
     {kReadings, map_yaml("flat.pgm"), {"flat.pgm", "P5\n10 0\n255\n"}},
     kLocalize,
     {"flat.pgm", "side of 0"}},
    {"ZeroHeightPng",
     {kReadings, map_yaml("flat.png")},
     kLocalize,
     {"flat.png", "side of 0"},
     [](const TempDir& dir) {
       dir.write("flat.png", "\x89PNG\r\n\x1a\n" + png_ihdr(10, 0) + png_chunk("IEND", ""));
     }},
    // 3. what OpenCV and libpng printed: truncated and damaged images
    {"TruncatedPgm",
     {kReadings, map_yaml("cut.pgm"), {"cut.pgm", room_pgm().substr(0, 500)}},
     kLocalize,
     {"cut.pgm", "truncated"}},
    {"TruncatedPng",
     {kReadings, map_yaml("cut.png")},
     kLocalize,
     {"cut.png", "truncated"},
     [](const TempDir& dir) {
       const std::string png = valid_png();
       dir.write("cut.png", png.substr(0, png.size() / 2));
     }},
    {"DamagedPng",
     {kReadings, map_yaml("bad.png")},
     kLocalize,
     {"bad.png", "CRC"},
     [](const TempDir& dir) {
       std::string png = valid_png();
       png[png.size() / 2] ^= 0x55;
       dir.write("bad.png", png);
     }},
    {"NotAnImage",
     {kReadings, map_yaml("m.pgm"), {"m.pgm", "GIF89a"}},
     kLocalize,
     {"m.pgm", "not a PGM, PPM or PNG"}},
    // 4. samples above the maxval; 16-bit images
    {"PixelAboveMaxval",
     {kReadings, map_yaml("m.pgm"), {"m.pgm", "P5\n3 1\n100\n\x10\x65\x10"}},
     kLocalize,
     {"m.pgm", "row 0, column 1", "101", "maxval 100"}},
    {"SixteenBitPgm",
     {kReadings, map_yaml("m.pgm"), {"m.pgm", "P5\n1 1\n65535\n\xff\xff"}},
     kLocalize,
     {"m.pgm", "16-bit"}},
    // 5. map YAML numbers beyond the coordinate limit
    {"HugeResolution",
     {kReadings, map_yaml("room.pgm", "1e300"), {"room.pgm", room_pgm()}},
     kLocalize,
     {"m.yaml", "resolution", "--max-coordinate-m"}},
    {"HugeOrigin",
     {kReadings, map_yaml("room.pgm", "0.05", "[1e300, 1e300, 0]"), {"room.pgm", room_pgm()}},
     kLocalize,
     {"m.yaml", "origin", "--max-coordinate-m"}},
    {"CornerBeyondLimit",
     {kReadings, map_yaml("room.pgm", "50000"), {"room.pgm", room_pgm()}},
     kLocalize,
     {"m.yaml", "corner", "--max-coordinate-m"}},
    // 6. polygon maps
    {"PolygonHugeCoordinates",
     {kReadings, {"p.yaml", square_polygon("1e12")}},
     "localize --global --map {dir}/p.yaml --readings {dir}/readings.json",
     {"p.yaml", "--max-coordinate-m"}},
    {"PolygonRasterOverCells",
     {kReadings, {"p.yaml", square_polygon("1e12")}},
     "--max-coordinate-m 1e13 localize --global --map {dir}/p.yaml --readings {dir}/readings.json",
     {"rasterized", "--max-cells"}},
    {"SectorsGridOverCells",
     {{"p.yaml", square_polygon("1e5")}},
     "sectors --polygons {dir}/p.yaml",
     {"compute_sectors", "--max-cells"}},
    {"PolygonTooManyVertices",
     {},
     "sectors --polygons {dir}/p.yaml",
     {"p.yaml", "20000 vertices", "--max-vertices"},
     [](const TempDir& dir) { dir.write("p.yaml", many_vertices(20000)); }},
    {"PolygonFileTooLarge",
     {},
     "sectors --polygons {dir}/p.yaml",
     {"p.yaml", "bytes", "--max-vertices"},
     [](const TempDir& dir) {
       dir.write("p.yaml", square_polygon("4") + std::string(4 << 20, '#'));
     }},
    {"MapYamlTooLarge",
     {kReadings},
     "localize --global --map {dir}/m.txt --readings {dir}/readings.json",
     {"m.txt", "too large for a map_server YAML"},
     [](const TempDir& dir) {
       dir.write("m.txt",
                 "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n" + std::string(2 << 20, '#'));
     }},
    // 7. directories where files belong
    {"MapYamlIsADirectory",
     {kReadings},
     "localize --global --map {dir}/d.yaml --readings {dir}/readings.json",
     {"d.yaml", "is a directory"},
     [](const TempDir& dir) { std::filesystem::create_directory(dir.file("d.yaml")); }},
    {"MapImageIsADirectory",
     {kReadings, map_yaml("img.pgm")},
     kLocalize,
     {"img.pgm", "is a directory"},
     [](const TempDir& dir) { std::filesystem::create_directory(dir.file("img.pgm")); }},
    {"PolygonsIsADirectory",
     {},
     "sectors --polygons {dir}/p.yaml",
     {"p.yaml", "is a directory"},
     [](const TempDir& dir) { std::filesystem::create_directory(dir.file("p.yaml")); }},
    // 8. a map smaller than one search cell: in test_bad_inputs_sensors.cpp (OneCellMapGlobal)
};

class BadInputMaps : public ::testing::TestWithParam<BadInputCase> {};

TEST_P(BadInputMaps, ExitsTwoWithOneLine) {
  run_bad_input(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Table, BadInputMaps, ::testing::ValuesIn(kMapCases), BadInputName{});

}  // namespace
}  // namespace gridloc::test
