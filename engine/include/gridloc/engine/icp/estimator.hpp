#pragma once
/// Seed 004's robust ICP behind the Estimator interface: scan-to-map matching of a laser scan
/// against the map's contour (IcpEstimator), and the correlation search refined by it
/// (CorrelationIcpEstimator). ICP needs a dense scan: a sonar ring's 16 echoes give no
/// tangents, so both throw for sonar observations.
#include <memory>
#include <string>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/estimator.hpp"
#include "gridloc/engine/icp/map_contour.hpp"
#include "gridloc/engine/icp/robust_icp.hpp"

namespace gridloc {

struct IcpEstimatorOptions {
  IcpOptions icp;
  MapContourOptions contour;
  VerdictOptions verdict;
};

/// Scan-to-map ICP from the window's centre. The window bounds the answer: a pose that ends
/// outside it (half sizes in the map's grid frame, as the correlation search's lattice) is
/// reported with on_window_edge set and verdict "not localized". Estimate:
/// pose = lattice_pose = the ICP pose; score = normalized_score = fit, the share of matching
/// points within IcpOptions::fit_distance_m of a tangent; confidence = fit *
/// sharpness when ICP converged (0 otherwise), distinctness 1 (ICP sees one hypothesis);
/// covariance = ICP's Gauss-Newton covariance; stats.poses_scored = iterations.
class IcpEstimator final : public Estimator {
 public:
  /// Builds the map's contour model; throws gridloc::Error for bad options (ICP, contour,
  /// verdict) or an empty map.
  explicit IcpEstimator(const OccupancyMap& map, IcpEstimatorOptions options = {});

  /// Throws gridloc::Error for a sonar observation, a bad scan or window.
  Estimate estimate(const Observation& observation, const SearchWindow& window) const override;
  std::string name() const override { return "icp"; }

  /// ICP of the observation's scan from `start` (world frame). A valid scan ICP cannot use
  /// (fewer than 3 matching points) gives a not-converged result at `start`, covariance
  /// infinite; a sonar observation or a bad scan throws gridloc::Error.
  IcpResult match(const Observation& observation, const Pose2& start) const;
  /// The Estimate of an ICP result, the window deciding on_window_edge (see the class).
  Estimate to_estimate(const IcpResult& result, const SearchWindow& window) const;

  const IcpEstimatorOptions& options() const { return options_; }
  const MapContour& contour() const { return contour_; }

 private:
  MapContour contour_;
  GridGeometry geometry_;  ///< the map's, for the window's frame
  IcpEstimatorOptions options_;
};

struct CorrelationIcpOptions {
  /// ICP's pose replaces the correlation's only when ICP converged within this distance and
  /// turn of it: farther, ICP slid into another alignment and the correlation's exact search
  /// is trusted.
  double max_shift_m = 0.3;
  double max_turn_rad = 0.0872664625997;  ///< 5 deg
};

/// The correlation search (exact, whole window) followed by ICP from its winner: the search
/// finds the right basin, ICP the sub-cell pose. Confidence, verdict, alternatives and
/// covariance are the correlation's; pose is ICP's when accepted (CorrelationIcpOptions).
class CorrelationIcpEstimator final : public Estimator {
 public:
  CorrelationIcpEstimator(std::shared_ptr<const CorrelationEstimator> correlation,
                          std::shared_ptr<const IcpEstimator> icp,
                          CorrelationIcpOptions options = {});

  Estimate estimate(const Observation& observation, const SearchWindow& window) const override;
  std::string name() const override { return "correlation+icp"; }

 private:
  std::shared_ptr<const CorrelationEstimator> correlation_;
  std::shared_ptr<const IcpEstimator> icp_;
  CorrelationIcpOptions options_;
};

}  // namespace gridloc
