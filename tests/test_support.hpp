#pragma once
// Helpers shared by the test files: bundled data paths, temporary folders, error checks.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <random>
#include <string>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/grid.hpp"

namespace gridloc::test {

namespace fs = std::filesystem;

/// The source tree's maps/ folder (set by tests/CMakeLists.txt).
/// A w x h map of `fill` at `res`, its origin (1, -2) and yaw 0.3 (not axis-aligned, so that
/// frame mistakes show).
inline OccupancyMap filled_map(int w, int h, CellState fill, double res) {
  GridGeometry g;
  g.resolution = res;
  g.origin = {1.0, -2.0};
  g.yaw = 0.3;
  g.width = w;
  g.height = h;
  return OccupancyMap(g, fill);
}

/// A free w x h map at `res` whose border cells are occupied (walls one cell thick), its
/// cell (0, 0) at `origin`.
inline OccupancyMap walled_room(int w, int h, double res, const Eigen::Vector2d& origin) {
  GridGeometry g;
  g.resolution = res;
  g.origin = origin;
  g.width = w;
  g.height = h;
  OccupancyMap map(g, CellState::Free);
  for (int ix = 0; ix < w; ++ix) map.at(ix, 0) = map.at(ix, h - 1) = CellState::Occupied;
  for (int iy = 0; iy < h; ++iy) map.at(0, iy) = map.at(w - 1, iy) = CellState::Occupied;
  return map;
}

inline std::string maps_dir() {
  return GRIDLOC_TEST_MAPS_DIR;
}
inline std::string map_path(const std::string& name) {
  return maps_dir() + "/" + name + ".yaml";
}
inline std::string ring_path() {
  return maps_dir() + "/sensors/wheelchair_14.yaml";
}

/// A fresh folder under the system temp directory, removed with its contents on destruction.
/// The name holds the test's name, the process id and a random number, so tests run in
/// parallel by ctest never share one.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info ? std::string(info->test_suite_name()) + "_" + info->name() : "gridloc";
    for (char& ch : name) {
      if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
    }
    std::random_device rd;
    path_ = fs::temp_directory_path() /
            ("gridloc_" + name + "_" + std::to_string(::getpid()) + "_" + std::to_string(rd()));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const fs::path& path() const { return path_; }
  /// Path of `name` inside the folder, as a string.
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  /// Writes `text` to `name` inside the folder and returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    const std::string p = file(name);
    std::ofstream out(p, std::ios::binary);
    out << text;
    return p;
  }

 private:
  fs::path path_;
};

/// Expects `fn` to throw gridloc::Error whose message contains every one of `parts`.
inline void expect_error(const std::function<void()>& fn,
                         std::initializer_list<std::string> parts) {
  try {
    fn();
    ADD_FAILURE() << "expected gridloc::Error, nothing was thrown";
  } catch (const Error& e) {
    const std::string msg = e.what();
    for (const auto& part : parts) {
      EXPECT_NE(msg.find(part), std::string::npos)
          << "message '" << msg << "' does not contain '" << part << "'";
    }
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected gridloc::Error, got another exception: " << e.what();
  }
}

}  // namespace gridloc::test
