#pragma once
// Netpbm map images (PGM P2/P5, PPM P3/P6), decoded by gridloc itself rather than OpenCV so
// that a truncated or oversized file is one gridloc::Error and nothing is printed (issue 14).
#include <cstddef>
#include <string>

#include "image.hpp"

namespace gridloc {

/// What a PGM or PPM header declares.
struct PnmHeader {
  bool ascii = false;       ///< P2/P3 (decimal samples) rather than P5/P6 (bytes)
  int channels = 1;         ///< 1 (PGM) or 3 (PPM)
  double width = 0.0;       ///< declared columns (a double: checked before any cast)
  double height = 0.0;      ///< declared rows
  int maxval = 255;         ///< the largest sample value, 1..255
  std::size_t data_at = 0;  ///< offset of the first sample in the file
};

/// Whether the bytes start like a Netpbm image ('P' and a digit).
bool looks_like_pnm(const std::string& bytes);

/// Parses the header of a P2, P3, P5 or P6 file; throws gridloc::Error naming `path` for a
/// malformed header, a side of 0, a maxval of 0 or above 255 (16-bit images are rejected).
PnmHeader read_pnm_header(const std::string& bytes, const std::string& path);

/// Decodes the samples into an 8-bit image of header.channels channels, rows from the top.
/// A maxval below 255 is scaled to 0..255 as map_server does (v * 255 / maxval, rounded
/// down); a sample above the maxval, or data shorter than the header declares, throws
/// gridloc::Error naming `path` (and the pixel's row and column).
Image decode_pnm(const std::string& bytes, const PnmHeader& header, const std::string& path);

}  // namespace gridloc
