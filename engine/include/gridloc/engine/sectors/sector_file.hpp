#pragma once
/// Visibility sectors saved and loaded (issue 18): computing them takes seconds on a furnished
/// room and tens on an office, at every `localize`; a saved SectorMap is read back instead.
/// The file (JSON) holds the polygon map the sectors were computed on and the options that
/// shape them, so that sectors are never used with another map or other options.
#include <string>

#include "gridloc/engine/sectors/visibility_sectors.hpp"
#include "gridloc/grids/limits.hpp"

namespace gridloc {

/// Writes `sectors`, computed with `options`, to `path`; throws gridloc::Error when the file
/// cannot be written.
void save_sectors(const SectorMap& sectors, const SectorOptions& options, const std::string& path);

/// Reads what save_sectors wrote, for `map` and `options`; throws gridloc::Error naming the
/// file for a missing file, a directory or device, a file over limits.max_file_mb, a malformed
/// file, sectors of another
/// polygon map, or sectors computed with another cell, label beam count or clearance.
SectorMap load_sectors(const std::string& path, const PolygonMap& map, const SectorOptions& options,
                       const ResourceLimits& limits = {});

}  // namespace gridloc
