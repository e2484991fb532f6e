#include "png_image.hpp"

#include <zlib.h>

#include <array>
#include <cstdint>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

constexpr char kSignature[] = "\x89PNG\r\n\x1a\n";
constexpr std::size_t kSignatureBytes = 8;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(path + ": " + what);
}

std::uint32_t be32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<std::uint8_t>(bytes[at + k]);
  return v;
}

/// One chunk of the file: its type and where its length field and data start.
struct Chunk {
  std::string type;
  std::size_t at = 0;  ///< offset of the length field
  std::uint32_t length = 0;
  std::size_t data() const { return at + 8; }
  std::size_t end() const { return at + 12 + length; }
};

bool is_letter(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
}

/// The chunk at `at`, its bounds, type and CRC checked.
Chunk read_chunk(const std::string& bytes, std::size_t at, const std::string& path) {
  if (bytes.size() - at < 12) {
    fail(path, "the PNG is truncated at byte " + std::to_string(at) + " (no IEND chunk)");
  }
  Chunk c{bytes.substr(at + 4, 4), at, be32(bytes, at)};
  for (char ch : c.type) {
    if (!is_letter(ch))
      fail(path, "the PNG is damaged: bad chunk type at byte " + std::to_string(at));
  }
  if (c.length > 0x7fffffffu || bytes.size() - at - 12 < c.length) {
    fail(path, "the PNG is truncated: chunk " + c.type + " at byte " + std::to_string(at) +
                   " runs past the end of the file");
  }
  const auto* p = reinterpret_cast<const Bytef*>(bytes.data() + at + 4);
  if (crc32(0L, p, 4 + c.length) != be32(bytes, c.data() + c.length)) {
    fail(path, "the PNG is damaged: chunk " + c.type + " at byte " + std::to_string(at) +
                   " fails its CRC");
  }
  return c;
}

/// Every chunk from IHDR to IEND (what follows IEND is ignored, as libpng does).
std::vector<Chunk> read_chunks(const std::string& bytes, const std::string& path) {
  std::vector<Chunk> chunks;
  std::size_t at = kSignatureBytes;
  do {
    chunks.push_back(read_chunk(bytes, at, path));
    at = chunks.back().end();
  } while (chunks.back().type != "IEND");
  return chunks;
}

int samples_per_pixel(int colour_type) {
  switch (colour_type) {
    case 2:
      return 3;
    case 4:
      return 2;
    case 6:
      return 4;
    default:
      return 1;  // grey, palette
  }
}

bool valid_depth(int colour_type, int depth) {
  switch (colour_type) {
    case 0:
      return depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16;
    case 3:
      return depth == 1 || depth == 2 || depth == 4 || depth == 8;
    case 2:
    case 4:
    case 6:
      return depth == 8 || depth == 16;
    default:
      return false;
  }
}

/// Walks the inflated image data row by row (the 7 passes of an interlaced image), checking
/// that each row starts with a known filter type and that the data has exactly the rows the
/// header declares.
class RowWalker {
 public:
  RowWalker(const PngHeader& h, const std::string& path) : path_(path) {
    const auto w = static_cast<std::size_t>(h.width), ht = static_cast<std::size_t>(h.height);
    const std::size_t bits =
        static_cast<std::size_t>(h.bit_depth) * samples_per_pixel(h.colour_type);
    const auto add = [&](std::size_t cols, std::size_t rows) {
      if (cols > 0 && rows > 0) passes_.push_back({rows, (cols * bits + 7) / 8});
    };
    if (!h.interlaced) {
      add(w, ht);
      return;
    }
    constexpr std::array<std::array<std::size_t, 4>, 7> kAdam7 = {{{0, 0, 8, 8},
                                                                   {4, 0, 8, 8},
                                                                   {0, 4, 4, 8},
                                                                   {2, 0, 4, 4},
                                                                   {0, 2, 2, 4},
                                                                   {1, 0, 2, 2},
                                                                   {0, 1, 1, 2}}};
    for (const auto& [x0, y0, dx, dy] : kAdam7) {
      add(w > x0 ? (w - x0 + dx - 1) / dx : 0, ht > y0 ? (ht - y0 + dy - 1) / dy : 0);
    }
  }

  void consume(const std::uint8_t* data, std::size_t n) {
    while (n > 0) {
      if (pass_ == passes_.size())
        fail(path_, "the PNG holds more image data than its header declares");
      const Pass& p = passes_[pass_];
      if (offset_ == 0 && data[0] > 4) {
        fail(path_, "the PNG is damaged: unknown row filter " + std::to_string(data[0]));
      }
      const std::size_t step = std::min(n, p.row_bytes + 1 - offset_);
      offset_ += step;
      data += step;
      n -= step;
      if (offset_ < p.row_bytes + 1) continue;
      offset_ = 0;
      if (++row_ < p.rows) continue;
      row_ = 0;
      ++pass_;
    }
  }

  bool done() const { return pass_ == passes_.size(); }

 private:
  struct Pass {
    std::size_t rows, row_bytes;
  };
  std::vector<Pass> passes_;
  std::size_t pass_ = 0, row_ = 0, offset_ = 0;
  const std::string& path_;
};

/// Inflates the IDAT chunks' data with zlib, checking it against the header's rows.
void check_image_data(const std::string& bytes, const std::vector<Chunk>& idats,
                      const PngHeader& header, const std::string& path) {
  RowWalker rows(header, path);
  z_stream z{};
  if (inflateInit(&z) != Z_OK) fail(path, "cannot start zlib to check the PNG");
  std::vector<std::uint8_t> out(1 << 16);
  int status = Z_OK;
  for (const Chunk& c : idats) {
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data() + c.data()));
    z.avail_in = c.length;
    while (z.avail_in > 0 && status != Z_STREAM_END) {
      z.next_out = out.data();
      z.avail_out = static_cast<uInt>(out.size());
      status = inflate(&z, Z_NO_FLUSH);
      if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR) break;
      try {
        rows.consume(out.data(), out.size() - z.avail_out);
      } catch (...) {
        inflateEnd(&z);
        throw;
      }
    }
    if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR) break;
    if (status == Z_STREAM_END && z.avail_in > 0) status = Z_NEED_DICT;  // data after the end
  }
  inflateEnd(&z);
  if (status != Z_STREAM_END || !rows.done()) {
    fail(path, status == Z_OK || status == Z_BUF_ERROR || status == Z_STREAM_END
                   ? "the PNG is truncated: its image data ends before the last row"
                   : "the PNG is damaged: its compressed image data is invalid");
  }
}

/// The palette and transparency rules of the PNG format; whether the chunk is kept.
bool keep_chunk(const Chunk& c, const PngHeader& h, int palette_entries, const std::string& path) {
  if (c.type == "PLTE") {
    if (h.colour_type == 0 || h.colour_type == 4) fail(path, "the PNG has a palette but is grey");
    const int most = 1 << std::min(h.bit_depth, 8);
    if (c.length % 3 != 0 || c.length == 0 || static_cast<int>(c.length / 3) > most) {
      fail(path, "the PNG's palette has an invalid length of " + std::to_string(c.length));
    }
    return h.colour_type == 3;  // a suggested palette of an RGB image is not needed
  }
  if (c.type == "tRNS") {
    if (h.colour_type == 4 || h.colour_type == 6) return false;  // libpng ignores it
    const bool ok = h.colour_type == 0   ? c.length == 2
                    : h.colour_type == 2 ? c.length == 6
                                         : c.length <= static_cast<std::uint32_t>(palette_entries);
    if (!ok)
      fail(path, "the PNG's tRNS chunk has an invalid length of " + std::to_string(c.length));
    return true;
  }
  if (c.type == "IDAT" || c.type == "IEND") return true;
  if (c.type[0] >= 'A' && c.type[0] <= 'Z')
    fail(path, "the PNG has an unknown critical chunk " + c.type);
  return false;  // ancillary: text, gamma, colour profiles, ... do not change the pixels
}

/// The chunks that make the pixels, their order checked.
std::vector<Chunk> pixel_chunks(const std::vector<Chunk>& chunks, const PngHeader& h,
                                const std::string& path) {
  std::vector<Chunk> kept{chunks.front()};
  int palette_entries = 0;
  bool seen_idat = false;
  for (std::size_t k = 1; k < chunks.size(); ++k) {
    const Chunk& c = chunks[k];
    if (c.type == "IHDR") fail(path, "the PNG has a second IHDR chunk");
    const bool before_data = c.type == "PLTE" || c.type == "tRNS";
    if (before_data && (seen_idat || (c.type == "PLTE" && palette_entries > 0))) {
      fail(path, "the PNG's " + c.type + " chunk is out of order");
    }
    if (c.type == "tRNS" && h.colour_type == 3 && palette_entries == 0) {
      fail(path, "the PNG's tRNS chunk comes before its palette");
    }
    if (!keep_chunk(c, h, palette_entries, path)) continue;
    if (c.type == "PLTE") palette_entries = static_cast<int>(c.length / 3);
    if (c.type == "IDAT" && h.colour_type == 3 && palette_entries == 0) {
      fail(path, "the PNG is a palette image without a palette");
    }
    seen_idat = seen_idat || c.type == "IDAT";
    kept.push_back(c);
  }
  if (!seen_idat) fail(path, "the PNG has no image data (IDAT chunk)");
  return kept;
}

}  // namespace

bool looks_like_png(const std::string& bytes) {
  return bytes.compare(0, kSignatureBytes, kSignature, kSignatureBytes) == 0;
}

PngHeader read_png_header(const std::string& bytes, const std::string& path) {
  if (bytes.size() < kSignatureBytes + 25 || bytes.compare(kSignatureBytes + 4, 4, "IHDR") != 0 ||
      be32(bytes, kSignatureBytes) != 13) {
    fail(path, "the PNG lacks its IHDR header chunk");
  }
  const std::size_t at = kSignatureBytes + 8;
  PngHeader h;
  h.width = be32(bytes, at);
  h.height = be32(bytes, at + 4);
  h.bit_depth = static_cast<std::uint8_t>(bytes[at + 8]);
  h.colour_type = static_cast<std::uint8_t>(bytes[at + 9]);
  const int compression = bytes[at + 10], filter = bytes[at + 11], interlace = bytes[at + 12];
  h.interlaced = interlace == 1;
  if (!(h.width >= 1.0) || !(h.height >= 1.0) || h.width > 0x7fffffff || h.height > 0x7fffffff) {
    fail(path, "the PNG header declares " + std::to_string(std::int64_t(h.width)) + " x " +
                   std::to_string(std::int64_t(h.height)) + " pixels (a side of 0, or too long)");
  }
  if (!valid_depth(h.colour_type, h.bit_depth) || compression != 0 || filter != 0 ||
      interlace > 1) {
    fail(path, "the PNG header is invalid (colour type " + std::to_string(h.colour_type) +
                   ", bit depth " + std::to_string(h.bit_depth) + ")");
  }
  if (h.bit_depth == 16) fail(path, "only 8-bit images are supported (this PNG has 16 bits)");
  return h;
}

cv::Mat decode_png(const std::string& bytes, const PngHeader& header, const std::string& path) {
  const std::vector<Chunk> chunks = pixel_chunks(read_chunks(bytes, path), header, path);
  std::vector<Chunk> idats;
  for (const Chunk& c : chunks) {
    if (c.type == "IDAT") idats.push_back(c);
  }
  check_image_data(bytes, idats, header, path);
  std::vector<std::uint8_t> clean(bytes.begin(), bytes.begin() + kSignatureBytes);
  for (const Chunk& c : chunks)
    clean.insert(clean.end(), bytes.begin() + c.at, bytes.begin() + c.end());
  cv::Mat image;
  try {
    image = cv::imdecode(clean, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    fail(path, std::string("OpenCV cannot decode the PNG: ") + e.err);
  }
  if (image.empty()) fail(path, "OpenCV cannot decode the PNG");
  return image;
}

}  // namespace gridloc
