// The heading-interval bound of branch and bound (BranchAndBoundOptions::heading_intervals).
#include "interval_bound.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

// The bound must be summed as exactly as score() sums (see branch_and_bound.cpp).
#if defined(__FAST_MATH__)
#error "interval_bound.cpp needs IEEE floating point: build without -ffast-math"
#endif

namespace gridloc::correlation_detail {

IntervalBound::IntervalBound(const Lattice& lattice, const HeadingGrids& grids,
                             const BoundPyramid& pyramid)
    : lattice_(lattice),
      grids_(grids),
      pyramid_(pyramid),
      global_(*grids.level().global),
      points_(*grids.points()) {
  inv_res_ = 1.0 / global_.grid.geometry.resolution;
  width_ = global_.grid.width();
  // Level 0 as floats: none when the grid keeps int8 cells alone. sum() never reads it (a
  // heading interval widens its block: level >= 2).
  arc_levels_.push_back(global_.has_floats() ? global_.arc_view().data() : nullptr);
  min_levels_.push_back(global_.has_floats() ? global_.grid.cells.data() : nullptr);
  for (int h = 1; h <= pyramid_.depth(); ++h) {
    arc_levels_.push_back(pyramid_.arc_max[static_cast<std::size_t>(h)].cells.data());
    min_levels_.push_back(pyramid_.grid_min[pyramid_.min_level(h)].cells.data());
  }
  if (pyramid_.has_int8()) {  // level 0 is the padded grid's own int8 copy
    arc8_levels_.push_back(global_.arc_view8().data());
    min8_levels_.push_back(global_.grid8.data());
  }
  for (std::size_t h = 1; h < pyramid_.arc_max8.size(); ++h) {
    arc8_levels_.push_back(pyramid_.arc_max8[h].data());
    min8_levels_.push_back(pyramid_.grid_min8[pyramid_.min_level(static_cast<int>(h))].data());
  }
  double mass = 0.0;
  for (float w : points_.weight) mass += std::abs(static_cast<double>(w));
  slack_ = (static_cast<double>(points_.size()) + 4.0) * std::ldexp(1.0, -24) * mass *
           std::max(1.0f, pyramid_.abs_max);
}

int IntervalBound::widening(double norm, int steps) const {
  if (steps == 0) return 0;
  return static_cast<int>(norm * steps * std::abs(lattice_.step_theta) * inv_res_ + 1e-6) + 1;
}

double IntervalBound::bound(int heading, int last_heading, int x, int y, int block_level) const {
  const int ref = (heading + last_heading) / 2;
  const int widen = widening(points_.max_norm, std::max(ref - heading, last_heading - ref));
  const auto& cells = grids_.point_cells(ref);
  const double scale = pyramid_.int8_scale;  // int8 levels hold values times it
  const double sums =
      pyramid_.float_levels
          ? sum(arc_levels_, min_levels_, x, y, block_level, widen, cells, 1.0)
          : sum(arc8_levels_, min8_levels_, x, y, block_level, widen, cells, scale) / scale;
  return sums + slack_;
}

/// The bound's sums over grids of T holding values times `scale`: every point's cell
/// widened by `widen` cells on every side.
template <typename T>
double IntervalBound::sum(const std::vector<const T*>& arc, const std::vector<const T*>& min, int x,
                          int y, int block_level, int widen, const HeadingGrids::PointCells& cells,
                          double scale) const {
  const int level = std::bit_width(static_cast<unsigned>((1 << block_level) + 2 * widen - 1));
  const double free_weight =
      points_.size() > points_.hit_count ? points_.weight[points_.hit_count] : 0.0;
  double positive = 0.0, negative = 0.0;
  if (level > pyramid_.depth()) {  // wider than any level: the whole grid's extremes
    positive =
        static_cast<double>(cells.hit_offset.size()) * std::max(pyramid_.arc_max_all, 0.0f) * scale;
    negative = static_cast<double>(cells.free_offset.size()) *
               std::min(pyramid_.grid_min_all, 0.0f) * scale;
    return positive + free_weight * negative;
  }
  // Pooled cells cover [x, x + 2^level): read `widen` cells before the block.
  const T* arc_level = arc[static_cast<std::size_t>(level)];
  const T* min_level = min[static_cast<std::size_t>(level)];
  const int bx = x + global_.pad - widen, by = y + global_.pad - widen;
  if (x >= widen && y >= widen) {  // every read inside the padded grid: flat offsets
    const std::ptrdiff_t base = static_cast<std::ptrdiff_t>(by) * width_ + bx;
    for (std::ptrdiff_t o : cells.hit_offset) {
      positive += std::max(static_cast<float>(arc_level[base + o]), 0.0f);
    }
    for (std::ptrdiff_t o : cells.free_offset) {
      negative += std::min(static_cast<float>(min_level[base + o]), 0.0f);
    }
  } else {  // near the map's edge: a read before the padded grid starts at its edge
    auto at = [&](int cx, int cy) {  // (dropping cells that do not exist)
      return static_cast<std::ptrdiff_t>(std::max(0, by + cy)) * width_ + std::max(0, bx + cx);
    };
    for (std::size_t k = 0; k < cells.hit_x.size(); ++k) {
      positive += std::max(static_cast<float>(arc_level[at(cells.hit_x[k], cells.hit_y[k])]), 0.0f);
    }
    for (std::size_t k = 0; k < cells.free_x.size(); ++k) {
      negative +=
          std::min(static_cast<float>(min_level[at(cells.free_x[k], cells.free_y[k])]), 0.0f);
    }
  }
  return positive + free_weight * negative;
}

}  // namespace gridloc::correlation_detail
