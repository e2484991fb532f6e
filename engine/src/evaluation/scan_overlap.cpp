#include "gridloc/engine/evaluation/scan_overlap.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

/// Whether `point` lies within `radius_m` of one of `points`.
bool near_any(const Eigen::Vector2d& point, const std::vector<Eigen::Vector2d>& points,
              double radius_m) {
  const double squared = radius_m * radius_m;
  for (const Eigen::Vector2d& other : points)
    if ((other - point).squaredNorm() <= squared) return true;
  return false;
}

std::string band_label(double low, double high) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g-%g", low, high);
  return buf;
}

}  // namespace

double scan_overlap(const std::vector<Eigen::Vector2d>& reference,
                    const std::vector<Eigen::Vector2d>& current, const Pose2& motion,
                    double radius_m) {
  if (current.empty()) return 0.0;
  const double c = std::cos(motion.theta), s = std::sin(motion.theta);
  std::size_t near = 0;
  for (const Eigen::Vector2d& p : current) {
    const Eigen::Vector2d moved(motion.x + c * p.x() - s * p.y(), motion.y + s * p.x() + c * p.y());
    if (near_any(moved, reference, radius_m)) ++near;
  }
  return static_cast<double>(near) / static_cast<double>(current.size());
}

void check_band_edges(const std::vector<double>& edges) {
  double previous = 0.0;
  for (double edge : edges) {
    if (!(edge > previous && edge < 1.0)) {
      std::ostringstream m;
      m << "overlap bands: the edges must rise strictly inside (0, 1), got " << edge << " after "
        << previous;
      throw Error(m.str());
    }
    previous = edge;
  }
}

std::vector<FailureRow> failures_by_band(const std::vector<double>& overlaps,
                                         const std::vector<bool>& failed,
                                         const std::vector<double>& edges) {
  if (overlaps.size() != failed.size())
    throw Error("overlap bands: " + std::to_string(overlaps.size()) + " overlaps but " +
                std::to_string(failed.size()) + " outcomes");
  check_band_edges(edges);
  std::vector<double> bounds{0.0};
  bounds.insert(bounds.end(), edges.begin(), edges.end());
  bounds.push_back(1.0);
  std::vector<FailureRow> rows;
  for (std::size_t b = 0; b + 1 < bounds.size(); ++b)
    rows.push_back({band_label(bounds[b], bounds[b + 1]), 0, 0});
  for (std::size_t k = 0; k < overlaps.size(); ++k) {
    std::size_t band = 0;
    while (band < edges.size() && overlaps[k] >= edges[band]) ++band;
    ++rows[band].pairs;
    if (failed[k]) ++rows[band].failures;
  }
  return rows;
}

}  // namespace gridloc
