#pragma once
// PNG map images, decoded by gridloc itself (zlib inflates the image data): the header read
// and the whole file checked (chunk lengths and CRCs, chunk order, the row filters and the
// number of rows), so that a damaged or truncated PNG is one gridloc::Error and nothing is
// printed, and a sonar-only user needs no image library (issue 18).
#include <string>

#include "image.hpp"

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

/// Checks the whole file (see above) and decodes it from the chunks that make the pixels
/// (IHDR, PLTE, tRNS, IDAT; ancillary chunks such as gamma or colour profiles are ignored):
/// every colour type at 8 bits, grey and palette images at 1, 2 and 4 bits, the five row
/// filters, interlaced (Adam7) or not. Returns the image OpenCV's imdecode(IMREAD_UNCHANGED)
/// gave before, pixel for pixel, but in R, G, B (alpha) order rather than B, G, R: grey 1
/// channel (its tRNS ignored); RGB and palette 3, or 4 with a tRNS chunk (alpha 0 for the RGB
/// key colour; palette indices past tRNS opaque, past PLTE black); grey + alpha 4 (the grey
/// level three times, then alpha); RGB + alpha 4. Rows from the top.
Image decode_png(const std::string& bytes, const PngHeader& header, const std::string& path);

}  // namespace gridloc
