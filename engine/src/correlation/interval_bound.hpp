#pragma once
// The bound of a branch-and-bound node of several headings (internal;
// BranchAndBoundOptions::heading_intervals): every rigid point's cell at the interval's middle
// heading, widened by as far as the interval turns it, read from the bound pyramid.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "gridloc/engine/correlation/branch_and_bound.hpp"

namespace gridloc::correlation_detail {

class IntervalBound {
 public:
  /// `grids` must hold rigid points (HeadingGrids::points() not null).
  IntervalBound(const Lattice& lattice, const HeadingGrids& grids, const BoundPyramid& pyramid);

  /// Half the angle an interval of 2^a headings spans around its middle heading, in steps.
  static int half_span(int a) { return a == 0 ? 0 : 1 << (a - 1); }
  /// Cells a point at `norm` (m) can move when the heading turns by up to `steps` steps.
  int widening(double norm, int steps) const;
  /// The farthest rigid point from the robot (m) and the number of points.
  double max_norm() const { return points_.max_norm; }
  std::size_t point_count() const { return points_.size(); }

  /// Upper bound of every pose of the 2^block_level block at cell (x, y) over headings
  /// [heading, last_heading].
  double bound(int heading, int last_heading, int x, int y, int block_level) const;

 private:
  template <typename T>
  double sum(const std::vector<const T*>& arc, const std::vector<const T*>& min, int x, int y,
             int block_level, int widen, const HeadingGrids::PointCells& cells, double scale) const;

  const Lattice& lattice_;
  const HeadingGrids& grids_;
  const BoundPyramid& pyramid_;
  const PaddedGrid& global_;  ///< the searched level's padded grid
  const ScanPoints& points_;
  double inv_res_ = 1.0;
  std::ptrdiff_t width_ = 0;
  double slack_ = 0.0;  ///< covers float rounding of the sums
  std::vector<const float*> arc_levels_, min_levels_;
  std::vector<const std::int8_t*> arc8_levels_, min8_levels_;
};

}  // namespace gridloc::correlation_detail
