#pragma once
/// The Localizer: the facade a navigation stack links (issues 13, 34). Built once from a map
/// and the sonar ring or a laser, it is fed odometry and sonar firings or scans as the robot
/// drives and keeps the current Estimate: each observation is fused with the drive behind it
/// (fuse_firings, fuse_scans) and matched by the exact correlation search: globally at
/// first, then in a window around each tracked place, carried along by odometry with a
/// covariance that grows while nothing confirms it. Each place is weighted by every
/// observation since it entered (hypothesis_weights.hpp); a re-search after a loss runs in
/// slices across updates (sliced_search.hpp) and its places enter with a small share; a
/// `localized` answer must agree with the last one and the odometry (jump_gate.hpp).
#include <Eigen/Core>
#include <mutex>
#include <numbers>
#include <optional>
#include <shared_mutex>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/localizer/hypothesis_set.hpp"
#include "gridloc/engine/localizer/hypothesis_weights.hpp"
#include "gridloc/engine/localizer/jump_gate.hpp"
#include "gridloc/engine/localizer/place_prior.hpp"
#include "gridloc/engine/localizer/sliced_search.hpp"
#include "gridloc/sensors/drive_fusion.hpp"

namespace gridloc {

struct LocalizerOptions {
  /// The search; its reach_m is raised to cover the ring along the whole drive window. Its
  /// second_peak_floor is 0: a sonar tracker seeds places from peaks well below the best too.
  /// A laser's estimator raises a floor of 0 to min(0.8, drop_ratio, split_ratio), and its
  /// coarse copy's searches use min(drop_ratio, split_ratio): every place a reader keeps is
  /// still found, in one search (the same tracks on the shared buildings, the updates 13 %
  /// and the first one 10-25x faster).
  CorrelationOptions correlation = [] {
    CorrelationOptions options;
    options.second_peak_floor = 0.0;
    return options;
  }();
  /// Which past firings join the latest (distance, turn, count).
  DriveWindowOptions drive;
  /// The window around a prior spans this many standard deviations of its covariance...
  double prior_sigmas = 3.0;
  /// ...grown by the odometry's error since the prior: this share of the distance driven...
  double odometry_error_per_m = 0.02;
  /// ...and this heading error per metre driven (rad/m; 1 deg/m)...
  double odometry_turn_error_per_m = 0.017453292519943295;
  /// ...and this share of each turn (rad/rad).
  double odometry_turn_error_per_rad = 0.02;
  double min_half_xy_m = 0.3;    ///< the window's half side is at least this...
  double max_half_xy_m = 2.0;    ///< ...and at most this (a place unconfirmed longer is kept)
  double min_half_theta = 0.17;  ///< rad (10 deg): the half heading range is at least this...
  /// ...and at most this (rad): a place the odometry has turned more than this is not looked
  /// for turned round, where a corridor reads the same (a loss and the re-search find it).
  double max_half_theta = 0.5 * std::numbers::pi;
  /// After this many observations in a row whose window explained nothing at the heaviest
  /// place, a re-search of the whole map starts (a wrong prior or a lost track); its places
  /// join with HypothesisWeightOptions::entry_weight. `ambiguous` answers are no miss: the
  /// look-alikes are tracked until the drive tells them apart.
  int misses_before_global = 3;
  /// A window whose normalized score falls below this share of the place's usual one
  /// explains nothing there (a miss, the place not moved), whatever its own verdict: a
  /// window always finds something, even for a robot carried elsewhere.
  double miss_fit_ratio = 0.5;
  /// A miss scoring at least this share of the place's usual normalized score still places
  /// a confirmed place when its winner is tight (tight(): localized_sigma_m/_rad) and lies
  /// where the odometry carried the place (not surprising, step_min_m): the room changed
  /// since the map was made (people, furniture, a door). Its covariance is fused with the
  /// carried one, and the place stays `localized` while that is tight; it still counts as a
  /// miss toward a re-search. At or above miss_fit_ratio: no such rule.
  /// Right after a plain miss (one that placed nothing) such a weak fit still places the
  /// place but is not `localized`: nothing vouches for where the place is since.
  double weak_fit_ratio = 0.25;
  /// A laser's window whose winner lies farther from the odometry's place than the hypothesis
  /// set merges (0.3 m or 15 deg) and either farther than the place's covariance allows (a
  /// surprising step) or where the odometry's place fits worse does not move the place: the
  /// winner joins as a place of its own, weighted by the odometry's prior, and the weights
  /// tell them apart over the next scans (a slip wins in a scan or two; a look-alike that
  /// fits only a little better, as where the map's half saw a corridor differently, does
  /// not). false: the place follows the winner, not `localized` at that scan.
  bool split_far_winners = true;
  /// When a far winner splits off, the place the odometry carried stays at the best pose
  /// within two cells and this many standard deviations of its carried heading (at least two
  /// heading steps, at most kept_max_half_theta): scored at a heading the odometry got a few
  /// degrees wrong, the right place fits far worse than the look-alike and loses the weights
  /// to it (aces' held-out scan 362 with 5 % + 5 deg/m odometry: 70 at 3.5 deg off against
  /// 109 at a place 0.36 m along the corridor, then three scans `localized` 0.3-0.9 m off).
  /// 0: two heading steps of the carried heading.
  double kept_heading_sigmas = 2.0;
  double kept_max_half_theta = 0.174532925199;  ///< 10 deg
  /// A window scoring below this share of the place's usual normalized score is not
  /// `localized`, whatever its own verdict: the scan fits the place worse than the scans
  /// before it did (a look-alike a corridor slid or turned the place into, or a view the map
  /// lacks). The place still follows it; 0: no such rule.
  double localized_fit_ratio = 0.0;
  /// A laser's window that turns the place more than step_min_rad from where the odometry
  /// carried it is not `localized` unless it scores at least this share of the place's usual
  /// normalized score: a scan taken while turning that fits worse than usual and disagrees
  /// with the odometry's heading (csail's scan 55: 62 % of usual, 5-7 degrees off) is
  /// matched to a wrong heading more often than the odometry is wrong. The place still
  /// follows it. 0: no such rule.
  double turn_fit_ratio = 0.7;
  /// The odometry's place (the best within two cells of where it carried the place) is kept
  /// when it scores within this share of the window's winner: the scan does not move a
  /// place it cannot pin (along a corridor). Cartographer's real-time matcher penalizes the
  /// distance from its prior for the same reason.
  double odometry_score_slack = 0.02;
  /// The odometry's place is also kept when the scan's evidence there plus the odometry's
  /// prior (place_prior.hpp) beats the window's winner, as long as it fits at least this
  /// share of the place's usual normalized score: a corridor slid along fits as well and lies
  /// where the odometry did not go; after a slip the odometry's place fits far worse.
  double prior_fit_ratio = 0.8;
  /// A window that moves a tracked place farther from where the odometry carried it than
  /// prior_sigmas of its grown covariance, and at least these, is not `localized` at that
  /// observation (a scan matched to the wrong place, or a slip: the place follows it, and the
  /// next observation tells which).
  double step_min_m = 0.1;
  /// A place whose window grew wider than these (a long drive with nothing to match) splits
  /// into the look-alikes its window holds, at par: the weights tell them apart as it drives.
  double wide_window_m = 1.0;
  double wide_window_rad = 0.5235987756;  ///< 30 deg
  /// ...those scoring at least this share of the window's best on the coarse copy.
  double split_ratio = 0.9;
  /// In a wide window, a place away from the carried one replaces it only when it scores
  /// this share more than the best near it.
  double far_place_margin = 0.1;
  double step_min_rad = 0.0349065850399;  ///< 2 deg
  /// A place the scan does not pin is carried by the odometry, and stays `localized` while
  /// its grown covariance is within these (1 sigma).
  double localized_sigma_m = 0.1;
  double localized_sigma_rad = 0.0290888208666;  ///< 1.67 deg
  /// A laser's places (whatever moved or carried them) are held to this instead of
  /// localized_sigma_m: a window's spread is read within three cells of its winner, so a
  /// window flat there (a scan few of whose returns lie on walls, a featureless stretch)
  /// reports about two cells (10 cm) and passed 10 cm. On the 13 shared buildings x 3
  /// odometry models x 3 seeds: wrong `localized` scans 225 -> 173 (freiburg-campus 43 -> 20,
  /// infinite-corridor 160 -> 131), right 83.35 -> 82.80 %; the nine of the README's
  /// tables 90.61 -> 90.39 %, wrong 4 -> 4.
  double laser_localized_sigma_m = 0.07;
  /// Added to a laser Localizer's reported covariance (Estimate::covariance), not to its
  /// places': the error of a real map and of the lattice that a window's score surface does
  /// not see (a scan matches a few centimetres off the map's walls, engine/doc/tracking.md's
  /// limits). On the 81 tracking runs of nine real buildings the share of `localized`
  /// position errors within the 2-sigma radius went from 61 % to 85 % and the mean NEES from
  /// 15 to 3.1 (fitted on seeds 1 and 2, checked on seed 3: 85.1 %, 3.1; issue 19). The
  /// verdicts and poses do not change.
  double reported_floor_m = 0.02;
  double reported_floor_rad = 0.00872664625997;  ///< 0.5 deg
  /// A laser's window that moves a confirmed place `localized` puts it where the Kalman
  /// update of two estimates of its position puts it: the window's winner (its covariance
  /// widened by fused_window_error_m) and where the odometry carried the place (its
  /// covariance grown by the drive). The heading is the window's. One scan's match is a few
  /// centimetres off where the map's walls and the lattice mislead it; consecutive scans'
  /// errors partly cancel, as a particle filter's cloud averages them (README, issue 34: on
  /// the 13 shared buildings x 3 odometry models x 3 seeds, 80.7 -> 83.4 % of the scans
  /// `localized` and right, 324 -> 225 wrong). false: the winner's position.
  bool fuse_carried_position = true;
  /// The error of a window's winner that its score surface does not see (m, 1 sigma; the
  /// same 2 cm as reported_floor_m), added to its covariance in that fusion.
  double fused_window_error_m = 0.02;
  /// A place holding less than this share of the weights is re-scored in its window alone:
  /// no look-alikes split off it, no second look twice as wide when its best lies on the
  /// window's edge (issue 34: with several places tracked, an update's time stays bounded).
  /// 0: every place gets both.
  double light_place_weight = 0.3;
  /// How each place's observations weigh, and the share `localized` needs.
  HypothesisWeightOptions weights;
  /// A `localized` answer disagreeing with the last one and the odometry is not localized.
  JumpGateOptions jump_gate;
  /// Re-searches after the first observation run in slices, a few per update.
  SlicedSearchOptions research;
  /// The look-alikes a global search leaves, tracked through motion.
  HypothesisSetOptions hypothesis_set;
  /// A laser's first search (nothing tracked yet) seeds its places scoring at least this
  /// share of its best, where a re-search's seeds keep hypothesis_set.drop_ratio:
  /// with no track to weigh them against, the drive's scans, not the first one, pick among
  /// look-alikes (a corridor turned round fits one scan 3 % better than the truth as often
  /// as not). On 220 seeded trials of the shared buildings `localized` wrong after the drive
  /// 5 -> 2 (README, issue 35).
  double first_drop_ratio = 0.9;
  /// While the answer is `ambiguous`, search the whole map again once the odometry path since
  /// the last global search reaches this (m): the drive behind the latest observation has
  /// grown and may tell the look-alikes apart (with one hypothesis tracked, only the seeds
  /// within max_half_xy_m of it join; 0: at every observation).
  double reseed_after_m = 1.0;
  /// Driver values up to this far above a sonar's max range read as no echo (from_driver).
  double max_range_slack_m = 0.01;
};

/// A laser scanner on the robot (issue 13: scans carry their mount, so the caller need not
/// re-project an off-centre laser).
struct LaserSensor {
  Pose2 mount;              ///< the laser's pose in the robot frame
  double max_range = 30.0;  ///< returns at or beyond this (m) are no return
  /// How a scan becomes rigid points (hits, or hits and free samples; not rays).
  ScanModelOptions model;
  /// Fuse each scan with the earlier ones of the drive window (LocalizerOptions::drive), as
  /// sonar firings are. Off by default: one laser scan is evidence enough, the places'
  /// weights add the scans up, and an odometry slip inside the window would shift the whole
  /// fused cloud (a confident wrong answer; issue 34).
  bool fuse_drive = false;
  /// Match scans on with_laser_tracking_grid's likelihood field whatever
  /// LocalizerOptions::correlation's grid (the default: it tracks real buildings best);
  /// false: the correlation options' grid and field as given.
  bool tracking_field = true;
};

/// The map's grid a laser Localizer tracks best on: `options` matching scans on a likelihood
/// field 5 cm wide that reaches 15 cm from a wall, with no free-space evidence (issue 34:
/// on nine real buildings under three odometry models and three seeds, 78.6 -> 86.4 % of
/// scans `localized` and right and 68 -> 28 wrong, against the contour-thinned grid; a ring
/// of sonars keeps that one, seed 001). A laser Localizer applies it unless
/// LaserSensor::tracking_field is false.
CorrelationOptions with_laser_tracking_grid(CorrelationOptions options);

/// Checks a laser description; throws gridloc::Error naming the field.
void validate(const LaserSensor& laser);

/// What the latest observation did besides its estimate (for logs, plots and progress).
struct LocalizerStatus {
  int search_slices_done = 0;  ///< a re-search under way: slices done...
  int search_slices = 0;       ///< ...of these (0 and 0: none under way)
  /// The share of it done (of its slices, or of its lattice's poses ruled out; 1 when done).
  double search_progress = 0.0;
  bool search_finished = false;  ///< a search finished at this observation; its places joined
  bool jump_rejected = false;    ///< the answer was `localized` but the jump gate refused it
  /// The answer was `localized` but is the first place from no prior, not yet borne out by
  /// the drive (JumpGateOptions::settle_first): `not localized` meanwhile.
  bool confirming = false;
  /// Why the answer is `not localized` (HeldBack::None when it is `localized` or
  /// `ambiguous`): the heaviest place's reason, or the jump gate's.
  HeldBack held_back = HeldBack::None;
};

/// What the Localizer holds between calls (see Localizer).
struct LocalizerState {
  std::optional<Pose2> odometry;      ///< the latest odometry pose
  std::vector<OdometryFiring> drive;  ///< sonar: firings within the drive window, oldest first
  std::vector<OdometryScan> scans;    ///< laser: scans within the drive window, oldest first
  /// The poses believed (world frame) at `set_odometry`; empty: localize globally next.
  HypothesisSet set;
  Pose2 set_odometry;                  ///< the odometry pose the set's poses refer to
  double travelled_m = 0.0;            ///< odometry path length since set_odometry
  double turned_rad = 0.0;             ///< odometry turning since set_odometry
  double since_global_m = 0.0;         ///< odometry path length since the last global search
  double since_weights_m = 0.0;        ///< path length since the weights last took evidence
  double since_weights_rad = 0.0;      ///< turning since then
  std::optional<SlicedSearch> search;  ///< a re-search under way
  JumpGate gate;
  LocalizerStatus status;
  std::optional<Estimate> estimate;  ///< the latest observation's estimate
};

/// Thread safety: one writer (reset, set_prior, add_observation) and any number of readers
/// (estimate) at the same time; add_odometry may come from another thread too, also while a
/// firing is being localized (the firing keeps the odometry it was taken at). Readers get the
/// previous estimate while a firing is being localized. The answer does not depend on
/// CorrelationOptions::threads.
class Localizer {
 public:
  /// Precomputes the global grids once; throws gridloc::Error for a bad map, ring or options.
  Localizer(OccupancyMap map, SonarRing ring, LocalizerOptions options = {});
  /// The same for a robot with a laser scanner (its scans go to add_observation(time, scan)).
  Localizer(OccupancyMap map, LaserSensor laser, LocalizerOptions options = {});

  /// Forgets the drive, the hypotheses and the estimate (not the latest odometry pose): the
  /// next observation localizes globally.
  void reset();
  /// The robot is at `pose` (world frame) with `covariance` of (x, y, theta) now, at the
  /// latest odometry pose: the one hypothesis. Throws for a non-finite pose or covariance, or
  /// a negative variance.
  void set_prior(const Pose2& pose, const Eigen::Matrix3d& covariance);
  /// The robot's odometry pose now (any fixed odometry frame); firings are taken here. The
  /// path length since the prior grows the search window.
  void add_odometry(const Pose2& odometry);
  /// A firing of the ring at the latest odometry pose (the odometry origin when none was
  /// given), as the driver publishes it (from_driver: +inf no echo, -inf too close); fuses it
  /// with the drive and localizes (engine/doc/tracking.md): each tracked place is carried by
  /// odometry and re-scored in a window, and weighed; without places (at first), after
  /// misses_before_global misses in a row of the heaviest, or while `ambiguous` once
  /// reseed_after_m has been driven, a search of the whole map starts (at the first
  /// observation it runs whole; later in slices, a few per call) and its places join with
  /// their entry weights; the answer is weighted_estimate's, through the jump gate.
  /// `time_s` must be finite; this version does not use it otherwise. Throws gridloc::Error
  /// for bad readings (the state is then unchanged).
  void add_observation(double time_s, const std::vector<double>& driver_ranges);
  /// A laser scan (sensor frame) at the latest odometry pose, for a Localizer built with a
  /// LaserSensor: alone, or with LaserSensor::fuse_drive fused with the drive's earlier scans
  /// (fuse_scans), and localized as a firing is. Ranges at or beyond LaserSensor::max_range (or the
  /// scan's own max_range) are no return. Throws gridloc::Error for a scan that fails validate(),
  /// or on a sonar Localizer (and a firing on a laser one).
  void add_observation(double time_s, const RangeScan& scan);
  /// The latest firing's estimate (pose, covariance, verdict, hypotheses with their
  /// weights); gridloc::Error before the first firing.
  Estimate estimate() const;
  /// What the latest observation did: a re-search's progress, a rejected jump.
  LocalizerStatus status() const;

  const CorrelationEstimator& estimator() const { return estimator_; }

 private:
  /// Localizes `observation`, taken at odometry pose `taken_at`, into `next` (a copy of the
  /// state) and publishes it.
  void localize(LocalizerState next, const Pose2& taken_at, const Observation& observation);
  /// Each tracked place carried by the odometry since the set and re-scored in its window.
  std::vector<TrackedHypothesis> follow(const LocalizerState& next, const Pose2& taken_at,
                                        const Observation& observation) const;
  /// One place carried by `moved` (its covariance grown by `travelled_m` and the turn) and
  /// re-scored in its window; nullopt when the carried pose leaves the map.
  /// With `look_alikes`, a window wider than wide_window_m or wide_window_rad also gives
  /// the other places in it scoring split_ratio of its best (on the coarse copy).
  /// With `second_look`, a confirmed place whose best lies on the window's edge is looked
  /// for once more, twice as wide.
  std::optional<TrackedHypothesis> follow_one(TrackedHypothesis hypothesis, const Pose2& moved,
                                              double travelled_m, const Observation& observation,
                                              std::vector<LookAlike>* look_alikes,
                                              bool second_look = true) const;
  /// Starts a re-search when the track is lost (or ambiguous long enough), runs its next
  /// slices (all of them at the first observation) and, once it is done, lets its places
  /// join `tracked`. Returns the finished search's estimate.
  std::optional<Estimate> advance_search(LocalizerState& next,
                                         std::vector<TrackedHypothesis>& tracked,
                                         const Pose2& taken_at,
                                         const Observation& observation) const;
  /// A finished search's places, carried from its observation to `now` (catch_up) and
  /// re-scored on its observation, join `tracked` with their entry weights (unless they meet
  /// a place already tracked); a re-search's are `newcomers` (TrackedHypothesis::newcomer).
  void join(const Estimate& global, const SlicedSearch& search,
            std::vector<TrackedHypothesis>& tracked, const SlicedSearch::PastObservation& now,
            bool newcomers) const;
  /// A search's place carried from the search's observation through up to
  /// SlicedSearchOptions::catch_up_steps of the observations taken meanwhile (evenly spread),
  /// then to `now`, matched in its window at each; nullopt when it leaves the map.
  std::optional<TrackedHypothesis> catch_up(TrackedHypothesis seed, const SlicedSearch& search,
                                            const SlicedSearch::PastObservation& now) const;
  /// Whether the window `e` around a carried place explains the observation there, and
  /// where it puts the place: updates the place and sets e.verdict to the place's own.
  /// A winner that LocalizerOptions::split_far_winners makes a place of its own is added to
  /// `look_alikes` (when given) instead of moving the place.
  void place(TrackedHypothesis& hypothesis, Estimate& e, const Observation& observation,
             const SearchWindow& global, std::vector<LookAlike>* look_alikes = nullptr) const;
  /// Why a window that moves the `carried` place to its winner `e` is not `localized`: a
  /// `surprise`-ing step, a `weak` fit, a wide window, a turn on a weak fit (None: it is).
  HeldBack moved_held_back(const TrackedHypothesis& carried, const Estimate& e, bool surprise,
                           bool weak) const;
  /// Moves the place to the window's winner `e` (LocalizerOptions::fuse_carried_position:
  /// its position fused with where the odometry carried the place) and confirms it.
  void take_winner(TrackedHypothesis& hypothesis, const Estimate& e) const;
  /// The place stays where the odometry carried it (`near`, the best within two cells),
  /// its covariance narrowed by the window `e` when it `fits_as_usual`; sets e.verdict.
  void keep_odometry_place(TrackedHypothesis& hypothesis, Estimate& e, const Estimate& near,
                           bool fits_as_usual, bool weak) const;
  /// Whether a look-alike split off a `carried` place that missed misses too and meets it:
  /// it explains the scan no better, and merging would hand it the place (orebro's held-out
  /// scans 213-219: turned 10-13 degrees, then lost), so it is not kept.
  bool takes_over_a_miss(const TrackedHypothesis& look_alike,
                         const TrackedHypothesis& carried) const;
  /// Whether a window's winner at `winner` joins as a place of its own rather than moving
  /// the place from `kept` (LocalizerOptions::split_far_winners).
  bool splits_off(const TrackedHypothesis& hypothesis, const Pose2& kept,
                  const Pose2& winner) const;
  /// Whether the window `e` turns the `carried` place more than step_min_rad on a fit below
  /// LocalizerOptions::turn_fit_ratio of its usual one.
  bool turns_on_a_weak_fit(const TrackedHypothesis& carried, const Estimate& e) const;
  /// A miss that still places the place (LocalizerOptions::weak_fit_ratio): when it does,
  /// moves the place there, fuses the covariances and sets e.verdict; else returns false.
  bool place_on_weak_fit(TrackedHypothesis& hypothesis, Estimate& e, bool after_a_miss) const;
  /// Whether a covariance is within localized_sigma_m and localized_sigma_rad.
  bool tight(const Eigen::Matrix3d& covariance) const;
  /// Whether `placed` lies farther from the carried place than its covariance allows.
  bool surprising(const TrackedHypothesis& predicted, const Pose2& placed) const;
  /// The window's estimate; a window wider than three coarse cells is searched on the
  /// coarse copy first, then within two coarse cells of its best on the tracker's grids.
  Estimate search_window(const Observation& observation, const SearchWindow& window,
                         const Eigen::Matrix3d& covariance,
                         std::vector<LookAlike>* look_alikes = nullptr) const;
  /// Where the odometry carried a place (a window's centre) and how unsure it is.
  struct PlacePrior {
    Pose2 carried;
    Eigen::Matrix3d covariance;
    Eigen::Vector3d floor;  ///< a cell and a heading step, added to the variances
  };
  PlacePrior place_prior(const Pose2& carried, const Eigen::Matrix3d& covariance,
                         double step_theta) const;
  /// The window's evidence (HypothesisWeightOptions::evidence_per_scan times its normalized
  /// score) plus the log prior of its pose.
  double posterior(const Estimate& e, const PlacePrior& prior) const;
  /// Whether a world pose lies on the map's grid.
  bool on_map(const Pose2& pose) const;
  /// The most a window spans either way of a place's heading: max_half_theta, at most pi.
  double max_window_turn() const;
  /// Whether a window centred at `pose` lies on the coarse copy's grid.
  bool coarse_contains(const Pose2& pose) const;
  /// A coarse window's peaks apart from `chosen` and scoring split_ratio of its best, each
  /// with its log prior against the chosen place's.
  std::vector<LookAlike> other_places(const Estimate& rough, const Estimate& chosen,
                                      const PlacePrior& prior) const;
  /// The best pose within two cells and max(half_theta, two heading steps) of `pose`.
  Estimate best_near(const Pose2& pose, const Observation& observation, const SearchWindow& global,
                     double half_theta = 0.0) const;
  /// How far either way of its carried heading a place kept beside a split-off winner is
  /// looked for (LocalizerOptions::kept_heading_sigmas).
  double kept_half_theta(const TrackedHypothesis& carried) const;
  /// The window around a carried place, its half sides from its covariance.
  SearchWindow window_around(const TrackedHypothesis& hypothesis, const SearchWindow& global) const;

  /// The estimator a search of the whole map runs on: the coarse copy when there is one.
  const CorrelationEstimator& search_estimator(bool first) const;

  LocalizerOptions options_;
  std::optional<LaserSensor> laser_;  ///< set for a laser Localizer
  CorrelationEstimator estimator_;
  /// A laser's coarse copy of the map for searches (SlicedSearchOptions::resolution).
  std::optional<CorrelationEstimator> coarse_;
  mutable std::shared_mutex mutex_;
  LocalizerState state_;
};

}  // namespace gridloc
