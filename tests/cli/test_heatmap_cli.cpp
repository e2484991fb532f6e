// End-to-end tests of `gridloc heatmap` (issue 4): the images and files it writes have the
// expected size and non-trivial content, the .npy volume matches volume.json and the
// estimate, and bad input is one error line with exit status 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "cli_support.hpp"
#include "gridloc/grids/map_io.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using test::TempDir;

using test::CliRun;
using test::expect_cli_error;
using test::quote;
using test::read_file;
using test::run_cli;

/// A NumPy .npy file: shape and float32 data.
struct Npy {
  std::vector<long long> shape;
  std::vector<float> data;
};

Npy read_npy(const std::string& path) {
  const std::string bytes = read_file(path);
  Npy n;
  EXPECT_GE(bytes.size(), 10u);
  if (bytes.size() < 10) return n;
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const std::size_t length = static_cast<std::uint8_t>(bytes[8]) |
                             (static_cast<std::size_t>(static_cast<std::uint8_t>(bytes[9])) << 8);
  EXPECT_EQ((10 + length) % 64, 0u) << "the data must start 64-byte aligned";
  const std::string header = bytes.substr(10, length);
  EXPECT_EQ(header.back(), '\n');
  EXPECT_NE(header.find("'descr': '<f4'"), std::string::npos) << header;
  EXPECT_NE(header.find("'fortran_order': False"), std::string::npos) << header;
  std::smatch m;
  const std::string h = header;
  EXPECT_TRUE(std::regex_search(h, m, std::regex(R"('shape': \((\d+), (\d+), (\d+)\))"))) << header;
  if (m.size() == 4) {
    for (int k = 1; k <= 3; ++k) n.shape.push_back(std::stoll(m[k].str()));
  }
  const std::size_t data_bytes = bytes.size() - 10 - length;
  EXPECT_EQ(data_bytes % sizeof(float), 0u);
  n.data.resize(data_bytes / sizeof(float));
  std::memcpy(n.data.data(), bytes.data() + 10 + length, n.data.size() * sizeof(float));
  return n;
}

/// Distinct colours of an image (BGR).
std::size_t colours(const cv::Mat& img) {
  std::set<std::tuple<int, int, int>> seen;
  for (int r = 0; r < img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) {
      const cv::Vec3b p = img.at<cv::Vec3b>(r, c);
      seen.insert({p[0], p[1], p[2]});
    }
  }
  return seen.size();
}

/// Checks every file of a heatmap folder against the command's JSON; returns volume.json.
nlohmann::json expect_heatmap_files(const std::string& out, const std::string& stdout_json) {
  const auto j = nlohmann::json::parse(stdout_json);
  for (const char* name : {"score_xy_best_theta.png", "score_xy_max_theta.png", "score_theta.png",
                           "local_overlay.png"}) {
    const std::string path = out + "/" + name;
    const cv::Mat img = cv::imread(path, cv::IMREAD_COLOR);
    EXPECT_FALSE(img.empty()) << path << " does not decode";
    if (img.empty()) continue;
    EXPECT_GE(img.cols, 500) << name;
    EXPECT_GE(img.rows, 350) << name;
    // Text, map greys, colour map and markers: far more than a blank or one-colour image.
    EXPECT_GE(colours(img), 50u) << name;
  }
  const auto volume = nlohmann::json::parse(read_file(out + "/volume.json"));
  const Npy npy = read_npy(out + "/scores.npy");
  const long long t = volume.at("headings"), ny = volume.at("ny"), nx = volume.at("nx");
  EXPECT_EQ(npy.shape, (std::vector<long long>{t, ny, nx}));
  EXPECT_EQ(volume.at("shape").get<std::vector<long long>>(), npy.shape);
  EXPECT_EQ(static_cast<long long>(npy.data.size()), t * ny * nx);
  EXPECT_EQ(volume.at("mass").size(), static_cast<std::size_t>(t));
  if (npy.data.empty()) return volume;
  // The volume's maximum is the search's winner, at the indices volume.json gives.
  const float best = *std::max_element(npy.data.begin(), npy.data.end());
  EXPECT_EQ(best, static_cast<float>(j.at("score").get<double>())) << stdout_json;
  EXPECT_EQ(best, static_cast<float>(volume.at("best").at("score").get<double>()));
  const long long bx = volume.at("best").at("x"), by = volume.at("best").at("y"),
                  bt = volume.at("best").at("t");
  EXPECT_EQ(npy.data[static_cast<std::size_t>((bt * ny + by) * nx + bx)], best);
  const auto [lo, hi] = std::minmax_element(npy.data.begin(), npy.data.end());
  EXPECT_LT(*lo, *hi) << "a flat volume";
  // The volume's winner is the search's lattice pose.
  EXPECT_NEAR(volume.at("best").at("pose").at("x").get<double>(),
              j.at("lattice").at("pose").at("x").get<double>(), 1e-9);
  EXPECT_NEAR(volume.at("best").at("pose").at("y").get<double>(),
              j.at("lattice").at("pose").at("y").get<double>(), 1e-9);
  EXPECT_EQ(j.at("files").at("scores").get<std::string>(), out + "/scores.npy");
  EXPECT_EQ(volume.at("files").at("scores").get<std::string>(), "scores.npy");
  return volume;
}

class HeatmapCli : public ::testing::Test {
 protected:
  void SetUp() override { ::setenv("GRIDLOC_DATA_DIR", test::maps_dir().c_str(), 1); }
  /// Noise-free readings of the bundled ring at (1.65, 1.65, 0.3) on `map`, in the folder.
  std::string readings_on(const std::string& map) {
    const std::string readings = dir.file("readings.json");
    const CliRun sim = run_cli(
        dir, "simulate --map " + quote(map) + " --pose 1.65,1.65,0.3 --out " + quote(readings));
    EXPECT_EQ(sim.status, 0) << sim.err;
    return readings;
  }
  TempDir dir;
};

TEST_F(HeatmapCli, SonarOnRoomL) {
  const std::string map = test::map_path("room_l");
  const std::string readings = dir.file("readings.json");
  // (1.65, 1.65) is 2 m from the L's west and 1.5 m from its south wall.
  ASSERT_EQ(run_cli(dir, "simulate --map " + quote(map) + " --pose 1.65,1.65,0.3 --realistic " +
                             "--out " + quote(readings))
                .status,
            0);
  const std::string out = dir.file("heat sonar");  // a space, and created by the command
  const CliRun r =
      run_cli(dir, "heatmap --map " + quote(map) + " --readings " + quote(readings) +
                       " --prior 1.9,1.4,0.6 --truth 1.65,1.65,0.3 --out " + quote(out));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const auto volume = expect_heatmap_files(out, r.out);
  // Seed 001's window: 17 x 17 cells of 10 cm, 19 headings of 5 degrees.
  EXPECT_EQ(volume.at("nx").get<int>(), 17);
  EXPECT_EQ(volume.at("ny").get<int>(), 17);
  EXPECT_EQ(volume.at("headings").get<int>(), 19);
  EXPECT_NEAR(volume.at("step_theta_deg").get<double>(), 5.0, 1e-6);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_LE(std::hypot(j.at("pose").at("x").get<double>() - 1.65,
                       j.at("pose").at("y").get<double>() - 1.65),
            0.10)
      << r.out;
}

/// Pixels of the estimate's red (the marker, and the covariance ellipse when drawn).
int red_pixels(const cv::Mat& img) {
  int n = 0;
  for (int r = 0; r < img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) {
      const cv::Vec3b p = img.at<cv::Vec3b>(r, c);
      n += p[2] > 180 && p[1] < 90 && p[0] < 90;
    }
  }
  return n;
}

// The x, y images draw the estimate's 95 % covariance ellipse: a covariance turned off
// (--covariance-cells 0) draws none, so far fewer red pixels (the ring's covariance reported
// at --covariance-temperature, the wider one).
TEST_F(HeatmapCli, TheCovarianceEllipseIsDrawn) {
  const std::string map = test::map_path("room_l");
  const std::string readings = readings_on(map);
  int red[2] = {0, 0};
  for (const int cells : {3, 0}) {
    const std::string out = dir.file("heat" + std::to_string(cells));
    const CliRun r = run_cli(dir, "heatmap --map " + quote(map) + " --readings " + quote(readings) +
                                      " --prior 1.9,1.4,0.6 --ring-covariance-temperature 0"
                                      " --covariance-cells " +
                                      std::to_string(cells) + " --out " + quote(out));
    ASSERT_EQ(r.status, 0) << r.err;
    red[cells == 0] = red_pixels(cv::imread(out + "/score_xy_best_theta.png", cv::IMREAD_COLOR));
  }
  EXPECT_GT(red[0], red[1] + 100) << red[0] << " vs " << red[1];
}

TEST_F(HeatmapCli, ScanOnRoomRect) {
  // 72 beams from (3, 2) in room_rect's own frame (6 x 4.5 m inside, corner at world
  // (0.15, 0.15)), walls only: the desk and cupboard make a few ranges wrong, as in life.
  std::string csv = "# angle_rad,range_m\n";
  for (int k = 0; k < 72; ++k) {
    const double a = -std::numbers::pi + k * 2.0 * std::numbers::pi / 72;
    const double c = std::cos(a), s = std::sin(a);
    double range = 100.0;
    if (c > 1e-9) range = std::min(range, 3.0 / c);
    if (c < -1e-9) range = std::min(range, -3.0 / c);
    if (s > 1e-9) range = std::min(range, 2.5 / s);
    if (s < -1e-9) range = std::min(range, -2.0 / s);
    csv += std::to_string(a) + "," + std::to_string(range) + "\n";
  }
  const std::string scan = dir.write("scan.csv", csv);
  const std::string out = dir.file("heat_scan");
  const CliRun r =
      run_cli(dir, "heatmap --map " + quote(test::map_path("room_rect")) + " --scan " +
                       quote(scan) + " --prior 3.3,2.0,0.1 --window-xy 0.4 --window-theta 0.2 " +
                       "--step-xy 0.05 --step-theta 0.02 --out " + quote(out));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto volume = expect_heatmap_files(out, r.out);
  EXPECT_EQ(volume.at("nx").get<int>(), 17);
  EXPECT_EQ(volume.at("headings").get<int>(), 21);
  EXPECT_NEAR(volume.at("resolution").get<double>(), 0.05, 1e-12);
}

TEST_F(HeatmapCli, Errors) {
  const std::string map = test::map_path("room_l");
  const std::string readings = readings_on(map);
  const std::string base = "heatmap --map " + quote(map) + " --readings " + quote(readings);
  // --out without its value, and without --out at all.
  expect_cli_error(run_cli(dir, base + " --prior 1.9,1.4,0.6 --out"), {"--out"});
  expect_cli_error(run_cli(dir, base + " --prior 1.9,1.4,0.6"), {"--out"});
  // The whole map at 0.01 degree steps: 83 x 73 cells x 36001 headings.
  const CliRun big =
      run_cli(dir, base + " --global --step-theta 0.000174533 --out " + quote(dir.file("big")));
  expect_cli_error(big, {"poses", "30000000", "--step-theta"});
  EXPECT_FALSE(test::fs::exists(dir.file("big"))) << "nothing is written for a refused volume";
  expect_cli_error(
      run_cli(dir, base + " --prior 1.9,1.4,0.6 --truth 1,2 --out " + quote(dir.file("t"))),
      {"--truth"});
  // A file where the folder should be.
  const std::string file = dir.write("a_file", "x");
  expect_cli_error(run_cli(dir, base + " --prior 1.9,1.4,0.6 --out " + quote(file)), {"--out"});
}

TEST_F(HeatmapCli, SectorsImage) {
  // `gridloc sectors --out` (seed 000's sectors) draws with the same plotting code.
  const std::string polygons = test::maps_dir() + "/polygons/room_l.yaml";
  const std::string out = dir.file("sectors out/l");  // a space, two levels created
  const CliRun r = run_cli(dir, "sectors --polygons " + quote(polygons) + " --out " + quote(out));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("wrote " + out + "/sectors.png"), std::string::npos) << r.out;
  const std::string png = out + "/sectors.png";
  ASSERT_GT(read_file(png).size(), 0u) << png;
  const cv::Mat img = cv::imread(png, cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty()) << png << " does not decode";
  EXPECT_GT(img.cols, 200);
  EXPECT_GT(img.rows, 200);
  EXPECT_LE(img.cols, 1700);
  // A colour per sector, greys, text: far more than a blank image.
  EXPECT_GE(colours(img), 100u);
  // sectors.json is what --json prints.
  const CliRun j = run_cli(dir, "sectors --polygons " + quote(polygons) + " --json");
  ASSERT_EQ(j.status, 0) << j.err;
  EXPECT_EQ(nlohmann::json::parse(read_file(out + "/sectors.json")), nlohmann::json::parse(j.out));
  EXPECT_GT(nlohmann::json::parse(j.out).at("sector_count").get<int>(), 1);
}

}  // namespace
}  // namespace gridloc
