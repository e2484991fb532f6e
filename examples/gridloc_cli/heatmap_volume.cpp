// The score volume of `gridloc heatmap` on disk (issue 4): scores.npy (float32, C order) and
// volume.json (shape, axes, map grid, best pose, heading masses, window, files).
#include "heatmap_volume.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <vector>

#include "commands.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc::cli {

void write_npy(const std::string& path, const ScoreVolume& volume) {
  static_assert(std::endian::native == std::endian::little, "write_npy assumes little endian");
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" +
                       std::to_string(volume.headings) + ", " + std::to_string(volume.ny) + ", " +
                       std::to_string(volume.nx) + "), }";
  const std::size_t unpadded = 10 + header.size() + 1;
  header += std::string((64 - unpadded % 64) % 64, ' ') + "\n";
  std::ofstream file(path, std::ios::binary);
  if (!file) throw Error(path + ": cannot write the score volume");
  const std::uint16_t length = static_cast<std::uint16_t>(header.size());
  file.write("\x93NUMPY\x01\x00", 8);
  file.put(static_cast<char>(length & 0xff));
  file.put(static_cast<char>(length >> 8));
  file << header;
  std::vector<float> data(volume.scores.begin(), volume.scores.end());
  file.write(reinterpret_cast<const char*>(data.data()),
             static_cast<std::streamsize>(data.size() * sizeof(float)));
  if (!file) throw Error(path + ": cannot write the score volume");
}

nlohmann::json volume_json(const ScoreVolume& volume, const SearchWindow& window,
                           const nlohmann::json& files) {
  const GridGeometry& grid = volume.geometry;
  const Pose2 first = volume.pose(0, 0, 0);
  std::vector<double> mass(volume.mass.begin(), volume.mass.end());
  return {{"file", "scores.npy"},
          {"dtype", "float32, little endian"},
          {"shape", {volume.headings, volume.ny, volume.nx}},
          {"axes", {"heading", "y", "x"}},
          {"index",
           "scores[t, y, x]: heading theta0 + t * step_theta, cell centre (x0, y0) + x * "
           "resolution * x_axis + y * resolution * y_axis (y grows northwards)"},
          {"nx", volume.nx},
          {"ny", volume.ny},
          {"headings", volume.headings},
          {"resolution", volume.resolution},
          {"x0", first.x},
          {"y0", first.y},
          {"x_axis", {std::cos(grid.yaw), std::sin(grid.yaw)}},
          {"y_axis", {-std::sin(grid.yaw), std::cos(grid.yaw)}},
          {"theta0", volume.theta0 + grid.yaw},
          {"step_theta", volume.step_theta},
          {"theta0_deg", rad2deg(volume.theta0 + grid.yaw)},
          {"step_theta_deg", rad2deg(volume.step_theta)},
          {"map_cell0", {volume.ix0, volume.iy0}},
          {"map_grid",
           {{"resolution", grid.resolution},
            {"origin", {grid.origin.x(), grid.origin.y()}},
            {"yaw", grid.yaw},
            {"width", grid.width},
            {"height", grid.height}}},
          {"best",
           {{"x", volume.best.ix},
            {"y", volume.best.iy},
            {"t", volume.best.it},
            {"score", volume.best.score},
            {"pose", to_json(volume.pose(volume.best.ix, volume.best.iy, volume.best.it))}}},
          {"mass", mass},
          {"window",
           {{"center", to_json(window.center)},
            {"half_xy", window.half_xy},
            {"half_theta", window.half_theta},
            {"step_xy", window.step_xy},
            {"step_theta", window.step_theta}}},
          {"files", files}};
}

}  // namespace gridloc::cli
