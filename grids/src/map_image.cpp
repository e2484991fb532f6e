#include "map_image.hpp"

#include "gridloc/grids/error.hpp"
#include "png_image.hpp"
#include "pnm_image.hpp"

namespace gridloc {
namespace {

/// Checks a declared image size before it is decoded: its cells, and the bytes that loading
/// it holds at once (the file, `channels` bytes per decoded pixel, and the OccupancyMap's one
/// byte per cell that load_ros_map fills from it).
void check_image_size(double width, double height, int channels, std::size_t file_bytes,
                      const std::string& path, const ResourceLimits& limits) {
  const double cells = check_grid_cells(width, height, limits, path + ": map image");
  check_memory(static_cast<double>(file_bytes) + cells * (channels + 1), limits,
               path + ": loading the map image");
}

}  // namespace

Image read_map_image(const std::string& path, const ResourceLimits& limits) {
  const std::string bytes = read_input_file(path, "map image", limits);
  if (looks_like_png(bytes)) {
    const PngHeader header = read_png_header(bytes, path);
    // decode_png gives 1, 3 or 4 channels (as OpenCV did); 4 bounds them all.
    check_image_size(header.width, header.height, 4, bytes.size(), path, limits);
    return decode_png(bytes, header, path);
  }
  if (looks_like_pnm(bytes)) {
    const PnmHeader header = read_pnm_header(bytes, path);
    check_image_size(header.width, header.height, header.channels, bytes.size(), path, limits);
    return decode_pnm(bytes, header, path);
  }
  throw Error(path + ": not a PGM, PPM or PNG image (the map image formats gridloc reads)");
}

}  // namespace gridloc
