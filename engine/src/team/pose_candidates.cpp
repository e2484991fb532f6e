#include "gridloc/engine/team/pose_candidates.hpp"

#include <algorithm>
#include <cmath>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/option_checks.hpp"
#include "wall_geometry.hpp"

namespace gridloc {

using team_detail::heading_of;
using team_detail::wall_direction;

Eigen::Vector2d PoseCandidate::position(double t) const {
  return Eigen::Vector2d(pose.x, pose.y) + t * along;
}

void validate(const CandidateOptions& options) {
  constexpr const char* kOwner = "candidate options";
  require_positive(options.angle_tolerance, kOwner, "angle_tolerance");
  require_option(options.features >= 1, kOwner, "features", options.features, "must be >= 1");
  require_non_negative(options.merge_m, kOwner, "merge_m");
  require_non_negative(options.merge_theta, kOwner, "merge_theta");
  require_share(options.min_agreement, kOwner, "min_agreement");
  require_positive(options.agreement_tolerance_m, kOwner, "agreement_tolerance_m");
}

namespace {

/// The turn taking the scan's walls onto the map's: each matched wall's turn, averaged with
/// the length seen of it as weight. Used for the heading instead of eq. 3.27's angle to the
/// corner, which a few millimetres of corner error turn by degrees at 10 cm; the fitted
/// walls' directions rest on all their returns.
double wall_turn(const ScanFeature& feature, const Eigen::Vector2d& env_wall1,
                 const Eigen::Vector2d* env_wall2) {
  const auto turn = [](const Eigen::Vector2d& scan, const Eigen::Vector2d& env) {
    return normalize_angle(heading_of(env) - heading_of(scan));
  };
  const double first = turn(feature.wall1, env_wall1);
  if (!env_wall2) return first;
  const double second = turn(feature.wall2, *env_wall2);
  const double seen1 = (feature.point - feature.saturation1).norm();
  const double seen2 = (feature.saturation2 - feature.point).norm();
  const Eigen::Vector2d mean =
      seen1 * team_detail::unit_at(first) + seen2 * team_detail::unit_at(second);
  return heading_of(mean);
}

/// The robot's pose once the map-frame vector from it to the feature's point is known
/// (eqs. 3.25-3.26) and its heading.
Pose2 place_at(const Eigen::Vector2d& map_point, const Eigen::Vector2d& robot_to_point,
               double heading) {
  const Eigen::Vector2d robot = map_point - robot_to_point;
  return {robot.x(), robot.y(), normalize_angle(heading)};
}

bool same_kind(const ScanFeature& feature, const MapCorner& corner, double tolerance) {
  const bool convex = feature.kind != FeatureKind::ConcaveCorner;
  if (convex != corner.convex()) return false;
  if (feature.kind == FeatureKind::ConvexCornerOneWall) return true;  // its angle is unseen
  return std::abs(feature.free_angle - corner.free_angle) <= tolerance;
}

std::vector<PoseCandidate> corner_candidates(const ScanFeature& feature, int feature_index,
                                             const MapFeatures& map,
                                             const CandidateOptions& options) {
  std::vector<PoseCandidate> candidates;
  for (std::size_t c = 0; c < map.corners.size(); ++c) {
    const MapCorner& corner = map.corners[c];
    if (!same_kind(feature, corner, options.angle_tolerance)) continue;
    const Eigen::Vector2d in = wall_direction(map.walls[corner.in]);
    const Eigen::Vector2d out = wall_direction(map.walls[corner.out]);
    const bool one_wall = feature.kind == FeatureKind::ConvexCornerOneWall;
    const Eigen::Vector2d& seen = feature.seen_wall_arrives ? in : out;
    const Eigen::Vector2d offsets =
        one_wall ? cartesian_offsets(feature, seen, {}) : cartesian_offsets(feature, in, out);
    const double heading =
        one_wall ? wall_turn(feature, seen, nullptr) : wall_turn(feature, in, &out);
    PoseCandidate candidate;
    candidate.pose = place_at(corner.point, offsets, heading);
    candidate.feature = feature_index;
    candidate.map_feature = static_cast<int>(c);
    candidates.push_back(candidate);
  }
  return candidates;
}

/// A wall seen between two saturation points fits on a map wall wherever the seen part lies
/// within it: the foot of the robot's perpendicular at t along the wall, t in
/// [before, length - after], before and after the seen part's extent either side of the foot
/// (ch. III B 1).
std::vector<PoseCandidate> wall_candidates(const ScanFeature& feature, int feature_index,
                                           const MapFeatures& map) {
  const double before = (feature.point - feature.saturation1).dot(feature.wall1);
  const double after = (feature.saturation2 - feature.point).dot(feature.wall1);
  std::vector<PoseCandidate> candidates;
  for (std::size_t w = 0; w < map.walls.size(); ++w) {
    const MapWall& wall = map.walls[w];
    const Eigen::Vector2d direction = wall_direction(wall);
    const double length = (wall.b - wall.a).norm();
    // The foot itself may lie beyond the wall's end (a wall seen from past its corner).
    const double first = before, last = length - after;
    if (last < first) continue;
    const Eigen::Vector2d foot = wall.a + first * direction;
    PoseCandidate candidate;
    candidate.pose = place_at(foot, cartesian_offsets(feature, direction, {}),
                              wall_turn(feature, direction, nullptr));
    candidate.along = direction;
    candidate.length = last - first;
    candidate.feature = feature_index;
    candidate.map_feature = static_cast<int>(w);
    candidates.push_back(candidate);
  }
  return candidates;
}

bool same_placement(const PoseCandidate& a, const PoseCandidate& b,
                    const CandidateOptions& options) {
  if (a.segment() != b.segment()) return false;
  if (std::abs(normalize_angle(a.pose.theta - b.pose.theta)) > options.merge_theta) return false;
  if ((a.position() - b.position()).norm() > options.merge_m) return false;
  return !a.segment() || ((a.position(a.length) - b.position(b.length)).norm() <= options.merge_m);
}

}  // namespace

std::vector<PoseCandidate> feature_candidates(const ScanFeature& feature, int feature_index,
                                              const MapFeatures& map,
                                              const CandidateOptions& options) {
  validate(options);
  if (feature.kind == FeatureKind::Wall) return wall_candidates(feature, feature_index, map);
  return corner_candidates(feature, feature_index, map, options);
}

std::vector<PoseCandidate> robot_candidates(const RangeScan& scan,
                                            const std::vector<ScanFeature>& features,
                                            const MapFeatures& map,
                                            const CandidateOptions& options) {
  validate(options);
  std::vector<PoseCandidate> kept;
  const int used = std::min<int>(options.features, static_cast<int>(features.size()));
  for (int f = 0; f < used; ++f)
    for (PoseCandidate& candidate : feature_candidates(features[f], f, map, options)) {
      if (!candidate.segment() && options.min_agreement > 0.0 &&
          scan_agreement(scan, candidate.pose, map, options.agreement_tolerance_m) <
              options.min_agreement)
        continue;
      const bool duplicate = std::any_of(kept.begin(), kept.end(), [&](const PoseCandidate& k) {
        return same_placement(k, candidate, options);
      });
      if (!duplicate) kept.push_back(candidate);
    }
  return kept;
}

double scan_agreement(const RangeScan& scan, const Pose2& pose, const MapFeatures& map,
                      double tolerance_m) {
  if (scan.ranges.empty()) return 0.0;
  const Eigen::Vector2d origin(pose.x, pose.y);
  std::size_t agreeing = 0;
  for (std::size_t k = 0; k < scan.ranges.size(); ++k) {
    const double wall =
        team_detail::ray_distance(map, origin, team_detail::unit_at(pose.theta + scan.angles[k]));
    const bool saturated = scan.ranges[k] >= scan.max_range;
    if (saturated ? wall >= scan.max_range - tolerance_m
                  : std::abs(wall - scan.ranges[k]) <= tolerance_m)
      ++agreeing;
  }
  return static_cast<double>(agreeing) / static_cast<double>(scan.ranges.size());
}

}  // namespace gridloc
