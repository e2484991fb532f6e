#pragma once
// PNG map images: the header read and the whole file checked by gridloc (chunk lengths and
// CRCs, the compressed data inflated and its row filters checked) before OpenCV decodes it,
// so that a damaged or truncated PNG is one gridloc::Error and libpng prints nothing.
#include <opencv2/core.hpp>
#include <string>

namespace gridloc {

/// What a PNG's IHDR chunk declares.
struct PngHeader {
  double width = 0.0;   ///< declared columns (a double: checked before any cast)
  double height = 0.0;  ///< declared rows
  int bit_depth = 8;    ///< 1, 2, 4, 8 or 16 bits per sample
  int colour_type = 0;  ///< 0 grey, 2 RGB, 3 palette, 4 grey + alpha, 6 RGB + alpha
  bool interlaced = false;
};

/// Whether the bytes start with the PNG signature.
bool looks_like_png(const std::string& bytes);

/// Reads the IHDR chunk; throws gridloc::Error naming `path` when it is missing or invalid
/// (a side of 0, an unknown colour type or bit depth), or the image has 16-bit samples.
PngHeader read_png_header(const std::string& bytes, const std::string& path);

/// Checks the whole file (see above) and decodes it with OpenCV, keeping only the chunks that
/// make the pixels (IHDR, PLTE, tRNS, IDAT, IEND) so that libpng has nothing to warn about.
/// Returns an 8-bit image of 1, 3 or 4 channels (OpenCV's IMREAD_UNCHANGED), rows from the top.
cv::Mat decode_png(const std::string& bytes, const PngHeader& header, const std::string& path);

}  // namespace gridloc
