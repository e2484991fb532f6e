#include "gridloc/engine/disambiguation/grid_geodesic.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <queue>
#include <string>
#include <utility>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The 8 steps: the 4 axis steps first, then the diagonals.
constexpr int kSteps8[8][2] = {{1, 0}, {-1, 0}, {0, 1},  {0, -1},
                               {1, 1}, {1, -1}, {-1, 1}, {-1, -1}};

bool in_oi(const GridGeometry& g, const std::vector<std::uint8_t>& oi, int ix, int iy) {
  return g.contains(ix, iy) && oi[g.index(ix, iy)] != 0;
}

/// Whether the step (dx, dy) from (ix, iy) stays in OI: its end cell, and for a diagonal both
/// cells beside it, so the path never cuts a corner.
bool step_allowed(const GridGeometry& g, const std::vector<std::uint8_t>& oi, int ix, int iy,
                  int dx, int dy) {
  if (!in_oi(g, oi, ix + dx, iy + dy)) return false;
  if (dx == 0 || dy == 0) return true;
  return in_oi(g, oi, ix + dx, iy) && in_oi(g, oi, ix, iy + dy);
}

/// Dijkstra from `source` over the OI cells (ties settled lowest index first).
void run_dijkstra(const GridGeometry& g, const std::vector<std::uint8_t>& oi, int source,
                  std::vector<double>& distance, std::vector<int>& previous) {
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  distance[static_cast<std::size_t>(source)] = 0.0;
  queue.push({0.0, source});
  const double axis = g.resolution, diagonal = g.resolution * std::numbers::sqrt2;
  while (!queue.empty()) {
    const auto [d, i] = queue.top();
    queue.pop();
    if (d > distance[static_cast<std::size_t>(i)]) continue;  // a stale entry
    const int ix = i % g.width, iy = i / g.width;
    for (const auto& step : kSteps8) {
      if (!step_allowed(g, oi, ix, iy, step[0], step[1])) continue;
      const int n = static_cast<int>(g.index(ix + step[0], iy + step[1]));
      const double through = d + (step[0] != 0 && step[1] != 0 ? diagonal : axis);
      if (through < distance[static_cast<std::size_t>(n)]) {
        distance[static_cast<std::size_t>(n)] = through;
        previous[static_cast<std::size_t>(n)] = i;
        queue.push({through, n});
      }
    }
  }
}

}  // namespace

std::pair<int, int> GridGeodesic::step_between(int from, int to) const {
  return {to % grid_.width - from % grid_.width, to / grid_.width - from / grid_.width};
}

GridGeodesic::GridGeodesic(const GridOverlay& overlay, const Eigen::Vector2d& source)
    : grid_(overlay.grid),
      in_oi_(overlay.in_oi),
      distance_(overlay.grid.size(), kInf),
      previous_(overlay.grid.size(), -1) {
  const int start = oi_index(source);
  if (start < 0) {
    throw Error("GridGeodesic: the source (" + std::to_string(source.x()) + ", " +
                std::to_string(source.y()) + ") is not in an OI cell");
  }
  run_dijkstra(grid_, in_oi_, start, distance_, previous_);
}

int GridGeodesic::oi_index(const Eigen::Vector2d& p) const {
  if (!p.allFinite()) return -1;
  const Cell c = grid_.cell_of(p.x() - grid_.origin.x(), p.y() - grid_.origin.y());
  return in_oi(grid_, in_oi_, c.ix, c.iy) ? static_cast<int>(grid_.index(c.ix, c.iy)) : -1;
}

Eigen::Vector2d GridGeodesic::center_of(int index) const {
  return grid_.origin + grid_.cell_center(index % grid_.width, index / grid_.width);
}

double GridGeodesic::distance_to(const Eigen::Vector2d& target) const {
  const int i = oi_index(target);
  return i < 0 ? kInf : distance_[static_cast<std::size_t>(i)];
}

std::vector<Eigen::Vector2d> GridGeodesic::path_to(const Eigen::Vector2d& target) const {
  const int end = oi_index(target);
  if (end < 0 || distance_[static_cast<std::size_t>(end)] == kInf) return {};
  std::vector<int> cells{end};
  for (int i = previous_[static_cast<std::size_t>(end)]; i >= 0;
       i = previous_[static_cast<std::size_t>(i)]) {
    cells.push_back(i);
  }
  std::reverse(cells.begin(), cells.end());
  std::vector<Eigen::Vector2d> path{center_of(cells.front())};
  for (std::size_t k = 1; k + 1 < cells.size(); ++k) {
    if (step_between(cells[k - 1], cells[k]) != step_between(cells[k], cells[k + 1])) {
      path.push_back(center_of(cells[k]));  // a turn: the steps into and out of it differ
    }
  }
  if (cells.size() > 1) path.push_back(center_of(cells.back()));
  return path;
}

}  // namespace gridloc
