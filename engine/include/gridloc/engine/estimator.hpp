#pragma once
/// The interface every pose estimator implements, so callers and the evaluation can swap them.
#include <string>
#include <vector>

#include <optional>

#include "gridloc/engine/estimate.hpp"
#include "gridloc/sensors/range_scan.hpp"
#include "gridloc/sensors/sonar_ring.hpp"

namespace gridloc {

/// One observation from the robot standing still: either a range per sonar of the ring (m),
/// in ring order, a sonar's max_range meaning no echo; or, when `scan` is set, a laser or IR
/// scan (then `ranges` must be empty); or `points`. `rejected` (empty = none) marks sonars an echo
/// filter rejected (filter_echoes): they contribute nothing, unlike a sonar without echo, whose
/// cone says "free"; every reading rejected is an error.
struct Observation {
  std::vector<double> ranges;
  std::optional<RangeScan> scan = std::nullopt;
  std::vector<bool> rejected = {};  ///< one flag per sonar, or empty
  /// The ring `ranges` belong to when it is not the estimator's own: a drive fused by
  /// fuse_firings (each firing's sonars re-mounted in the latest pose's frame). Its reach must
  /// lie within the estimator's (CorrelationOptions::reach_m). Unset: the estimator's ring.
  std::optional<SonarRing> ring = std::nullopt;
  /// A scan given as rigid points in the robot frame instead of `scan` (then `ranges` and
  /// `scan` must be empty): a laser mounted off the robot's centre or a drive of scans fused
  /// by fuse_scans. Correlation only; its points reach at most the estimator's reach.
  std::optional<ScanPoints> points = std::nullopt;
};

/// The estimators a caller can choose by name (the command line's --estimator and
/// --estimators, the evaluation's configurations, the relations' matchers).
enum class EstimatorKind {
  Correlation,     ///< the correlation search (CorrelationEstimator, seed 001)
  Icp,             ///< robust ICP from the prior (IcpEstimator, match_scans; seed 004)
  CorrelationIcp,  ///< the correlation search, then ICP from its winner
  Sectors,         ///< visibility sectors on a polygon map (SectorEstimator; seed 000)
  /// the sector fix refined by the correlation's local search (SectorCorrelationEstimator)
  SectorsCorrelation,
};

/// "correlation", "icp", "correlation+icp", "sectors" or "sectors+correlation".
std::string to_string(EstimatorKind kind);
/// Whether the kind localizes on a polygon map by visibility sectors (sectors,
/// sectors+correlation): global, from a 360 degree scan.
bool is_sector_estimator(EstimatorKind kind);
/// The kind to_string() names; gridloc::Error listing the choices otherwise.
EstimatorKind parse_estimator_kind(const std::string& name);

class Estimator {
 public:
  virtual ~Estimator() = default;
  /// Best pose for `observation` inside `window`; throws gridloc::Error for bad input.
  virtual Estimate estimate(const Observation& observation, const SearchWindow& window) const = 0;
  virtual std::string name() const = 0;
};

}  // namespace gridloc
