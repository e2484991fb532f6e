// The names of the reasons a tracker's answer is held back.
#include "gridloc/engine/localizer/held_back.hpp"

namespace gridloc {

std::string to_string(HeldBack reason) {
  switch (reason) {
    case HeldBack::None:
      return "none";
    case HeldBack::NoPlace:
      return "no_place";
    case HeldBack::Miss:
      return "miss";
    case HeldBack::WeakFit:
      return "weak_fit";
    case HeldBack::Surprise:
      return "surprise";
    case HeldBack::SplitOff:
      return "split_off";
    case HeldBack::LookAlikes:
      return "look_alikes";
    case HeldBack::WideWindow:
      return "wide_window";
    case HeldBack::TurnOnWeakFit:
      return "turn_on_weak_fit";
    case HeldBack::WideCarried:
      return "wide_carried";
    case HeldBack::Unconfirmed:
      return "unconfirmed";
    case HeldBack::Newcomer:
      return "newcomer";
    case HeldBack::JumpRejected:
      return "jump_rejected";
    case HeldBack::Confirming:
      return "confirming";
  }
  return "unknown";
}

}  // namespace gridloc
