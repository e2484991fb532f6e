// Fuzz harness: a polygon map file read by load_polygon_map and, when it loads, rasterized by
// rasterize_polygon_map at its own resolution (grids/src/polygon_map.cpp).
#include "fuzz_support.hpp"
#include "gridloc/grids/polygon_map.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const gridloc::fuzz::ScratchFile file("polygons.yaml", data, size);
  const std::string path = file.path();
  gridloc::fuzz::expect_clean([&] {
    const gridloc::PolygonMap map = gridloc::load_polygon_map(path);
    (void)gridloc::rasterize_polygon_map(map);
  });
  return 0;
}
