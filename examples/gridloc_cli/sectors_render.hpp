#pragma once
// The image of `gridloc sectors`: the visibility sectors of a polygon map (seed 000 §2), each
// filled in its own colour and numbered as in the printed table, drawn with OpenCV in the
// world frame (metres).
#include <opencv2/core.hpp>
#include <string>

#include "gridloc/engine/sectors/visibility_sectors.hpp"

namespace gridloc::cli {

/// The sectors of `sectors` (SectorMap::sector_of over SectorMap::grid), the outside and the
/// obstacles grey, the walls and vertices dark, sector k numbered k + 1 at its representative
/// point, ambiguous sectors hatched and outlined in red, metre axes and a legend. `name` (the
/// map's file name) heads the title line.
cv::Mat render_sectors(const SectorMap& sectors, const std::string& name);

}  // namespace gridloc::cli
