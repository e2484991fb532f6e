#pragma once
/// The sparse local evidence grid: cells relative to the robot centre, already oriented.
#include <vector>

namespace gridloc {

/// Structure of arrays; cell k lies dx[k], dy[k] cells from the robot's cell (the robot
/// centre is the centre of cell (0,0)). Values: occupied > 0, free < 0. Cells are sorted by
/// (dy, dx) so that scoring walks global-grid rows in order.
struct SparseLocalGrid {
  double resolution = 0.1;
  double theta = 0.0;  ///< the heading this grid was built for (grid frame)
  std::vector<int> dx;
  std::vector<int> dy;
  std::vector<float> value;

  std::size_t size() const { return value.size(); }
  /// Largest |dx| or |dy|: how far the grid reaches, in cells.
  int extent() const;
  /// Sum of |value|: the best score this grid could reach on a perfect global grid.
  double mass() const;
};

}  // namespace gridloc
