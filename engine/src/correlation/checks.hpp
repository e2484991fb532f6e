#pragma once
// The correlation estimator's checks of its options and observations (internal).
#include "gridloc/engine/correlation/estimator.hpp"

namespace gridloc::correlation_detail {

/// Checks the options on their own; throws gridloc::Error naming the first that is wrong.
void check(const CorrelationOptions& options);

/// What the global grids' padding covers (m); throws gridloc::Error for a bad reach.
double padding_reach(const CorrelationOptions& options, const SonarRing& ring);

/// Checks the observation is sonar readings for `ring` or a scan within `reach`, not both.
void check_observation(const Observation& observation, const SonarRing& ring, double reach);

}  // namespace gridloc::correlation_detail
