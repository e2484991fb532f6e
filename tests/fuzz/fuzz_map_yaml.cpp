// Fuzz harness: a map_server YAML file read by load_map_metadata (grids/src/map_io.cpp).
#include "fuzz_support.hpp"
#include "gridloc/grids/map_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const gridloc::fuzz::ScratchFile file("map.yaml", data, size);
  const std::string path = file.path();
  gridloc::fuzz::expect_clean([&] { (void)gridloc::load_map_metadata(path); });
  return 0;
}
