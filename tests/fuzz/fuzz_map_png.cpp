// Fuzz harness: the fuzzed bytes as the PNG of a fixed scale-mode map_server YAML (scale mode
// reads the alpha channel), loaded by load_ros_map (grids/src/map_io.cpp, gridloc's decoder in
// grids/src/png_image.cpp).
#include "map_image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gridloc::fuzz::load_fuzzed_image("map.png", "scale", data, size);
  return 0;
}
