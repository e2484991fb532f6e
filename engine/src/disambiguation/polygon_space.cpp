#include "gridloc/engine/disambiguation/polygon_space.hpp"

#include <cmath>
#include <optional>

#include "gridloc/engine/disambiguation/geodesic.hpp"
#include "gridloc/engine/disambiguation/information.hpp"
#include "gridloc/engine/disambiguation/overlay.hpp"
#include "gridloc/engine/disambiguation/sampling.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

class GeodesicPaths final : public OverlayPaths {
 public:
  GeodesicPaths(const Area& oi, const Eigen::Vector2d& source) : geodesic_(oi, source) {}
  double distance_to(const Eigen::Vector2d& target) const override {
    return geodesic_.distance_to(target);
  }
  std::vector<Eigen::Vector2d> path_to(const Eigen::Vector2d& target) const override {
    return geodesic_.path_to(target);
  }

 private:
  GeodesicDistance geodesic_;
};

/// One overlay; U is computed on first use (UAL only) and kept for the stop's later rounds.
class PolygonStopOverlay final : public StopOverlay {
 public:
  PolygonStopOverlay(Overlay overlay, const PolygonSpaceOptions& options)
      : overlay_(std::move(overlay)), options_(options) {}

  std::vector<Eigen::Vector2d> sample(SamplingAlgorithm algorithm, int count, Rng& rng,
                                      bool& from_useful) const override {
    from_useful = algorithm == SamplingAlgorithm::Ual && region_size(useful()) > 0.0;
    return sample_uniform(from_useful ? useful() : Region{overlay_.oi}, count, rng);
  }
  std::vector<Eigen::Vector2d> lattice(double step) const override {
    return sample_lattice({overlay_.oi}, step);
  }
  double oi_size() const override { return area_size(overlay_.oi); }
  bool oi_contains(const Eigen::Vector2d& p) const override { return covers(overlay_.oi, p); }
  std::unique_ptr<OverlayPaths> paths_from(const Eigen::Vector2d& source) const override {
    return std::make_unique<GeodesicPaths>(overlay_.oi, source);
  }

 private:
  const Region& useful() const {
    if (!useful_) {  // seed 002 §IV-D step 6
      useful_ = useful_region(overlay_.oi, overlay_.internal_edges, options_.range,
                              options_.samples_per_edge);
    }
    return *useful_;
  }

  Overlay overlay_;
  PolygonSpaceOptions options_;
  mutable std::optional<Region> useful_;
};

}  // namespace

void validate(const PolygonSpaceOptions& options) {
  if (!(options.range > 0.0)) {
    throw Error("disambiguation: range must be > 0 (got a non-positive or NaN value)");
  }
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance)) {
    throw Error("disambiguation: tolerance must be a positive finite number");
  }
  if (options.samples_per_edge < 2) throw Error("disambiguation: samples_per_edge must be >= 2");
}

PolygonPlanningSpace::PolygonPlanningSpace(Area free_world, const PolygonSpaceOptions& options)
    : free_world_(std::move(free_world)), options_(options) {
  validate(options_);
}

std::unique_ptr<StopOverlay> PolygonPlanningSpace::overlay(const std::vector<Pose2>& hypotheses,
                                                           const Eigen::Vector2d& anchor) const {
  return std::make_unique<PolygonStopOverlay>(make_overlay(free_world_, hypotheses, anchor),
                                              options_);
}

std::vector<int> PolygonPlanningSpace::classes(const std::vector<Pose2>& hypotheses,
                                               const Eigen::Vector2d& r) const {
  return equivalence_classes(predicted_views(free_world_, hypotheses, r, options_.range),
                             options_.tolerance);
}

std::vector<RangeView> predicted_views(const Area& free_world, const std::vector<Pose2>& hypotheses,
                                       const Eigen::Vector2d& r, double range) {
  std::vector<RangeView> views;
  views.reserve(hypotheses.size());
  for (const Pose2& start : hypotheses) {
    views.push_back(range_view(free_world, to_world(start, r), start.theta, range));
  }
  return views;
}

}  // namespace gridloc
