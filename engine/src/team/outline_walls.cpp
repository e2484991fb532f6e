// Walls from a traced outline: Douglas-Peucker pieces, short pieces dropped, a line fitted to
// each remaining piece, neighbouring lines intersected.
#include "outline_walls.hpp"

#include "wall_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "gridloc/grids/planar.hpp"

namespace gridloc::detail {
namespace {

std::size_t farthest_from(const Polygon& ring, const Eigen::Vector2d& p) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < ring.size(); ++i) {
    if ((ring[i] - p).squaredNorm() > (ring[best] - p).squaredNorm()) best = i;
  }
  return best;
}

/// Douglas-Peucker on the ring's chain from index `from` forward (wrapping) by `length`
/// points: sets keep[] of the chain's points that stay.
void simplify_chain(const Polygon& ring, std::size_t from, std::size_t length, double tolerance,
                    std::vector<bool>& keep) {
  const std::size_t n = ring.size();
  std::vector<std::pair<std::size_t, std::size_t>> chains{{from, length}};
  while (!chains.empty()) {
    const auto [first, steps] = chains.back();
    chains.pop_back();
    const Eigen::Vector2d &a = ring[first], &b = ring[(first + steps) % n];
    double worst = -1.0;
    std::size_t worst_step = 0;
    for (std::size_t step = 1; step < steps; ++step) {
      const double dist = distance_to_segment(ring[(first + step) % n], a, b);
      if (dist > worst) worst = dist, worst_step = step;
    }
    if (worst <= tolerance) continue;
    keep[(first + worst_step) % n] = true;
    chains.push_back({first, worst_step});
    chains.push_back({(first + worst_step) % n, steps - worst_step});
  }
}

/// The indices Douglas-Peucker keeps on the closed ring, ascending.
std::vector<std::size_t> breakpoints(const Polygon& ring, double tolerance) {
  const std::size_t n = ring.size();
  const std::size_t a = farthest_from(ring, ring[0]);
  const std::size_t b = farthest_from(ring, ring[a]);
  std::vector<bool> keep(n, false);
  keep[a] = keep[b] = true;
  simplify_chain(ring, a, (b + n - a) % n, tolerance, keep);
  simplify_chain(ring, b, (a + n - b) % n, tolerance, keep);
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < n; ++i) {
    if (keep[i]) kept.push_back(i);
  }
  // The anchors were kept unconditionally: each goes where the ring runs straight through it.
  for (std::size_t anchor : {a, b}) {
    const std::size_t m = kept.size();
    if (m <= 3) break;
    const auto at =
        static_cast<std::size_t>(std::lower_bound(kept.begin(), kept.end(), anchor) - kept.begin());
    if (distance_to_segment(ring[anchor], ring[kept[(at + m - 1) % m]], ring[kept[(at + 1) % m]]) <=
        tolerance) {
      kept.erase(kept.begin() + static_cast<std::ptrdiff_t>(at));
    }
  }
  return kept;
}

/// A piece of the ring, points first .. first + steps (wrapping), and the line fitted to it.
struct WallPiece {
  std::size_t first = 0, steps = 0;
  Eigen::Vector2d centre, direction;  ///< a point of the line; unit, the ring's way
};

/// The total-least-squares line through the piece's points (its end points left out when it
/// has at least 4), directed from its first point towards its last.
void fit_line(const Polygon& ring, WallPiece& piece) {
  const std::size_t n = ring.size();
  const std::size_t skip = piece.steps >= 3 ? 1 : 0;
  const FittedLine line = total_least_squares_line(piece.steps + 1 - 2 * skip, [&](std::size_t k) {
    return ring[(piece.first + skip + k) % n];
  });
  piece.centre = line.centroid;
  piece.direction = line.direction;
  const Eigen::Vector2d chord = ring[(piece.first + piece.steps) % n] - ring[piece.first];
  if (piece.direction.dot(chord) < 0.0) piece.direction = -piece.direction;
}

/// Where wall `before` ends and wall `after` starts.
Eigen::Vector2d join(const Polygon& ring, const WallPiece& before, const WallPiece& after) {
  const std::size_t n = ring.size();
  const Eigen::Vector2d& gap_start = ring[(before.first + before.steps) % n];
  Eigen::Vector2d fallback = 0.5 * (gap_start + ring[after.first]);
  const double denom = cross(before.direction, after.direction);
  if (std::abs(denom) <= 1e-6) return fallback;  // near parallel: a step, no corner
  Eigen::Vector2d p =
      line_intersection(before.centre, before.direction, after.centre, after.direction);
  const Eigen::Vector2d& before_start = ring[before.first];
  const Eigen::Vector2d& after_end = ring[(after.first + after.steps) % n];
  if ((p - before_start).dot(before.direction) <= 0.0 ||
      (after_end - p).dot(after.direction) <= 0.0) {
    return fallback;
  }
  return p;
}

/// The vertices where consecutive walls meet (vertex k starts wall k).
Polygon wall_vertices(const Polygon& ring, const std::vector<WallPiece>& walls) {
  Polygon vertices;
  for (std::size_t k = 0; k < walls.size(); ++k) {
    vertices.push_back(join(ring, walls[(k + walls.size() - 1) % walls.size()], walls[k]));
  }
  return vertices;
}

/// The wall whose length between its vertices (m, negative when they run against it) is
/// shortest, and that length.
std::pair<std::size_t, double> shortest_wall(const Polygon& vertices,
                                             const std::vector<WallPiece>& walls) {
  std::pair<std::size_t, double> best{0, std::numeric_limits<double>::infinity()};
  for (std::size_t k = 0; k < walls.size(); ++k) {
    const double l = (vertices[(k + 1) % walls.size()] - vertices[k]).dot(walls[k].direction);
    if (l < best.second) best = {k, l};
  }
  return best;
}

}  // namespace

Polygon fit_walls(const Polygon& dense, double tolerance_m, double min_wall_m) {
  const std::size_t n = dense.size();
  if (n < 3) return {};
  const std::vector<std::size_t> cuts = breakpoints(dense, tolerance_m);
  std::vector<WallPiece> walls;
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    const std::size_t first = cuts[k], last = cuts[(k + 1) % cuts.size()];
    WallPiece piece{first, (last + n - first) % n, {}, {}};
    if (piece.steps == 0) piece.steps = n;  // one cut: the whole ring
    if ((dense[last] - dense[first]).norm() < min_wall_m) continue;
    fit_line(dense, piece);
    walls.push_back(piece);
  }
  while (walls.size() >= 3) {
    Polygon vertices = wall_vertices(dense, walls);
    const auto [k, length] = shortest_wall(vertices, walls);
    if (length >= min_wall_m) return vertices;
    walls.erase(walls.begin() + static_cast<std::ptrdiff_t>(k));  // its neighbours meet
  }
  return {};
}

}  // namespace gridloc::detail
