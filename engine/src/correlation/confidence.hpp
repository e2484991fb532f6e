#pragma once
// How sure the correlation estimator is (internal): the distinct peaks of the scores, the
// covariance around the winner, the readings' agreement and the verdict.
#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"

namespace gridloc::correlation_detail {

/// Heading steps per full turn of `lattice` (2 pi / step) when it covers every heading (its
/// first and last headings lie less than a step apart across +-pi), else 0: neighbourhoods
/// then wrap around +-pi.
double heading_turn(const Lattice& lattice);

/// The neighbourhood of `p` whose poses are not distinct from it, in lattice units.
Exclusion neighbourhood(const LatticePose& p, double res, const Lattice& lattice,
                        const CorrelationOptions& options);

/// Distinct local maxima of the scored poses, best first, up to `max_count`.
std::vector<LatticePose> distinct_peaks(std::vector<LatticePose> scored, double res,
                                        const Lattice& lattice, const CorrelationOptions& options,
                                        std::size_t max_count);

/// Covariance of the pose around the lattice winner `best`, from the scores within k cells.
Eigen::Matrix3d peak_covariance(const LatticePose& best, const Lattice& lattice,
                                const PaddedGrid& global,
                                const std::function<PlacedLocalGrid(int)>& placed_at, int k,
                                double yaw, double temperature = 1.0);
/// The same at each of `temperatures`, from one scoring of the neighbourhood.
std::vector<Eigen::Matrix3d> peak_covariances(const LatticePose& best, const Lattice& lattice,
                                              const PaddedGrid& global,
                                              const std::function<PlacedLocalGrid(int)>& placed_at,
                                              int k, double yaw,
                                              const std::vector<double>& temperatures);
/// `around_winner` (the covariance read around peaks.front(), the winner) widened to the
/// second moment about the winner of a mixture: every peak with that spread and the weight
/// exp((score - best) / temperature) (CorrelationOptions::covariance_spans_peaks). The
/// offsets are from the winner's lattice pose (the refined pose lies within half a cell).
Eigen::Matrix3d spanning_peaks(const Eigen::Matrix3d& around_winner,
                               const std::vector<Hypothesis>& peaks, double temperature);
/// sqrt(var x + var y) of a pose covariance (m): ConfidenceParts::spread_m.
double position_spread(const Eigen::Matrix3d& covariance);

/// Fills the confidence, its parts, the ambiguity flag and the verdict of `e` (the sharpness
/// from e.confidence_parts.spread_m, which the caller sets).
void judge(Estimate& e, bool searched_second, const VerdictOptions& v);

/// Estimate::agreement: the share of `ranges` a noise-free simulation at `pose` reproduces
/// (0 for a pose outside the map).
double reading_agreement(const OccupancyMap& map, const SonarRing& ring,
                         const std::vector<double>& ranges, const std::vector<bool>& rejected,
                         const Pose2& pose);

}  // namespace gridloc::correlation_detail
