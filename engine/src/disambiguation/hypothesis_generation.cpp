#include "gridloc/engine/disambiguation/hypothesis_generation.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "gridloc/engine/disambiguation/overlay.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

/// A vertex of the sensed view (viewer frame) and the direction of a wall leaving it.
struct SeenCorner {
  Eigen::Vector2d position;
  Eigen::Vector2d wall;  ///< unit vector along a piece that ends at the vertex
};

std::optional<SeenCorner> first_seen_corner(const RangeView& view) {
  for (const ViewPiece& piece : view.pieces) {
    const Eigen::Vector2d along = piece.segment.b - piece.segment.a;
    if (piece.a_is_vertex) return SeenCorner{piece.segment.a, along.normalized()};
    if (piece.b_is_vertex) return SeenCorner{piece.segment.b, -along.normalized()};
  }
  return std::nullopt;
}

Eigen::Vector2d rotated(const Eigen::Vector2d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

double direction(const Eigen::Vector2d& v) {
  return std::atan2(v.y(), v.x());
}

/// The headings that put the seen wall along one of the walls at `vertex` (ring index i).
std::vector<double> aligning_headings(const Polygon& ring, std::size_t i, const SeenCorner& seen) {
  const Eigen::Vector2d& vertex = ring[i];
  const Eigen::Vector2d& next = ring[(i + 1) % ring.size()];
  const Eigen::Vector2d& previous = ring[(i + ring.size() - 1) % ring.size()];
  const double seen_direction = direction(seen.wall);
  return {normalize_angle(direction(next - vertex) - seen_direction),
          normalize_angle(direction(previous - vertex) - seen_direction)};
}

/// Candidate start poses: the seen corner on every map vertex.
std::vector<Pose2> candidate_starts(const Area& area, const SeenCorner& seen, double heading,
                                    bool rotation) {
  std::vector<Pose2> candidates;
  auto add_ring = [&](const Polygon& ring) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const std::vector<double> headings =
          rotation ? aligning_headings(ring, i, seen) : std::vector<double>{heading};
      for (const double theta : headings) {
        const Eigen::Vector2d start = ring[i] - rotated(seen.position, theta);
        candidates.push_back({start.x(), start.y(), theta});
      }
    }
  };
  add_ring(area.outer);
  for (const Polygon& hole : area.holes) add_ring(hole);
  return candidates;
}

bool pose_less(const Pose2& a, const Pose2& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.theta < b.theta;
}

bool same_pose(const Pose2& a, const Pose2& b, double tolerance) {
  return std::abs(a.x - b.x) <= tolerance && std::abs(a.y - b.y) <= tolerance &&
         std::abs(normalize_angle(a.theta - b.theta)) <= tolerance;
}

std::vector<Pose2> without_duplicates(std::vector<Pose2> poses, double tolerance) {
  std::sort(poses.begin(), poses.end(), pose_less);
  std::vector<Pose2> kept;
  for (const Pose2& pose : poses) {
    if (find_pose(kept, pose, tolerance) < 0) kept.push_back(pose);
  }
  return kept;
}

}  // namespace

void validate(const HypothesisOptions& options) {
  if (!(options.range > 0.0))
    throw Error("hypotheses: range must be > 0 (got a non-positive or NaN value)");
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance)) {
    throw Error("hypotheses: tolerance must be a positive finite number");
  }
}

std::vector<Pose2> matching_starts(const Area& free_world, const RangeView& sensed, double heading,
                                   const HypothesisOptions& options) {
  validate(options);
  const std::optional<SeenCorner> seen = first_seen_corner(sensed);
  if (!seen) {
    throw Error(
        "the view from the start holds no map vertex within range: the places that match it "
        "form a continuum (seed 002 needs a view with a vertex; raise --range or move)");
  }
  std::vector<Pose2> matches;
  for (const Pose2& candidate : candidate_starts(free_world, *seen, heading, options.rotation)) {
    const Eigen::Vector2d at(candidate.x, candidate.y);
    if (!covers(free_world, at)) continue;
    const RangeView view = range_view(free_world, at, candidate.theta, options.range);
    if (same_view(view, sensed, options.tolerance)) matches.push_back(candidate);
  }
  return without_duplicates(std::move(matches), options.tolerance);
}

std::vector<Pose2> start_hypotheses(const Area& free_world, const Pose2& true_start,
                                    const HypothesisOptions& options) {
  validate(options);
  const Eigen::Vector2d at(true_start.x, true_start.y);
  if (!covers(free_world, at)) {
    throw Error("the start (" + std::to_string(at.x()) + ", " + std::to_string(at.y()) +
                ") lies outside the map's free space");
  }
  const RangeView sensed = range_view(free_world, at, true_start.theta, options.range);
  return matching_starts(free_world, sensed, true_start.theta, options);
}

int find_pose(const std::vector<Pose2>& hypotheses, const Pose2& pose, double tolerance) {
  for (std::size_t i = 0; i < hypotheses.size(); ++i) {
    if (same_pose(hypotheses[i], pose, tolerance)) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace gridloc
