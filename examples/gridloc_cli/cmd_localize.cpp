// gridloc localize: one localization from a readings file and a prior, as JSON.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "gridloc/engine/correlation/coarse_to_fine.hpp"
#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/correlation/scan_checks.hpp"
#include "gridloc/engine/icp/estimator.hpp"
#include "gridloc/engine/sectors/estimator.hpp"
#include "gridloc/engine/sectors/sector_file.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "limit_options.hpp"
#include "localization_args.hpp"
#include "options.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {
namespace {

constexpr double kAutoCoarse = -1.0;  ///< --coarse left out: chosen from the map's cell

struct LocalizeArgs {
  LocalizationArgs inputs;
  std::string estimator = "correlation";
  std::string sectors;  ///< --sectors: sectors saved by `gridloc sectors --out`
  int repeat = 1;
  /// --coarse: a laser scan's --global search on a coarse copy of the map with cells of this
  /// size (m), its best places refined at the map's cell; 0: the exact search of every pose;
  /// kAutoCoarse (the default): 0.2 m where the map's cell is 0.1 m or finer, else exact.
  double coarse = kAutoCoarse;
  int coarse_places = CoarseToFineOptions{}.places;                      ///< --coarse-places
  double through_wall_ratio = CoarseToFineOptions{}.through_wall_ratio;  ///< --through-wall-ratio
  double reported_floor_m = CoarseToFineOptions{}.reported_floor_m;      ///< --reported-floor-m
  double reported_floor_deg = rad2deg(CoarseToFineOptions{}.reported_floor_rad);  ///< ...-deg
  bool no_edge_check = false;  ///< --no-edge-check: ScanChecks::edge_not_localized off
  double close_second_ratio = ScanChecks{}.close_second_ratio;  ///< --close-second-ratio
  bool json = true;  // --json: JSON is the only output, the flag is accepted
};

/// The estimator kind of --estimator, checked against --repeat, --scan and --prior;
/// gridloc::Error naming the option otherwise.
EstimatorKind checked_kind(const LocalizeArgs& args) {
  require_flag(args.repeat >= 1, "--repeat", args.repeat, "must be >= 1");
  const EstimatorKind kind = parse_estimator_kind(args.estimator);
  if (!args.sectors.empty() && !is_sector_estimator(kind)) {
    throw Error("--sectors needs --estimator sectors or sectors+correlation");
  }
  if (kind != EstimatorKind::Correlation && args.inputs.scan.empty()) {
    const bool sectors = is_sector_estimator(kind);
    throw Error("--estimator " + args.estimator + " needs a laser scan (--scan): " +
                (sectors ? "a sonar ring's echoes give no label (seed 000 needs a 360 degree scan)"
                         : "ICP finds no tangents in a sonar ring's echoes"));
  }
  const bool cell = std::isfinite(args.coarse) && args.coarse <= kMaxCoarseCell &&
                    (args.coarse >= 0.0 || args.coarse == kAutoCoarse);
  if (!cell) {
    throw Error(
        "--coarse must be a cell size in [0, 0.5] m (0: the exact search; leave it out for "
        "the automatic choice)");
  }
  require_flag(args.coarse_places >= 1 && args.coarse_places <= kMaxPlaces, "--coarse-places",
               args.coarse_places, "must lie in [1, 100]");
  require_flag(args.through_wall_ratio >= 0.0 && std::isfinite(args.through_wall_ratio),
               "--through-wall-ratio", args.through_wall_ratio,
               "must be finite and >= 0 (0: no check)");
  require_flag(args.close_second_ratio >= 0.0 && args.close_second_ratio <= 1.0,
               "--close-second-ratio", args.close_second_ratio, "must lie in [0, 1]");
  // Bounded so that their squares stay finite: a floor is centimetres and a degree or two.
  require_flag(args.reported_floor_m >= 0.0 && args.reported_floor_m <= 100.0, "--reported-floor-m",
               args.reported_floor_m, "must lie in [0, 100] m");
  require_flag(args.reported_floor_deg >= 0.0 && args.reported_floor_deg <= 180.0,
               "--reported-floor-deg", args.reported_floor_deg, "must lie in [0, 180] degrees");
  if (kind == EstimatorKind::Icp && args.inputs.whole_map) {
    throw Error(
        "--estimator icp needs --prior: ICP only refines a pose (use correlation+icp with "
        "--global)");
  }
  return kind;
}

/// The sector estimator, or the sector fix refined by a local correlation search with the
/// options of `correlation`, on the polygon map of --map.
std::unique_ptr<Estimator> make_sector_estimator(
    const LocalizeArgs& args, EstimatorKind kind,
    const std::shared_ptr<const CorrelationEstimator>& correlation) {
  // Global: the window (--prior or --global) only sets on_window_edge.
  if (!is_polygon_map_input(args.inputs.map)) {
    throw Error(
        "--estimator " + args.estimator +
        " needs a polygon map (--map with a 'boundary'; maps/README.md, Polygon map format), not " +
        (args.inputs.map == kStdin ? std::string("standard input") : args.inputs.map));
  }
  const PolygonMap polygons = load_polygon_map(map_input_path(args.inputs.map), limits());
  SectorEstimatorOptions options;
  options.sectors.limits = limits();
  // Saved sectors (gridloc sectors --out) instead of computing them again.
  SectorMap computed = args.sectors.empty() ? compute_sectors(polygons, options.sectors)
                                            : load_sectors(input_path(args.sectors, "--sectors"),
                                                           polygons, options.sectors, limits());
  if (kind == EstimatorKind::Sectors) {
    return std::make_unique<SectorEstimator>(std::move(computed), options);
  }
  auto sectors = std::make_shared<const SectorEstimator>(std::move(computed), options);
  // The local search on its own 2.5 cm lattice: the sector fix is already within
  // centimetres (kSectorRefinementResolution).
  CorrelationOptions fine = correlation->options();
  fine.resolution = kSectorRefinementResolution;
  fine.max_bound_depth = 0;  // its windows are its own, not the --prior window's
  auto local = std::make_shared<const CorrelationEstimator>(
      rasterize_polygon_map(polygons, fine.resolution), fine);
  return std::make_unique<SectorCorrelationEstimator>(sectors, local);
}

/// The coarse copy's cell of --coarse for a localization at `fine` m cells, 0 for the exact
/// search: only a laser scan's --global search of the correlation estimator is coarse-to-fine.
double coarse_cell(const LocalizeArgs& args, EstimatorKind kind, double fine) {
  const bool applies =
      kind == EstimatorKind::Correlation && args.inputs.whole_map && !args.inputs.scan.empty();
  if (!applies || args.coarse == 0.0) return 0.0;
  if (args.coarse > 0.0) {
    if (args.coarse <= fine) {
      std::ostringstream message;
      message << "--coarse " << args.coarse << " m must be coarser than the map's " << fine
              << " m cell (0: the exact search)";
      throw Error(message.str());
    }
    return args.coarse;
  }
  constexpr double kAutoCell = 0.2;  // 4 cells of a 5 cm map
  return fine <= 0.5 * kAutoCell ? kAutoCell : 0.0;
}

CoarseToFineOptions coarse_to_fine_options(const LocalizeArgs& args, double coarse) {
  CoarseToFineOptions options;
  options.resolution = coarse;
  options.places = args.coarse_places;
  options.through_wall_ratio = args.through_wall_ratio;
  options.reported_floor_m = args.reported_floor_m;
  options.reported_floor_rad = deg2rad(args.reported_floor_deg);
  return options;
}

/// The estimator of `kind` other than the correlation search itself (null for that one):
/// the sector estimators, ICP on the correlation estimator's map, the search then ICP, or
/// the search on a coarse copy refined at the map's cell (`coarse` > 0).
std::unique_ptr<Estimator> make_estimator(
    const LocalizeArgs& args, EstimatorKind kind,
    const std::shared_ptr<const CorrelationEstimator>& correlation, double coarse) {
  if (is_sector_estimator(kind)) return make_sector_estimator(args, kind, correlation);
  if (coarse > 0.0) {
    return std::make_unique<CoarseToFineEstimator>(correlation,
                                                   coarse_to_fine_options(args, coarse));
  }
  if (kind == EstimatorKind::Correlation) return nullptr;
  auto icp = std::make_shared<const IcpEstimator>(correlation->map());
  if (kind == EstimatorKind::Icp) return std::make_unique<IcpEstimator>(*icp);
  return std::make_unique<CorrelationIcpEstimator>(correlation, icp);
}

/// The last of `repeat` localizations and the times of all of them, sorted (ms).
struct RepeatedEstimate {
  Estimate estimate;
  std::vector<double> ms;
};

RepeatedEstimate estimate_repeatedly(const Estimator& estimator, const Observation& observation,
                                     const SearchWindow& window, int repeat) {
  RepeatedEstimate result;
  for (int i = 0; i < repeat; ++i) {
    result.estimate = estimator.estimate(observation, window);
    result.ms.push_back(result.estimate.stats.elapsed_ms);
  }
  std::sort(result.ms.begin(), result.ms.end());
  return result;
}

/// The output of `localize`: the estimate, the estimator, the correlation estimator's `search`
/// (its strategy, or coarse-to-fine on a coarse copy of `coarse` m cells), the lattice pose,
/// the window, the echo filter's rejections (several firings) and the timing.
nlohmann::json localize_json(const RepeatedEstimate& result, const Estimator& estimator,
                             const Localization& localization, double precompute_ms, int repeat,
                             const std::string& search, double coarse) {
  const Estimate& e = result.estimate;
  const SearchWindow& window = localization.window;
  nlohmann::json out = to_json(e);
  out["estimator"] = estimator.name();
  if (!search.empty()) out["search"] = search;
  if (coarse > 0.0) out["coarse_m"] = coarse;
  out["lattice"] = {{"pose", to_json(e.lattice_pose)}, {"score", e.score}};
  out["window"] = {{"center", to_json(window.center)},
                   {"half_xy", window.half_xy},
                   {"half_theta", window.half_theta},
                   {"step_xy", window.step_xy},
                   {"step_theta", window.step_theta}};
  if (localization.firings > 1) {
    const std::vector<bool>& rejected_mask = localization.observation.rejected;
    nlohmann::json rejected = nlohmann::json::array();
    for (std::size_t i = 0; i < rejected_mask.size(); ++i) {
      if (rejected_mask[i]) rejected.push_back(i);
    }
    out["echo_filter"] = {{"firings", localization.firings}, {"rejected_sonars", rejected}};
  }
  const std::vector<double>& ms = result.ms;
  out["timing"] = {{"median_ms", ms[ms.size() / 2]},
                   {"min_ms", ms.front()},
                   {"precompute_ms", precompute_ms},
                   {"repeat", repeat}};
  return out;
}

void run(const LocalizeArgs& args) {
  const EstimatorKind kind = checked_kind(args);
  double coarse = 0.0;
  // A coarse-to-fine search's fine estimator searches small windows only: a shallow pyramid.
  Localization localization = prepare_localization(args.inputs, [&](CorrelationOptions& options) {
    coarse = coarse_cell(args, kind, options.resolution);
    if (coarse > 0.0) {
      options.max_bound_depth =
          refinement_bound_depth(coarse_to_fine_options(args, coarse), options.resolution);
    }
  });
  const auto t0 = std::chrono::steady_clock::now();
  std::shared_ptr<const CorrelationEstimator> correlation = std::move(localization.estimator);
  const std::unique_ptr<Estimator> chosen = make_estimator(args, kind, correlation, coarse);
  const double precompute_ms =
      localization.precompute_ms +
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const Estimator& estimator = chosen ? *chosen : static_cast<const Estimator&>(*correlation);
  const std::string search = kind != EstimatorKind::Correlation ? ""
                             : coarse > 0.0                     ? "coarse-to-fine"
                                            : to_string(correlation->options().strategy);
  RepeatedEstimate result =
      estimate_repeatedly(estimator, localization.observation, localization.window, args.repeat);
  // A laser scan's windowed answer reports the floor its whole-map answer does (coarse-to-fine
  // adds it itself): a real map's error the score surface does not see.
  // ... and gets its checks (coarse-to-fine checks the walls itself; its windows' edges are
  // the coarse copy's).
  if (localization.observation.scan && kind == EstimatorKind::Correlation && coarse == 0.0) {
    ScanChecks checks;
    checks.through_wall_ratio = args.through_wall_ratio;
    checks.edge_not_localized = !args.no_edge_check;
    // A window's second place nearly as good (whole-map answers have issue 35's rules).
    checks.close_second_ratio = args.inputs.whole_map ? 0.0 : args.close_second_ratio;
    check_scan_answer(result.estimate, correlation->map(), *localization.observation.scan, checks);
    add_reported_floor(result.estimate, args.reported_floor_m, deg2rad(args.reported_floor_deg));
  }
  std::cout << localize_json(result, estimator, localization, precompute_ms, args.repeat, search,
                             coarse)
                   .dump(2)
            << "\n";
}

}  // namespace

void add_localize(CLI::App& app) {
  auto args = std::make_shared<LocalizeArgs>();
  auto* cmd =
      app.add_subcommand("localize", "Localize from sonar readings and a prior; prints JSON");
  args->inputs.add_to(cmd, "no prior: search the whole map and every heading (use --strategy bnb)");
  cmd->add_option(
         "--estimator", args->estimator,
         "correlation (seed 001's search) | icp (seed 004's robust ICP against the "
         "map's contour, from --prior; --scan only) | correlation+icp (the search, "
         "then ICP from its winner; --scan only) | sectors (seed 000's visibility "
         "sectors: global, a polygon --map and a 360 degree --scan) | sectors+correlation (the "
         "sector fix refined by a 2.5 cm local correlation search)")
      ->capture_default_str();
  cmd->add_option("--sectors", args->sectors,
                  "--estimator sectors or sectors+correlation: the sectors saved by `gridloc "
                  "sectors --out DIR` (DIR/sector_map.json) instead of computing them (- reads "
                  "standard input)");
  cmd->add_option("--coarse", args->coarse,
                  "--global with --scan: search a coarse copy of the map with cells of this size "
                  "(m) and refine its best places at the map's cell (fast, not proven optimal); "
                  "0: the exact search of every pose; at most 0.5; default: 0.2 where the map's "
                  "cell is 0.1 m or finer, else exact")
      ->capture_default_str();
  cmd->add_option("--coarse-places", args->coarse_places,
                  "coarse-to-fine: the coarse copy's best places refined at most (its winner and "
                  "the distinct places scoring --second-peak-floor of it)")
      ->capture_default_str();
  cmd->add_option("--through-wall-ratio", args->through_wall_ratio,
                  "with --scan (the correlation search): an answer whose returns cross a wall "
                  "of the map this share of its fit or more is not localized (JSON "
                  "through_walls: that share); 0: no check")
      ->capture_default_str();
  cmd->add_flag("--no-edge-check", args->no_edge_check,
                "with --scan and --prior: an answer whose winner lies on the window's edge "
                "(JSON on_window_edge) stays localized (by default it is not localized)");
  cmd->add_option("--close-second-ratio", args->close_second_ratio,
                  "with --scan and --prior: an answer with a second place farther than 0.3 m "
                  "scoring this share of it, some returns through walls (2 %) and confidence "
                  "below 0.5 is ambiguous (a corridor's repeating doors); 0: no check (nor "
                  "with --through-wall-ratio 0)")
      ->capture_default_str();
  cmd->add_option("--reported-floor-m", args->reported_floor_m,
                  "with --scan (the correlation search): added to the reported position "
                  "standard deviations in quadrature (a real map's error; 0 with "
                  "--reported-floor-deg 0: the score surface's covariance alone)")
      ->capture_default_str();
  cmd->add_option("--reported-floor-deg", args->reported_floor_deg,
                  "with --scan: the same for the heading (degrees)")
      ->capture_default_str();
  cmd->add_option("--repeat", args->repeat, "repeat the localization N times for timing")
      ->capture_default_str();
  // Issue 3's comparison scripts pass --json; localize prints JSON either way.
  cmd->add_flag("--json", args->json, "print JSON (the only output format; accepted for scripts)");
  read_stdin_at_most_once(cmd, {{"--map"}, {"--ring"}, {"--readings"}, {"--scan"}, {"--sectors"}});
  cmd->callback([args] { run(*args); });
}

}  // namespace gridloc::cli
