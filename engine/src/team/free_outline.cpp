// The free space's outline: the unit cell edges between a Free cell and a cell that is not,
// linked at the cell corners into closed rings, each edge given by its midpoint.
#include "free_outline.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace gridloc::detail {
namespace {

// Directions of a unit edge between cell corners: +x, +y, -x, -y; d + 1 (mod 4) turns left.
constexpr std::array<int, 4> kStepX{1, 0, -1, 0};
constexpr std::array<int, 4> kStepY{0, 1, 0, -1};

/// Which cells are Free and in a 4-connected region of at least `min_cells` cells.
std::vector<std::uint8_t> free_mask(const OccupancyMap& map, int min_cells) {
  const GridGeometry& g = map.geometry;
  std::vector<std::uint8_t> mask(g.size(), 0);
  for (std::size_t i = 0; i < g.size(); ++i) mask[i] = map.cells[i] == CellState::Free;
  std::vector<std::uint8_t> seen(g.size(), 0);
  std::vector<std::size_t> region;
  for (std::size_t start = 0; start < g.size(); ++start) {
    if (!mask[start] || seen[start]) continue;
    region.assign(1, start);
    seen[start] = 1;
    for (std::size_t k = 0; k < region.size(); ++k) {  // breadth first; region grows
      const int ix = static_cast<int>(region[k] % g.width);
      const int iy = static_cast<int>(region[k] / g.width);
      for (int d = 0; d < 4; ++d) {
        const int nx = ix + kStepX[d], ny = iy + kStepY[d];
        if (!g.contains(nx, ny)) continue;
        const std::size_t n = g.index(nx, ny);
        if (mask[n] && !seen[n]) seen[n] = 1, region.push_back(n);
      }
    }
    if (region.size() < static_cast<std::size_t>(min_cells)) {
      for (std::size_t i : region) mask[i] = 0;
    }
  }
  return mask;
}

/// The boundary edges on the (width + 1) x (height + 1) grid of cell corners: bit d of a
/// corner is set when an edge leaves it in direction d with a free cell on its left.
class CornerEdges {
 public:
  CornerEdges(const GridGeometry& g, const std::vector<std::uint8_t>& mask)
      : width_(g.width + 1), bits_(static_cast<std::size_t>(g.width + 1) * (g.height + 1), 0) {
    const auto is_free = [&](int ix, int iy) {
      return g.contains(ix, iy) && mask[g.index(ix, iy)];
    };
    for (int iy = 0; iy < g.height; ++iy) {
      for (int ix = 0; ix < g.width; ++ix) {
        if (!is_free(ix, iy)) continue;
        if (!is_free(ix, iy - 1)) add(ix, iy, 0);          // bottom side, +x
        if (!is_free(ix + 1, iy)) add(ix + 1, iy, 1);      // right side, +y
        if (!is_free(ix, iy + 1)) add(ix + 1, iy + 1, 2);  // top side, -x
        if (!is_free(ix - 1, iy)) add(ix, iy + 1, 3);      // left side, -y
      }
    }
  }
  int width() const { return width_; }
  std::size_t corners() const { return bits_.size(); }
  bool has(std::size_t corner, int d) const { return bits_[corner] >> d & 1; }

 private:
  void add(int x, int y, int d) { bits_[static_cast<std::size_t>(y) * width_ + x] |= 1 << d; }
  int width_;
  std::vector<std::uint8_t> bits_;
};

/// The direction to leave `corner` by after arriving in direction d: the leftmost edge there,
/// which keeps regions that touch at a corner apart (each arrival at such a corner has its own
/// left turn, so the choice pairs arrivals with departures one to one).
int next_direction(const CornerEdges& edges, std::size_t corner, int d) {
  for (int turn : {1, 0, 3}) {
    if (edges.has(corner, (d + turn) % 4)) return (d + turn) % 4;
  }
  return -1;  // unreachable: every arrival at a corner has a departure
}

/// A point of the outline in half cells of the grid frame (exact integers).
struct HalfCellPoint {
  long x = 0, y = 0;
};

/// The midpoints of the ring's unit edges from edge (start, d0) on, marking the edges used:
/// the marching-squares contour of the Free mask (between each free cell's centre and its
/// non-free neighbour's), which cuts a step's corner where the edges themselves zigzag.
std::vector<HalfCellPoint> trace_midpoints(const CornerEdges& edges, std::size_t start, int d0,
                                           std::vector<std::uint8_t>& used) {
  std::vector<HalfCellPoint> midpoints;
  const auto w = static_cast<std::ptrdiff_t>(edges.width());
  std::size_t corner = start;
  int d = d0;
  do {
    used[corner] |= 1 << d;
    const auto x = static_cast<long>(corner % edges.width());
    const auto y = static_cast<long>(corner / edges.width());
    midpoints.push_back({2 * x + kStepX[d], 2 * y + kStepY[d]});
    corner =
        static_cast<std::size_t>(static_cast<std::ptrdiff_t>(corner) + kStepX[d] + kStepY[d] * w);
    d = next_direction(edges, corner, d);
  } while (corner != start || d != d0);
  return midpoints;
}

/// The points in world coordinates (m).
Polygon to_world(const GridGeometry& g, const std::vector<HalfCellPoint>& points) {
  Polygon ring;
  ring.reserve(points.size());
  for (const HalfCellPoint& at : points) {
    const Pose2 p = g.to_world_frame({0.5 * static_cast<double>(at.x) * g.resolution,
                                      0.5 * static_cast<double>(at.y) * g.resolution, 0.0});
    ring.push_back({p.x, p.y});
  }
  return ring;
}

}  // namespace

std::vector<Polygon> free_outline(const OccupancyMap& map, int min_region_cells) {
  const GridGeometry& g = map.geometry;
  const CornerEdges edges(g, free_mask(map, min_region_cells));
  std::vector<std::uint8_t> used(edges.corners(), 0);
  std::vector<Polygon> rings;
  for (std::size_t corner = 0; corner < edges.corners(); ++corner) {
    for (int d = 0; d < 4; ++d) {
      if (edges.has(corner, d) && !(used[corner] >> d & 1)) {
        rings.push_back(to_world(g, trace_midpoints(edges, corner, d, used)));
      }
    }
  }
  return rings;
}

}  // namespace gridloc::detail
