#pragma once
/// A sonar front-end in the spirit of Borenstein and Koren's EERUF (seed 001 §6, ref. [10]):
/// the ring fires several times in a row from the same pose; an echo that consecutive
/// firings do not repeat (crosstalk, a stray reflection, noise) is rejected, so that it never
/// reaches the local grid.
#include <vector>

#include "gridloc/sensors/sonar_ring.hpp"

namespace gridloc {

struct EchoFilterOptions {
  /// Two echoes agree when they differ by at most tolerance_m + tolerance_frac times the
  /// shorter one (m, fraction of the range).
  double tolerance_m = 0.05;
  double tolerance_frac = 0.03;
  /// A sonar's reading is kept when at least this many firings agree (>= 2).
  int min_agreeing = 2;
};

/// One reading per sonar after filtering, and which sonars were rejected.
struct FilteredReadings {
  /// Per sonar in ring order: the median of the largest group of agreeing firings (exactly
  /// max_range for no echo); for a rejected sonar, the median of all its firings (a valid
  /// reading that must not be used: see `rejected`).
  std::vector<double> ranges;
  std::vector<bool> rejected;  ///< true: the firings disagreed, the sonar gives no evidence
  int rejected_count = 0;
};

/// Filters `firings` (K >= 2 consecutive readings of `ring` from one pose, each one range per
/// sonar in ring order, max_range or more meaning no echo). Per sonar, the largest group of
/// firings whose ranges pairwise agree (two "no echo" agree; an echo and "no echo" never do) is
/// found, ties going to the tighter group, then the shorter ranges; when it holds at least
/// `min_agreeing` firings its median is the reading, otherwise the sonar is rejected. Throws
/// gridloc::Error for fewer than 2 firings, a firing whose size is not the ring's, a NaN or
/// negative range, or bad options.
FilteredReadings filter_echoes(const SonarRing& ring,
                               const std::vector<std::vector<double>>& firings,
                               const EchoFilterOptions& options = {});

/// Checks `options`; throws gridloc::Error naming the field.
void validate(const EchoFilterOptions& options);

}  // namespace gridloc
