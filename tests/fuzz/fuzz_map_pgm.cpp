// Fuzz harness: the fuzzed bytes as the PGM of a fixed trinary map_server YAML, loaded by
// load_ros_map (grids/src/map_io.cpp, gridloc's decoders in grids/src/pnm_image.cpp).
#include "map_image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gridloc::fuzz::load_fuzzed_image("map.pgm", "trinary", data, size);
  return 0;
}
