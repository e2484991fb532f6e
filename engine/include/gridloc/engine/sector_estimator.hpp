#pragma once
/// Seed 000's visibility-sector localization behind the Estimator interface: global (no
/// prior), from one 360-degree scan, on a polygon map.
#include <string>

#include "gridloc/engine/estimator.hpp"
#include "gridloc/engine/visibility_sectors.hpp"

namespace gridloc {

struct SectorEstimatorOptions {
  SectorOptions sectors;
  SectorLocalizationOptions localization;
  /// confidence = exp(-residual / residual_scale_m) when a sector matched (0 otherwise).
  double residual_scale_m = 0.05;
  double localized_confidence = 0.2;  ///< below: not localized
};

/// Estimate: pose = lattice_pose = the sector fix; verdict "ambiguous" when another sector
/// explains the scan as well (seed 000 §4.1), "not localized" when no sector label matches
/// or the confidence is low; score = normalized_score = confidence; on_window_edge when the
/// pose lies outside the window (the search itself ignores the window: it is global);
/// covariance is not computed (zero).
class SectorEstimator final : public Estimator {
 public:
  /// Computes the sectors (the costly part: once per map); throws gridloc::Error for bad
  /// options.
  explicit SectorEstimator(const PolygonMap& map, SectorEstimatorOptions options = {});

  /// Throws gridloc::Error for a sonar observation or a bad scan.
  Estimate estimate(const Observation& observation, const SearchWindow& window) const override;
  std::string name() const override { return "sectors"; }

  const SectorMap& sectors() const { return sectors_; }
  /// The last fix's details are in the returned Estimate; this gives them all.
  SectorFix fix(const Observation& observation) const;

 private:
  SectorMap sectors_;
  SectorEstimatorOptions options_;
};

}  // namespace gridloc
