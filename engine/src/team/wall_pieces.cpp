// The straight walls along a run: split-and-merge, each piece fitted by total least squares
// (seed 003 ch. VI B fits y = m x + b by polyfit, eq. 6.2; an orthogonal regression replaces
// it here because y = m x + b cannot hold a vertical wall and weighs a steep wall's errors
// along the wrong axis).
#include <algorithm>
#include <cmath>
#include <utility>

#include "gridloc/grids/planar.hpp"
#include "scan_runs.hpp"

namespace gridloc::team_detail {
namespace {

/// Run points [begin, end) (indices wrap in a closed run).
struct PieceSpan {
  std::ptrdiff_t begin = 0, end = 0;
};

/// The point of (begin, end - 1) farthest from the chord through the span's ends, and its
/// distance; (-1, 0) for a span of fewer than 3 points.
std::pair<std::ptrdiff_t, double> farthest_from_chord(const ScanRun& run, const PieceSpan& s) {
  std::pair<std::ptrdiff_t, double> best{-1, 0.0};
  if (s.end - s.begin < 3) return best;
  const Eigen::Vector2d& a = run.at(s.begin);
  const Eigen::Vector2d chord = run.at(s.end - 1) - a;
  const double length = chord.norm();
  for (std::ptrdiff_t i = s.begin + 1; i < s.end - 1; ++i) {
    const Eigen::Vector2d v = run.at(i) - a;
    const double d = length > 1e-12 ? std::abs(cross(chord, v)) / length : v.norm();
    if (d > best.second) best = {i, d};
  }
  return best;
}

/// Splits the run until no point lies farther than split_m from its piece's chord.
std::vector<PieceSpan> split_run(const ScanRun& run, double split_m) {
  std::vector<PieceSpan> pending{{0, run.size()}}, pieces;
  while (!pending.empty()) {
    const PieceSpan s = pending.back();
    pending.pop_back();
    const auto [k, d] = farthest_from_chord(run, s);
    if (k < 0 || d <= split_m) {
      pieces.push_back(s);
      continue;
    }
    pending.push_back({s.begin, k});
    pending.push_back({k, s.end});
  }
  std::sort(pieces.begin(), pieces.end(),
            [](const PieceSpan& a, const PieceSpan& b) { return a.begin < b.begin; });
  return pieces;
}

/// Merges adjacent pieces (the last and the first of a closed run too), the straightest joint
/// fit first, while a joint fit's farthest point stays within split_m.
void merge_pieces(const ScanRun& run, std::vector<PieceSpan>& pieces, double split_m) {
  while (pieces.size() >= 2) {
    const std::size_t n = pieces.size();
    const std::size_t pairs = run.closed ? n : n - 1;
    std::size_t best = n;
    double best_distance = split_m;
    for (std::size_t i = 0; i < pairs; ++i) {
      const PieceSpan& a = pieces[i];
      const PieceSpan& b = pieces[(i + 1) % n];
      const std::ptrdiff_t end = i + 1 < n ? b.end : b.end + run.size();
      const double d = fit_piece(run, a.begin, end).max_distance;
      if (d <= best_distance) best = i, best_distance = d;
    }
    if (best == n) return;
    if (best + 1 < n) {
      pieces[best].end = pieces[best + 1].end;
      pieces.erase(pieces.begin() + static_cast<std::ptrdiff_t>(best) + 1);
    } else {  // the seam of a closed run: the last piece takes the first in
      pieces.back().end = pieces.front().end + run.size();
      pieces.erase(pieces.begin());
    }
  }
}

/// Moves the boundary between two adjacent pieces by up to two points, to where the points
/// around it lie nearest their pieces' lines (a split leaves the corner point on either side).
/// `seam`: b's indices lie one turn before a's (the last and first piece of a closed run).
void settle_boundary(const ScanRun& run, PieceSpan& a, PieceSpan& b, std::ptrdiff_t seam) {
  const FittedLine la = fit_piece(run, a.begin, a.end).line;
  const FittedLine lb = fit_piece(run, b.begin, b.end).line;
  const std::ptrdiff_t boundary = a.end, b_end = b.end + seam;
  const std::ptrdiff_t lo = std::max(boundary - 2, std::min(boundary, a.begin + 2));
  const std::ptrdiff_t hi = std::min(boundary + 2, std::max(boundary, b_end - 2));
  const std::ptrdiff_t window_begin = std::max(a.begin, boundary - 2);
  const std::ptrdiff_t window_end = std::min(b_end, boundary + 2);
  auto cost = [&](std::ptrdiff_t cut) {
    double sum = 0.0;
    for (std::ptrdiff_t i = window_begin; i < window_end; ++i) {
      const double d = (i < cut ? la : lb).distance(run.at(i));
      sum += d * d;
    }
    return sum;
  };
  std::ptrdiff_t best = boundary;
  double best_cost = cost(boundary);
  for (std::ptrdiff_t cut = lo; cut <= hi; ++cut) {
    const double c = cost(cut);
    if (c < best_cost) best = cut, best_cost = c;
  }
  a.end = best;
  b.begin = best - seam;
}

void settle_boundaries(const ScanRun& run, std::vector<PieceSpan>& pieces) {
  for (std::size_t i = 0; i + 1 < pieces.size(); ++i) {
    settle_boundary(run, pieces[i], pieces[i + 1], 0);
  }
  if (run.closed && pieces.size() >= 2) {
    settle_boundary(run, pieces.back(), pieces.front(), run.size());
  }
}

}  // namespace

double FittedLine::distance(const Eigen::Vector2d& p) const {
  return std::abs(normal().dot(p - centroid));
}

Eigen::Vector2d FittedLine::project(const Eigen::Vector2d& p) const {
  return centroid + direction.dot(p - centroid) * direction;
}

WallPiece fit_piece(const ScanRun& run, std::ptrdiff_t begin, std::ptrdiff_t end) {
  WallPiece piece;
  piece.begin = begin;
  piece.end = end;
  const auto fit = total_least_squares_line(
      static_cast<std::size_t>(end - begin),
      [&](std::size_t k) { return run.at(begin + static_cast<std::ptrdiff_t>(k)); });
  Eigen::Vector2d direction = fit.direction.normalized();
  if (direction.dot(run.at(end - 1) - run.at(begin)) < 0.0) direction = -direction;
  piece.line.centroid = fit.centroid;
  piece.line.direction = direction;
  for (std::ptrdiff_t i = begin; i < end; ++i) {
    const double d = piece.line.distance(run.at(i));
    piece.sum_squares += d * d;
    piece.max_distance = std::max(piece.max_distance, d);
  }
  return piece;
}

std::vector<WallPiece> fitted_walls(const ScanRun& run, const FeatureOptions& options) {
  std::vector<PieceSpan> pieces = split_run(run, options.split_m);
  merge_pieces(run, pieces, options.split_m);
  settle_boundaries(run, pieces);
  std::vector<WallPiece> walls;
  for (const PieceSpan& s : pieces) {
    WallPiece w = fit_piece(run, s.begin, s.end);
    const double length = std::abs(w.line.direction.dot(run.at(s.end - 1) - run.at(s.begin)));
    if (w.count() >= options.min_wall_points && length >= options.min_wall_m) walls.push_back(w);
  }
  return walls;
}

}  // namespace gridloc::team_detail
