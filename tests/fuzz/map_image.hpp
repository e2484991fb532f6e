#pragma once
// The map image harnesses' shared body: a fixed map_server YAML naming the image, the fuzzed
// bytes as that image, and load_ros_map (grids/src/map_io.cpp) reading both.
#include <string>

#include "fuzz_support.hpp"
#include "gridloc/grids/map_io.hpp"

namespace gridloc::fuzz {

/// Writes a YAML whose image is `image_name` in `mode` (trinary, scale or raw) and the fuzzed
/// bytes as that image, side by side, and loads the map under the error contract.
inline void load_fuzzed_image(const std::string& image_name, const std::string& mode,
                              const std::uint8_t* data, std::size_t size) {
  const std::string yaml = "image: " + ScratchFile::file_name(image_name) +
                           "\nresolution: 0.05\norigin: [-1.0, -2.0, 0.3]\nnegate: 0\n"
                           "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: " +
                           mode + "\n";
  const ScratchFile yaml_file("map.yaml", yaml);
  const ScratchFile image_file(image_name, data, size);
  expect_clean([&] { (void)load_ros_map(yaml_file.path()); });
}

}  // namespace gridloc::fuzz
