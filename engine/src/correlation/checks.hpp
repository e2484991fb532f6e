#pragma once
// The correlation estimator's checks of its options and observations (internal).
#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/correlation/memory.hpp"

namespace gridloc::correlation_detail {

/// Checks the options on their own; throws gridloc::Error naming the first that is wrong.
void check(const CorrelationOptions& options);

/// What the global grids' padding covers (m); throws gridloc::Error for a bad reach.
double padding_reach(const CorrelationOptions& options, const SonarRing& ring);

/// Checks that options.resolution is not coarser than the map, then the cells of every global
/// grid the options build for `map` (reach `reach` m) and
/// the memory they and a search of size `search` need (correlation_memory_bytes) against
/// options.limits, before anything is allocated; throws gridloc::Error naming the limit.
/// `hits_only`: a laser's hits alone (correlation_memory_bytes).
void check_resources(const GridGeometry& map, const CorrelationOptions& options, double reach,
                     const SearchSize& search = {}, bool hits_only = false);

/// Checks the observation is sonar readings for `ring` or a scan within `reach`, not both.
void check_observation(const Observation& observation, const SonarRing& ring, double reach);

}  // namespace gridloc::correlation_detail
