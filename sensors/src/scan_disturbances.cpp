#include "gridloc/sensors/scan_disturbances.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/rng.hpp"

namespace gridloc {
namespace {

void check_share(double share, const char* who) {
  if (!(share >= 0.0 && share <= 1.0)) {
    throw Error(std::string(who) + ": share must lie in [0, 1], got " + std::to_string(share));
  }
}

}  // namespace

void add_range_noise(RangeScan& scan, double sigma_m, std::uint64_t seed) {
  if (!(sigma_m >= 0.0) || !std::isfinite(sigma_m)) {
    throw Error("add_range_noise: sigma_m must be finite and >= 0, got " + std::to_string(sigma_m));
  }
  Rng rng(seed);
  for (double& r : scan.ranges) {
    if (r < scan.max_range) r = std::max(r + sigma_m * rng.gaussian(), 1e-3);
  }
}

std::vector<Eigen::Vector2d> scatter_outliers(std::vector<Eigen::Vector2d> points, double share,
                                              double half_side_m, std::uint64_t seed) {
  check_share(share, "scatter_outliers");
  if (!(half_side_m > 0.0) || !std::isfinite(half_side_m)) {
    throw Error("scatter_outliers: half_side_m must be positive, got " +
                std::to_string(half_side_m));
  }
  Rng rng(seed);
  // A partial Fisher-Yates shuffle picks the replaced points.
  std::vector<std::size_t> idx(points.size());
  std::iota(idx.begin(), idx.end(), 0);
  const auto n = static_cast<std::size_t>(share * static_cast<double>(points.size()));
  for (std::size_t k = 0; k < n; ++k) {
    std::swap(idx[k], idx[k + rng.next() % (idx.size() - k)]);
    points[idx[k]] = {rng.uniform(-half_side_m, half_side_m),
                      rng.uniform(-half_side_m, half_side_m)};
  }
  return points;
}

std::vector<Eigen::Vector2d> appear_obstacles(std::vector<Eigen::Vector2d> points, double share,
                                              std::uint64_t seed) {
  check_share(share, "appear_obstacles");
  Rng rng(seed);
  const std::size_t n = points.size();
  const auto run = static_cast<std::size_t>(share * static_cast<double>(n) / 4.0);
  if (run == 0) return points;
  for (std::size_t b = 0; b < 4; ++b) {
    const std::size_t room = n / 4 - run;  // run <= n / 4 since share <= 1
    const std::size_t start = b * n / 4 + (room > 0 ? rng.next() % room : 0);
    const double scale = rng.uniform(0.4, 0.8);
    for (std::size_t k = start; k < start + run; ++k) points[k] *= scale;
  }
  return points;
}

}  // namespace gridloc
