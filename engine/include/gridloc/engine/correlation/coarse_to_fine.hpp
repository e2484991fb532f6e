#pragma once
/// A global search on a coarse copy of the map, refined at the map's own cell (issue 35): the
/// coarse copy's best places, each looked for again in a small window on the fine grids; the
/// best of those is the answer, the distinct others its hypotheses. On a real building's 5 cm
/// map it is several times faster than the exact search of every fine pose, and it is not proven
/// optimal (Estimate::stats.proven_optimal is false): a place the coarse copy scores below
/// its best ones is never looked at closely. The fine estimator alone is the exact mode.
#include <memory>
#include <string>

#include "gridloc/engine/correlation/estimator.hpp"

namespace gridloc {

/// m: coarser cells rank places too poorly for a window of a few cells around them (intel's
/// held-out scan 80: 0.5 m answered 7 m off, `not localized`; 1 m 21 m off, `localized`).
constexpr double kMaxCoarseCell = 0.5;
constexpr int kMaxPlaces = 100;  ///< CorrelationOptions::hypotheses' limit

struct CoarseToFineOptions {
  double resolution = 0.2;  ///< the coarse copy's cell (m); coarser than the fine estimator's
  /// Coarse places refined at most (>= 1): the coarse winner and the distinct places after
  /// it scoring the fine options' second_peak_floor of it, found in its one search whatever
  /// their second_peak (they are what the answer is chosen from, and its hypotheses).
  int places = 8;
  double half_xy_cells = 1.5;     ///< a refinement window's half width, in coarse cells
  double half_theta_steps = 2.0;  ///< its half heading span, in coarse heading steps
  /// The coarse copy is a likelihood field spread over a coarse cell and reaching two, with
  /// free-space evidence (a wall's returns then score near it whichever coarse cell they fall
  /// in); false: the fine estimator's own model at the coarse cell.
  bool field = true;
  /// A distinct refined place (beyond VerdictOptions::ambiguity_xy or _theta) scoring this
  /// share of the best makes the answer `ambiguous` (the exact search's is
  /// VerdictOptions::ambiguity_ratio, 0.97, from simulated sonar). On the held-out scans of
  /// the shared buildings the wrong `localized` answers had a place at 0.71-0.95 of the best
  /// where most right ones had none above 0.87: 0.87 (README, issue 35; 0.9 kept 11 wrong
  /// answers of 240 where 0.87 keeps 7, and one right one fewer).
  double ambiguity_ratio = 0.87;
  /// A refined place apart from the best (beyond CorrelationOptions::distinct_xy or
  /// _theta) but within VerdictOptions::ambiguity_xy and _theta of it, scoring this share of
  /// the best, makes a `localized` answer `not localized`: the scan fits a stretch of
  /// corridor, not a pose (belgioioso's held-out scan 378: a place 0.4 m along it at 0.99
  /// of the best, the answer 1.6 m off).
  double ridge_ratio = 0.97;
  /// A `localized` answer to a laser scan whose returns cross a wall of the map (more than
  /// through_wall_margin_m before their end) this share of its fit or more
  /// (Estimate::through_walls >= through_wall_ratio * normalized_score) is `not localized`:
  /// the scan contradicts the map there nearly as much as it fits it. On 660 held-out scans
  /// of 11 real buildings (seeds 1-6, 10 each) 0.7 turned 10 of the 18 wrong `localized`
  /// answers and 5 of the 502 right ones (README, issue 35); 0: no check.
  double through_wall_ratio = 0.7;
  double through_wall_margin_m = 0.3;  ///< the pose's and the map's blur (m)
  /// Added to the answer's reported covariance (Estimate::covariance, its variances), after
  /// every decision: the error of a real map that the score surface does not see (a map
  /// drawn from a log puts a wall a few centimetres from where another pass sees it). On
  /// the held-out scans of 11 real buildings (seeds 1-3, 257 `localized` answers) 2-sigma
  /// coverage 55.6 -> 86.0 % and the mean NEES of those within 0.3 m 36.8 -> 3.2; checked
  /// on seeds 4-6 (248): 50.8 -> 86.3 %, 39.9 -> 3.1 (README, issue 19). No pose, verdict
  /// or confidence changes; 0 and 0: the score surface's covariance alone.
  double reported_floor_m = 0.03;
  double reported_floor_rad = 0.00872664625997;  ///< 0.5 deg
};

/// Checks the options against the fine cell; throws gridloc::Error naming the field.
void validate(const CoarseToFineOptions& options, double fine_resolution);

/// The bound pyramid depth the refinement windows need (one block over a window, plus one):
/// a fine estimator built only for them (CorrelationOptions::max_bound_depth) precomputes
/// less and holds less memory than one deep enough for the whole map.
int refinement_bound_depth(const CoarseToFineOptions& options, double fine_resolution);

class CoarseToFineEstimator final : public Estimator {
 public:
  /// Builds the coarse copy of `fine`'s map (its options at options.resolution); throws
  /// gridloc::Error for bad options and for a coarse copy over the limits.
  CoarseToFineEstimator(std::shared_ptr<const CorrelationEstimator> fine,
                        CoarseToFineOptions options = {});

  /// `window` is the fine estimator's (its global_window(), or a smaller one): the coarse
  /// search covers the same area and headings on the coarse lattice. Each refinement is the
  /// fine estimator's own search of its window (the winner's with its covariance).
  Estimate estimate(const Observation& observation, const SearchWindow& window) const override;
  std::string name() const override { return "correlation"; }

  const CorrelationEstimator& fine() const { return *fine_; }
  const CorrelationEstimator& coarse() const { return coarse_; }
  const CoarseToFineOptions& options() const { return options_; }

 private:
  /// The coarse copy's window over `window`'s area, at the coarse cell and its heading step.
  SearchWindow coarse_window(const Observation& observation, const SearchWindow& window) const;
  /// The fine search of the window around one coarse place (moved inside the map when the
  /// coarse cell overhangs it).
  Estimate refine_place(const Observation& observation, const Pose2& place,
                        double coarse_step_theta, double fine_step_theta) const;

  std::shared_ptr<const CorrelationEstimator> fine_;
  CoarseToFineOptions options_;
  CorrelationEstimator coarse_;
};

}  // namespace gridloc
