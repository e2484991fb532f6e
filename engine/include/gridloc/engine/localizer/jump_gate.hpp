#pragma once
/// The jump gate (issue 34): a `localized` answer whose motion since the last `localized`
/// answer disagrees with the odometry beyond what their uncertainties allow is not
/// `localized`. The new place is accepted once it has held, consistent with the odometry, over
/// settle_m of driving and settle_updates answers: a track that switched to a look-alike
/// says so for a while instead of jumping. With settle_first, the first place (nothing
/// `localized` before it, no prior) settles the same way: one scan from no prior is a guess
/// the drive must bear out.
#include <Eigen/Core>
#include <optional>

#include "gridloc/grids/geometry.hpp"

namespace gridloc {

struct JumpGateOptions {
  double sigmas = 3.0;               ///< the allowed disagreement, in standard deviations...
  double min_m = 0.3;                ///< ...and at least this (m)...
  double min_rad = 0.0872664625997;  ///< ...and this (rad, 5 deg)
  /// The odometry's error: this share of the path driven since the last `localized` answer,
  /// plus this heading drift per metre (whose position effect grows with the path squared).
  double odometry_error_per_m = 0.02;
  double odometry_turn_error_per_m = 0.017453292519943295;
  double settle_m = 1.0;   ///< a rejected place is accepted after this much driving on it...
  int settle_updates = 3;  ///< ...and this many answers in a row
  /// The first `localized` answer, with no reference before it, settles like a jump (on the
  /// shared buildings one held-out scan from no prior is sometimes `localized` metres off at
  /// confidences the right answers have: engine/doc/tracking.md); false: it passes at once.
  bool settle_first = true;
  /// ...and passes after settle_m of driving and this many answers (the one from no prior
  /// and one borne out by the drive: a held-out log's next scan may come 5 m later).
  int settle_first_updates = 2;
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const JumpGateOptions& options);

/// One answer as the gate sees it: the pose, its covariance and the odometry pose it was
/// taken at.
struct GatedPose {
  Pose2 pose;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  Pose2 odometry;
};

/// The gate's memory: the last accepted `localized` answer, and the place being settled.
class JumpGate {
 public:
  JumpGate() : JumpGate(JumpGateOptions{}) {}
  explicit JumpGate(JumpGateOptions options);

  /// Whether a `localized` answer at `answer` passes. A pass becomes the reference; a
  /// rejection starts (or goes on) settling the new place, and passes once it has settled.
  bool admit(const GatedPose& answer);
  /// Forgets everything (a reset of the localizer).
  void reset();
  /// Forgets everything but `reference`, which answers are then checked against (a prior
  /// the user gave: an answer consistent with it passes at once).
  void reset(const GatedPose& reference);
  /// Whether an answer was accepted (or a reference given) since the last reset.
  bool has_reference() const { return reference_.has_value(); }
  /// Whether `b` agrees with `a` carried by the odometry between them.
  bool consistent(const GatedPose& a, const GatedPose& b) const;

 private:
  struct Settling {
    GatedPose last;
    double driven_m = 0.0;
    int updates = 1;
  };
  JumpGateOptions options_;
  std::optional<GatedPose> reference_;
  std::optional<Settling> settling_;
};

}  // namespace gridloc
