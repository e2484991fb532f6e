// Shared helpers of the map loader's tests (test_map_io.cpp, test_map_io_limits.cpp): map
// images written as PGM text, their YAML, and the states of a loaded row.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gridloc/grids/map_io.hpp"
#include "test_support.hpp"

namespace gridloc::map_io_test {

using test::expect_error;
using test::TempDir;

/// Binary PGM (P5); `top_first` holds the image rows from the top (image row 0) down.
inline std::string pgm(int w, int h, const std::vector<std::uint8_t>& top_first) {
  std::string s = "P5\n" + std::to_string(w) + " " + std::to_string(h) + "\n255\n";
  s.append(top_first.begin(), top_first.end());
  return s;
}

inline std::string yaml(const std::string& image, const std::string& extra = "",
                        const std::string& resolution = "0.5",
                        const std::string& origin = "[0.0, 0.0, 0.0]") {
  return "image: " + image + "\nresolution: " + resolution + "\norigin: " + origin + "\n" + extra;
}

/// A one-row map whose pixels are `values`, loaded with the extra YAML lines `extra`.
inline OccupancyMap load_row(const TempDir& dir, const std::vector<std::uint8_t>& values,
                             const std::string& extra) {
  dir.write("row.pgm", pgm(static_cast<int>(values.size()), 1, values));
  return load_ros_map(dir.write("row.yaml", yaml("row.pgm", extra)));
}

constexpr CellState F = CellState::Free;
constexpr CellState O = CellState::Occupied;
constexpr CellState U = CellState::Unknown;

inline std::vector<CellState> row_states(const OccupancyMap& m, int iy = 0) {
  std::vector<CellState> v;
  for (int ix = 0; ix < m.width(); ++ix) v.push_back(m.at(ix, iy));
  return v;
}

/// Loads a map whose image file holds `image` (under the name `name`).
inline OccupancyMap load_image(const TempDir& dir, const std::string& name,
                               const std::string& image, const ResourceLimits& limits = {}) {
  dir.write(name, image);
  return load_ros_map(dir.write("m.yaml", yaml(name)), limits);
}

}  // namespace gridloc::map_io_test
