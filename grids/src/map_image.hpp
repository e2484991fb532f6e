#pragma once
// Reading a map_server map image within the resource limits (issue 14).
#include <string>

#include "gridloc/grids/limits.hpp"
#include "image.hpp"

namespace gridloc {

/// Reads a PGM/PPM or PNG map image: checks the file (check_input_file), reads the size its
/// header declares and checks it (check_grid_cells) and the memory loading it takes
/// (check_memory: the file, the decoded image and the map's own byte per cell) before
/// decoding. Returns an 8-bit image of 1 to 4 channels, rows from the top. Every fault is a
/// gridloc::Error naming `path`; nothing is printed.
Image read_map_image(const std::string& path, const ResourceLimits& limits);

}  // namespace gridloc
