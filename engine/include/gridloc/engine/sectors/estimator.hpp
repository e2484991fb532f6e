#pragma once
/// Seed 000's visibility-sector localization behind the Estimator interface: global (no
/// prior), from one 360-degree scan, on a polygon map.
#include <memory>
#include <string>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/estimator.hpp"
#include "gridloc/engine/sectors/localization.hpp"
#include "gridloc/engine/sectors/visibility_sectors.hpp"

namespace gridloc {

struct SectorEstimatorOptions {
  SectorOptions sectors;
  SectorLocalizationOptions localization;
  /// confidence = exp(-residual / residual_scale_m) when a sector matched (0 otherwise).
  double residual_scale_m = 0.05;
  double localized_confidence = 0.2;  ///< below: not localized
};

/// An estimate with the sector fix behind it (which sector the label matched, the candidates).
struct SectorEstimate {
  Estimate estimate;
  SectorFix fix;
};

/// Estimate: pose = lattice_pose = the sector fix; verdict "ambiguous" when a look-alike pose
/// explains the scan as well (seed 000 §4.1), "not localized" when no sector label matches
/// or the confidence is low; score = normalized_score = confidence; alternatives = the fix's
/// (the winner and its look-alikes, scored like the confidence), second_score the first
/// look-alike's (NaN without one); covariance = the fix's (Gauss-Newton on the readings'
/// distances to their walls); on_window_edge when the pose lies outside the window (the
/// search itself ignores the window: it is global).
class SectorEstimator final : public Estimator {
 public:
  /// Computes the sectors (the costly part: once per map); throws gridloc::Error for bad
  /// options.
  explicit SectorEstimator(const PolygonMap& map, SectorEstimatorOptions options = {});
  /// On sectors computed before (load_sectors, sector_file.hpp) with options.sectors.
  explicit SectorEstimator(SectorMap sectors, SectorEstimatorOptions options = {});

  /// Throws gridloc::Error for a sonar observation or a bad scan.
  Estimate estimate(const Observation& observation, const SearchWindow& window) const override;
  std::string name() const override { return "sectors"; }
  /// estimate() with the fix behind it.
  SectorEstimate locate(const Observation& observation, const SearchWindow& window) const;

  const SectorMap& sectors() const { return sectors_; }
  /// What localize_in_sectors() found for the observation: the sector, the candidates, the
  /// scan's label. Throws as estimate().
  SectorFix fix(const Observation& observation) const;
  /// The Estimate of a fix (what estimate() returns), `elapsed_ms` its time.
  Estimate to_estimate(const SectorFix& fix, const SearchWindow& window, double elapsed_ms) const;

 private:
  SectorMap sectors_;
  SectorEstimatorOptions options_;
};

struct SectorCorrelationOptions {
  /// Half sizes of the correlation's local search around the sector fix: the fix's errors
  /// (a vertex located from a few noisy readings) are centimetres, a wrong vertex tens.
  double half_xy = 0.3;                ///< m
  double half_theta = 0.174532925199;  ///< rad, 10 deg
};

/// The lattice (and the polygon map's rasterization) a sector fix's local search is built on
/// by default (m): the fix is already within centimetres. SectorCorrelationEstimator takes
/// the CorrelationEstimator its caller built, at whatever resolution.
inline constexpr double kSectorRefinementResolution = 0.025;

/// Seed 000's sector fix refined by the correlation engine's exact local search around it
/// (issue 6's optional refinement): the label finds the place without a prior, the search the
/// pose within it. Pose, lattice_pose, score and covariance are the search's; confidence,
/// verdict and ambiguity the sector fix's (the local window cannot see look-alike places).
/// No sector matched: the sector estimator's "not localized", without a search.
class SectorCorrelationEstimator final : public Estimator {
 public:
  /// Throws gridloc::Error for null estimators or non-positive half sizes.
  SectorCorrelationEstimator(std::shared_ptr<const SectorEstimator> sectors,
                             std::shared_ptr<const CorrelationEstimator> correlation,
                             SectorCorrelationOptions options = {});

  Estimate estimate(const Observation& observation, const SearchWindow& window) const override;
  std::string name() const override { return "sectors+correlation"; }
  /// estimate() with the sector fix behind it.
  SectorEstimate locate(const Observation& observation, const SearchWindow& window) const;

 private:
  std::shared_ptr<const SectorEstimator> sectors_;
  std::shared_ptr<const CorrelationEstimator> correlation_;
  SectorCorrelationOptions options_;
};

}  // namespace gridloc
