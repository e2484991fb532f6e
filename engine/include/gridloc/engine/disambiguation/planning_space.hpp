#pragma once
/// The map side of seed 002's COL and UAL: what the planner asks of a map, so that one loop
/// runs on a polygon map (exact views, Boost.Geometry overlays) and on an occupancy grid
/// (its twin: lattice overlays, predicted scans).
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "gridloc/grids/geometry.hpp"
#include "gridloc/sensors/rng.hpp"

namespace gridloc {

/// Where the random points are drawn: all of OI (COL, §IV-C) or its useful region (UAL, §IV-D).
enum class SamplingAlgorithm { Col, Ual };

/// Shortest paths inside one overlay's OI from one source (seed 002's distance_OI).
class OverlayPaths {
 public:
  virtual ~OverlayPaths() = default;
  /// The length of the shortest path inside OI to `target` (start frame); +inf outside OI.
  virtual double distance_to(const Eigen::Vector2d& target) const = 0;
  /// Its vertices from the source to the target; empty outside OI.
  virtual std::vector<Eigen::Vector2d> path_to(const Eigen::Vector2d& target) const = 0;
};

/// One stop's overlay of the hypotheses still standing (seed 002 §IV steps 3-6).
class StopOverlay {
 public:
  virtual ~StopOverlay() = default;
  /// `count` random points, uniform over OI (COL) or over U (UAL). When U is empty (an
  /// approximation lost it) OI serves and `from_useful` is false.
  virtual std::vector<Eigen::Vector2d> sample(SamplingAlgorithm algorithm, int count, Rng& rng,
                                              bool& from_useful) const = 0;
  /// The points of a lattice of about `step` spacing over OI (start frame).
  virtual std::vector<Eigen::Vector2d> lattice(double step) const = 0;
  /// OI's area (square map units).
  virtual double oi_size() const = 0;
  /// Whether start-frame point p lies in OI.
  virtual bool oi_contains(const Eigen::Vector2d& p) const = 0;
  /// Shortest paths inside OI from `source` (a point of OI).
  virtual std::unique_ptr<OverlayPaths> paths_from(const Eigen::Vector2d& source) const = 0;
};

class PlanningSpace {
 public:
  virtual ~PlanningSpace() = default;
  /// The overlay of `hypotheses` (start poses in the world), OI the component holding
  /// start-frame point `anchor` (the start, or where the robot stands now).
  virtual std::unique_ptr<StopOverlay> overlay(
      const std::vector<Pose2>& hypotheses,
      const Eigen::Vector2d& anchor = Eigen::Vector2d::Zero()) const = 0;
  /// The equivalence class of each hypothesis at start-frame point `r` (0, 1, ... in order of
  /// first appearance): hypotheses whose predicted sensing there is the same share a class.
  virtual std::vector<int> classes(const std::vector<Pose2>& hypotheses,
                                   const Eigen::Vector2d& r) const = 0;
  /// Seed 002's info at `r`: the expected number of `hypotheses` that sensing there rules
  /// out, from the sizes of classes().
  double info(const std::vector<Pose2>& hypotheses, const Eigen::Vector2d& r) const;
};

}  // namespace gridloc
