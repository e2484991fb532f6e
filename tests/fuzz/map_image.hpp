#pragma once
// The map image harnesses' shared body: a fixed map_server YAML naming the image, the fuzzed
// bytes as that image, and load_ros_map (grids/src/map_io.cpp) reading both.
#include <string>

#include "fuzz_support.hpp"
#include "gridloc/grids/map_io.hpp"

namespace gridloc::fuzz {

/// Writes, once per process, a YAML whose image is `image_name` in `mode` (trinary, scale or
/// raw), then the fuzzed bytes as the image, and loads the map under the error contract.
inline void load_fuzzed_image(const std::string& image_name, const std::string& mode,
                              const std::uint8_t* data, std::size_t size) {
  static const std::string yaml_path = [&] {
    const std::string yaml = "image: " + image_name +
                             "\nresolution: 0.05\norigin: [-1.0, -2.0, 0.3]\nnegate: 0\n"
                             "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: " +
                             mode + "\n";
    return write_file("map.yaml", reinterpret_cast<const std::uint8_t*>(yaml.data()), yaml.size());
  }();
  write_file(image_name, data, size);
  expect_clean([&] { (void)load_ros_map(yaml_path); });
}

}  // namespace gridloc::fuzz
