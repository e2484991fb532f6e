#pragma once
/// Why a tracker's answer is not `localized` (LocalizerStatus::held_back): which of the
/// tracker's rules held it back (engine/doc/tracking.md names each step). A navigation stack
/// reports it beside the verdict; an engineer tuning the tracker counts the scans per reason.
#include <string>

namespace gridloc {

enum class HeldBack {
  None,           ///< not held back: `localized`, or `ambiguous` (the weights say why)
  NoPlace,        ///< no place tracked yet: a search is under way, or nothing lies on the map
  Miss,           ///< the window fitted far below the place's usual fit (miss_fit_ratio)
  WeakFit,        ///< the fit fell below localized_fit_ratio of the place's usual one
  Surprise,       ///< the window moved the place farther than the odometry allows
  SplitOff,       ///< the window's winner lies far from the odometry's place: a place of its own
  LookAlikes,     ///< the window's winner beats the odometry's place, which fits worse than usual
  WideWindow,     ///< the window's own covariance is wider than a localized place's
  TurnOnWeakFit,  ///< the window turned the place on a weak fit (turn_fit_ratio)
  WideCarried,    ///< the odometry's place: its covariance is wider than a localized place's
  Unconfirmed,    ///< no window has placed this place `localized` since it entered
  Newcomer,       ///< a re-search's place not yet carried newcomer_settle_m
  JumpRejected,   ///< the jump gate refused a step the odometry did not make
  Confirming,     ///< the first place from no prior, not yet borne out by the drive
};

/// The reason's name in snake_case ("none", "miss", "split_off", ...): the JSON field's value.
std::string to_string(HeldBack reason);

}  // namespace gridloc
