#pragma once
// A decoded map image: what the PGM/PPM and PNG decoders give load_ros_map. Private to
// gridloc_grids (not installed), so that reading map images needs no image library.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace gridloc {

/// An 8-bit image: `height` rows from the top, each `width` pixels of `channels` interleaved
/// samples (grey; R, G, B; or R, G, B, alpha).
struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<std::uint8_t> pixels;  ///< height * width * channels samples

  Image() = default;
  Image(int cols, int rows, int samples_per_pixel)
      : width(cols),
        height(rows),
        channels(samples_per_pixel),
        pixels(static_cast<std::size_t>(cols) * static_cast<std::size_t>(rows) *
               static_cast<std::size_t>(samples_per_pixel)) {}

  /// The first sample of image row `r` (0 is the top).
  std::uint8_t* row(int r) { return pixels.data() + row_offset(r); }
  const std::uint8_t* row(int r) const { return pixels.data() + row_offset(r); }

 private:
  std::size_t row_offset(int r) const {
    return static_cast<std::size_t>(r) * static_cast<std::size_t>(width) *
           static_cast<std::size_t>(channels);
  }
};

}  // namespace gridloc
