#include "gridloc/engine/disambiguation/sampling.hpp"

#include <algorithm>
#include <cmath>

#include "gridloc/engine/disambiguation/overlay.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

constexpr double kMaxLatticePoints = 5e7;  ///< sample_lattice's bound (memory: 16 bytes each)

struct Box {
  Eigen::Vector2d low, high;
};

Box bounding_box(const Area& area) {
  Box box{area.outer.front(), area.outer.front()};
  for (const Eigen::Vector2d& vertex : area.outer) {
    box.low = box.low.cwiseMin(vertex);
    box.high = box.high.cwiseMax(vertex);
  }
  return box;
}

/// The area of `region` that holds the share `u` (in [0, 1)) of the total size.
std::size_t area_at_share(const std::vector<double>& cumulative, double u) {
  const double target = u * cumulative.back();
  const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), target);
  return std::min<std::size_t>(static_cast<std::size_t>(it - cumulative.begin()),
                               cumulative.size() - 1);
}

Eigen::Vector2d point_in(const Area& area, const Box& box, Rng& rng) {
  for (int attempt = 0; attempt < 100000; ++attempt) {
    Eigen::Vector2d p(rng.uniform(box.low.x(), box.high.x()),
                      rng.uniform(box.low.y(), box.high.y()));
    if (covers(area, p)) return p;
  }
  throw Error("sampling: an area covers almost none of its bounding box");
}

}  // namespace

std::vector<Eigen::Vector2d> sample_uniform(const Region& region, int count, Rng& rng) {
  std::vector<double> cumulative;
  double total = 0.0;
  for (const Area& area : region) {  // a ring of fewer than 3 vertices has no area: never drawn
    const double size = area.outer.size() < 3 ? 0.0 : std::max(0.0, area_size(area));
    cumulative.push_back(total += size);
  }
  std::vector<Eigen::Vector2d> points;
  if (region.empty() || !(total > 0.0)) return points;
  std::vector<Box> boxes;
  for (const Area& area : region) {
    boxes.push_back(area.outer.empty() ? Box{} : bounding_box(area));
  }
  points.reserve(static_cast<std::size_t>(std::max(count, 0)));
  for (int i = 0; i < count; ++i) {
    const std::size_t chosen = area_at_share(cumulative, rng.uniform());
    points.push_back(point_in(region[chosen], boxes[chosen], rng));
  }
  return points;
}

std::vector<Eigen::Vector2d> sample_lattice(const Region& region, double step) {
  if (!(step > 0.0) || !std::isfinite(step)) throw Error("sampling: lattice step must be > 0");
  std::vector<Eigen::Vector2d> points;
  for (const Area& area : region) {
    if (area.outer.size() < 3) continue;
    const Box box = bounding_box(area);
    const Eigen::Vector2d cells = (box.high - box.low) / step;
    if (cells.x() * cells.y() > kMaxLatticePoints) {
      throw Error("sampling: a lattice of step " + std::to_string(step) + " over an area of " +
                  std::to_string(area_size(area)) +
                  " square units would hold more than 5e7 points");
    }
    for (double y = box.low.y() + 0.5 * step; y < box.high.y(); y += step) {
      for (double x = box.low.x() + 0.5 * step; x < box.high.x(); x += step) {
        if (covers(area, {x, y})) points.emplace_back(x, y);
      }
    }
  }
  return points;
}

}  // namespace gridloc
