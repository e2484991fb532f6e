#include "gridloc/sensors/sonar_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "canvas.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

using detail::Canvas;

/// Angular samples across a cone so that neighbouring samples at range rho are at most a
/// quarter cell apart.
int angular_samples(double cone, double rho, double res) {
  return std::max(2, static_cast<int>(std::ceil(cone * rho / (0.25 * res))) + 1);
}

/// Per-thread buffers of add_cone, reused: a grid draws 14 cones, a search many grids.
struct ConeScratch {
  std::vector<int> arc, free_cells;
  std::vector<double> ux, uy;
  static ConeScratch& for_this_thread() {
    thread_local ConeScratch scratch;
    return scratch;
  }
};

void add_cone(Canvas& canvas, const SonarSpec& s, double d, double theta,
              const Eigen::Vector2d& centre, const SonarModelOptions& options) {
  // References taken once: thread-local lookups stay out of the loops.
  ConeScratch& scratch = ConeScratch::for_this_thread();
  std::vector<int>& arc = scratch.arc;
  std::vector<int>& free_cells = scratch.free_cells;
  std::vector<double>& ux = scratch.ux;
  std::vector<double>& uy = scratch.uy;
  const std::uint32_t pass_arc = canvas.new_pass(), pass_free = canvas.new_pass();
  const double res = canvas.resolution();
  // seed 001 eq. (3), in this project's axes (x forward): sensor at (r, beta + theta), axis
  // at epsilon + theta.
  const double sx = centre.x() + s.radius * std::cos(s.bearing + theta);
  const double sy = centre.y() + s.radius * std::sin(s.bearing + theta);
  const double axis = s.heading + theta;
  const bool echo = d < s.max_range;
  const double free_limit = echo ? d : s.max_range;

  // Arc: for each layer (the echo range, and +-arc_depth cells around it when asked), the
  // ordered distinct cells along the arc, thinned to an 8-connected chain by dropping the
  // corner cell of every 4-connected step.
  arc.clear();
  if (echo) {
    const double depth = options.arc_depth_cells * res;
    const int layers = depth > 0.0 ? 1 : 0;
    for (int layer = -layers; layer <= layers; ++layer) {
      const double rho = d + layer * depth;
      const int m = angular_samples(s.cone, rho, res);
      const std::size_t first = arc.size();
      for (int k = 0; k < m; ++k) {
        const double a = axis - 0.5 * s.cone + s.cone * k / (m - 1);
        const int idx = canvas.cell_index(sx + rho * std::cos(a), sy + rho * std::sin(a));
        // Every touched cell is excluded from the free sector; a cell joins the arc once.
        if (!canvas.mark(idx, pass_arc)) continue;
        while (arc.size() >= first + 2 && canvas.adjacent8(idx, arc[arc.size() - 2])) {
          arc.pop_back();
        }
        arc.push_back(idx);
      }
    }
    const float v = 1.0f / static_cast<float>(arc.size());
    for (int idx : arc) canvas.add_arc(idx, v);
  }

  // Free sector: cells swept by the cone before the arc, sampled every half cell along
  // and across the cone (directions computed once, thinned out at short range).
  free_cells.clear();
  const double step = 0.5 * res;
  const int m_max = std::max(2, static_cast<int>(std::ceil(s.cone * free_limit / step)) + 1);
  ux.resize(static_cast<std::size_t>(m_max));
  uy.resize(static_cast<std::size_t>(m_max));
  for (int k = 0; k < m_max; ++k) {
    const double a = axis - 0.5 * s.cone + s.cone * k / (m_max - 1);
    ux[k] = std::cos(a);
    uy[k] = std::sin(a);
  }
  for (double rho = 0.0; rho < free_limit; rho += step) {
    const int m = std::max(2, static_cast<int>(std::ceil(s.cone * rho / step)) + 1);
    const int stride = std::max(1, (m_max - 1) / (m - 1));
    for (int k = 0;; k = std::min(k + stride, m_max - 1)) {
      const int idx = canvas.cell_index(sx + rho * ux[k], sy + rho * uy[k]);
      if (!canvas.marked(idx, pass_arc) && canvas.mark(idx, pass_free)) free_cells.push_back(idx);
      if (k == m_max - 1) break;
    }
  }
  if (!free_cells.empty()) {
    const float v = -1.0f / static_cast<float>(free_cells.size());
    for (int idx : free_cells) canvas.add_free(idx, v);
  }
}

void check_resolution(double resolution) {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw Error("local grid resolution must be positive, got " + std::to_string(resolution));
  }
}

}  // namespace

SparseLocalGrid rasterize_oriented(const SonarRing& ring, const std::vector<double>& ranges,
                                   double theta, double resolution, const Eigen::Vector2d& centre,
                                   const SonarModelOptions& options,
                                   const std::vector<bool>& rejected) {
  check_resolution(resolution);
  std::size_t active = 0;  // sonars that draw a cone: the footprint's N
  Canvas& canvas = Canvas::for_this_thread(
      (ring.reach() + 2 * resolution + centre.norm()) / resolution, 2, centre, resolution);
  for (std::size_t i = 0; i < ring.sonars.size(); ++i) {
    if (i < rejected.size() && rejected[i]) continue;  // an echo filter rejected it: no evidence
    add_cone(canvas, ring.sonars[i], ranges[i], theta, centre, options);
    ++active;
  }
  // Footprint: its n cells share -N/n, overriding the cones (the robot stands there).
  if (ring.footprint.polygon.size() >= 3) {
    const double c = std::cos(theta), s = std::sin(theta);
    std::vector<int> cells;
    // Only cells within the footprint's circumscribed circle can lie inside it.
    double radius = 0.0;
    for (const auto& p : ring.footprint.polygon) radius = std::max(radius, p.norm());
    const int half = static_cast<int>(std::ceil((radius + centre.norm()) / resolution)) + 1;
    for (int cy = -half; cy <= half; ++cy) {
      for (int cx = -half; cx <= half; ++cx) {
        const double wx = cx * resolution - centre.x(), wy = cy * resolution - centre.y();
        // Cell centre back into the robot frame.
        const Eigen::Vector2d p(c * wx + s * wy, -s * wx + c * wy);
        if (footprint_contains(ring.footprint, p)) cells.push_back(canvas.index_of_cell(cx, cy));
      }
    }
    const float v = -static_cast<float>(active) / static_cast<float>(cells.size());
    for (int idx : cells) {
      canvas.set(idx, 0.0f, v);
    }
  }
  return canvas.collect(theta);
}

SparseLocalGrid rasterize_turned(const SonarRing& ring, const std::vector<double>& ranges,
                                 double theta, double resolution, const Eigen::Vector2d& centre,
                                 const SonarModelOptions& options,
                                 const std::vector<bool>& rejected) {
  const SparseLocalGrid upright =
      rasterize_oriented(ring, ranges, 0.0, resolution, Eigen::Vector2d::Zero(), options, rejected);
  Canvas& canvas = Canvas::for_this_thread(
      (ring.reach() + 3 * resolution + centre.norm()) / resolution, 2, centre, resolution);
  const double c = std::cos(theta), s = std::sin(theta);
  // Write into the arc/free layers by sign so that "later value wins" holds per cell.
  for (std::size_t k = 0; k < upright.size(); ++k) {
    const double x = upright.dx[k] * resolution, y = upright.dy[k] * resolution;
    const int idx = canvas.cell_index(centre.x() + c * x - s * y, centre.y() + s * x + c * y);
    const float v = upright.value[k];
    canvas.set(idx, v > 0.0f ? v : 0.0f, v < 0.0f ? v : 0.0f);
  }
  return canvas.collect(theta);
}

SparseLocalGrid rasterize(const SonarRing& ring, const std::vector<double>& ranges, double theta,
                          double resolution, LocalModel model, const Eigen::Vector2d& centre,
                          const SonarModelOptions& options, const std::vector<bool>& rejected) {
  return model == LocalModel::Oriented
             ? rasterize_oriented(ring, ranges, theta, resolution, centre, options, rejected)
             : rasterize_turned(ring, ranges, theta, resolution, centre, options, rejected);
}

}  // namespace gridloc
