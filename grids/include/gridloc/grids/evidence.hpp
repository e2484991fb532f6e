#pragma once
/// Global evidence grids built from a map (seed 001 §2 and §5).
#include "gridloc/grids/grid.hpp"
#include "gridloc/grids/likelihood_field.hpp"
#include "gridloc/grids/limits.hpp"

namespace gridloc {

/// How the global grid treats obstacles: `Raw` keeps every occupied cell at +1; `Thinned`
/// keeps only the one-cell-thick contour facing free space (seed 001 §5); `LikelihoodField`
/// scores each cell by its distance to the nearest occupied cell, with free-space evidence
/// beyond a cutoff (make_likelihood_field, issue 13).
enum class GlobalModel { Raw, Thinned, LikelihoodField };

/// Builds the map directly at another resolution (seed 001 §2: never by averaging evidence):
/// a cell is Occupied if any map cell centred in it is occupied, Free if all such cells are
/// free, Unknown otherwise. Finer resolutions sample the map at the cell centre. The result
/// keeps the map's origin and yaw. Throws gridloc::Error for a non-positive resolution, and
/// for a result over limits.max_cells (its size is checked as doubles before it is cast).
OccupancyMap resample(const OccupancyMap& map, double resolution,
                      const ResourceLimits& limits = {});

/// Occupied +1, free -1, unknown 0.
EvidenceGrid make_evidence(const OccupancyMap& map);

/// Contour correction of seed 001 §5: an occupied cell stays +1 only if one of its 8
/// neighbours is Free; the interior of obstacles becomes unknown (0). Free cells stay -1.
EvidenceGrid make_thinned_evidence(const OccupancyMap& map);

/// The global grid of one search level: `map` resampled at `resolution`, then raw, thinned or
/// its likelihood field (with `field`, which only that model reads) at that resolution;
/// `limits` bounds the resampled grid (see resample()).
EvidenceGrid make_global_grid(const OccupancyMap& map, double resolution, GlobalModel model,
                              const LikelihoodFieldOptions& field = {},
                              const ResourceLimits& limits = {});

}  // namespace gridloc
