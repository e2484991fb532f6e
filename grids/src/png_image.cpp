#include "png_image.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
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

/// The palette (PLTE) and transparency (tRNS) of an image, as libpng applied them for OpenCV.
struct Colours {
  /// R, G, B, alpha of each palette index; indices past the PLTE entries are opaque black.
  std::array<std::array<std::uint8_t, 4>, 256> palette{};
  bool transparent = false;  ///< a tRNS chunk adds an alpha channel (RGB and palette images)
  std::array<std::uint8_t, 3> key{};  ///< an RGB image's transparent colour (low bytes)
};

/// The palette and transparency of the kept chunks (pixel_chunks). A grey image's tRNS is
/// ignored and an empty palette tRNS means no transparency, as OpenCV's libpng did.
Colours read_colours(const std::string& bytes, const std::vector<Chunk>& chunks,
                     const PngHeader& h) {
  Colours colours;
  for (auto& entry : colours.palette) entry = {0, 0, 0, 255};
  const auto at = [&](const Chunk& c, std::size_t k) {
    return static_cast<std::uint8_t>(bytes[c.data() + k]);
  };
  for (const Chunk& c : chunks) {
    if (c.type == "PLTE") {
      for (std::size_t i = 0; i < c.length / 3; ++i)
        colours.palette[i] = {at(c, 3 * i), at(c, 3 * i + 1), at(c, 3 * i + 2), 255};
    } else if (c.type == "tRNS" && h.colour_type == 3 && c.length > 0) {
      colours.transparent = true;
      for (std::size_t i = 0; i < c.length; ++i) colours.palette[i][3] = at(c, i);
    } else if (c.type == "tRNS" && h.colour_type == 2) {
      colours.transparent = true;
      colours.key = {at(c, 1), at(c, 3), at(c, 5)};  // 16-bit samples: an 8-bit image's low byte
    }
  }
  return colours;
}

/// The channels of the decoded image: OpenCV's IMREAD_UNCHANGED (grey 1; RGB and palette 3,
/// or 4 with a tRNS chunk; grey + alpha and RGB + alpha 4), in R, G, B, alpha order.
int output_channels(const PngHeader& h, const Colours& colours) {
  switch (h.colour_type) {
    case 0:
      return 1;
    case 2:
    case 3:
      return colours.transparent ? 4 : 3;
    default:
      return 4;
  }
}

/// The `i`-th sample of a row packed at `depth` (1, 2 or 4) bits, the leftmost in the high
/// bits of each byte.
std::uint8_t packed_sample(const std::uint8_t* row, std::size_t i, int depth) {
  const std::size_t bit = i * static_cast<std::size_t>(depth);
  const int shift = 8 - depth - static_cast<int>(bit % 8);
  return static_cast<std::uint8_t>((row[bit / 8] >> shift) & ((1 << depth) - 1));
}

/// Writes unfiltered rows of pixels into the decoded image, in its output channels.
class PixelWriter {
 public:
  PixelWriter(const PngHeader& h, const Colours& colours, Image& image)
      : header_(h), colours_(colours), image_(image) {}

  /// Writes `cols` pixels of `row`, the first at column `x0`, then every `dx`, in image row y.
  void put_row(const std::uint8_t* row, std::size_t cols, std::size_t x0, std::size_t dx,
               std::size_t y) const {
    std::uint8_t* out = image_.row(static_cast<int>(y));
    const auto channels = static_cast<std::size_t>(image_.channels);
    for (std::size_t i = 0; i < cols; ++i) {
      const std::array<std::uint8_t, 4> rgba = pixel(row, i);
      std::copy_n(rgba.begin(), channels, out + (x0 + i * dx) * channels);
    }
  }

 private:
  /// Pixel `i` of an unfiltered row as R, G, B, alpha (grey: the grey level first).
  std::array<std::uint8_t, 4> pixel(const std::uint8_t* row, std::size_t i) const {
    const int depth = header_.bit_depth;
    switch (header_.colour_type) {
      case 0: {  // grey: 1, 2 and 4 bits scaled to 0..255 (as png_set_expand_gray_1_2_4_to_8)
        const int level =
            depth == 8 ? row[i] : packed_sample(row, i, depth) * 255 / ((1 << depth) - 1);
        const auto v = static_cast<std::uint8_t>(level);
        return {v, v, v, 255};
      }
      case 3:
        return colours_.palette[depth == 8 ? row[i] : packed_sample(row, i, depth)];
      case 4:
        return {row[2 * i], row[2 * i], row[2 * i], row[2 * i + 1]};
      case 2: {
        const std::uint8_t* p = row + 3 * i;
        const bool keyed = colours_.transparent && p[0] == colours_.key[0] &&
                           p[1] == colours_.key[1] && p[2] == colours_.key[2];
        return {p[0], p[1], p[2], static_cast<std::uint8_t>(keyed ? 0 : 255)};
      }
      default:
        return {row[4 * i], row[4 * i + 1], row[4 * i + 2], row[4 * i + 3]};
    }
  }

  const PngHeader& header_;
  const Colours& colours_;
  Image& image_;
};

/// The Paeth predictor of the PNG format: whichever of left, up and up-left is closest to
/// left + up - up_left (ties in that order).
int paeth(int left, int up, int up_left) {
  const int estimate = left + up - up_left;
  const int to_left = std::abs(estimate - left), to_up = std::abs(estimate - up),
            to_up_left = std::abs(estimate - up_left);
  if (to_left <= to_up && to_left <= to_up_left) return left;
  return to_up <= to_up_left ? up : up_left;
}

/// Undoes the row filter `filter` (0 None, 1 Sub, 2 Up, 3 Average, 4 Paeth) of the
/// `row_bytes` bytes of `row` in place; `above` is the unfiltered row above (zeros for the
/// first row of a pass) and `pixel_bytes` the bytes per pixel, at least 1.
void unfilter_row(int filter, std::uint8_t* row, const std::uint8_t* above, std::size_t row_bytes,
                  std::size_t pixel_bytes) {
  for (std::size_t i = 0; i < row_bytes; ++i) {
    const int left = i >= pixel_bytes ? row[i - pixel_bytes] : 0;
    const int up = above[i];
    const int up_left = i >= pixel_bytes ? above[i - pixel_bytes] : 0;
    int predicted = 0;
    switch (filter) {
      case 1:
        predicted = left;
        break;
      case 2:
        predicted = up;
        break;
      case 3:
        predicted = (left + up) / 2;
        break;
      case 4:
        predicted = paeth(left, up, up_left);
        break;
      default:
        break;
    }
    row[i] = static_cast<std::uint8_t>(row[i] + predicted);
  }
}

/// Walks the inflated image data row by row (the 7 passes of an interlaced image), checking
/// that each row starts with a known filter type and that the data has exactly the rows the
/// header declares; each row is unfiltered and its pixels written as it completes, so only
/// two rows of the image data are held at once.
class RowDecoder {
 public:
  RowDecoder(const PngHeader& h, const PixelWriter& writer, const std::string& path)
      : writer_(writer), path_(path) {
    const auto w = static_cast<std::size_t>(h.width), ht = static_cast<std::size_t>(h.height);
    const std::size_t bits =
        static_cast<std::size_t>(h.bit_depth) * samples_per_pixel(h.colour_type);
    pixel_bytes_ = std::max<std::size_t>(1, bits / 8);
    const auto add = [&](std::size_t x0, std::size_t y0, std::size_t dx, std::size_t dy) {
      const std::size_t cols = w > x0 ? (w - x0 + dx - 1) / dx : 0;
      const std::size_t rows = ht > y0 ? (ht - y0 + dy - 1) / dy : 0;
      if (cols > 0 && rows > 0)
        passes_.push_back({x0, y0, dx, dy, cols, rows, (cols * bits + 7) / 8});
    };
    if (!h.interlaced) {
      add(0, 0, 1, 1);
    } else {
      constexpr std::array<std::array<std::size_t, 4>, 7> kAdam7 = {{{0, 0, 8, 8},
                                                                     {4, 0, 8, 8},
                                                                     {0, 4, 4, 8},
                                                                     {2, 0, 4, 4},
                                                                     {0, 2, 2, 4},
                                                                     {1, 0, 2, 2},
                                                                     {0, 1, 1, 2}}};
      for (const auto& [x0, y0, dx, dy] : kAdam7) add(x0, y0, dx, dy);
    }
    start_pass();
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
      std::copy_n(data, step, row_.begin() + static_cast<std::ptrdiff_t>(offset_));
      offset_ += step;
      data += step;
      n -= step;
      if (offset_ == p.row_bytes + 1) finish_row();
    }
  }

  bool done() const { return pass_ == passes_.size(); }

 private:
  struct Pass {
    std::size_t x0, y0, dx, dy;  ///< the pass's first pixel and its steps (Adam7)
    std::size_t cols, rows, row_bytes;
  };

  /// The rows of the pass begin: the row above its first is zeros.
  void start_pass() {
    if (done()) return;
    row_.assign(passes_[pass_].row_bytes + 1, 0);  // [0] is the filter type
    above_.assign(passes_[pass_].row_bytes + 1, 0);
  }

  void finish_row() {
    const Pass& p = passes_[pass_];
    unfilter_row(row_[0], row_.data() + 1, above_.data() + 1, p.row_bytes, pixel_bytes_);
    writer_.put_row(row_.data() + 1, p.cols, p.x0, p.dx, p.y0 + row_in_pass_ * p.dy);
    std::swap(row_, above_);
    offset_ = 0;
    if (++row_in_pass_ < p.rows) return;
    row_in_pass_ = 0;
    ++pass_;
    start_pass();
  }

  std::vector<Pass> passes_;
  std::size_t pixel_bytes_ = 1;
  std::size_t pass_ = 0, row_in_pass_ = 0, offset_ = 0;
  std::vector<std::uint8_t> row_, above_;  ///< the row being read; the one above, unfiltered
  const PixelWriter& writer_;
  const std::string& path_;
};

/// Inflates the IDAT chunks' data with zlib, checking it against the header's rows and
/// decoding each row with `writer`.
void decode_image_data(const std::string& bytes, const std::vector<Chunk>& idats,
                       const PngHeader& header, const PixelWriter& writer,
                       const std::string& path) {
  RowDecoder rows(header, writer, path);
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
  const int compression = static_cast<unsigned char>(bytes[at + 10]);
  const int filter = static_cast<unsigned char>(bytes[at + 11]);
  const int interlace = static_cast<unsigned char>(bytes[at + 12]);
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

Image decode_png(const std::string& bytes, const PngHeader& header, const std::string& path) {
  const std::vector<Chunk> chunks = pixel_chunks(read_chunks(bytes, path), header, path);
  std::vector<Chunk> idats;
  for (const Chunk& c : chunks) {
    if (c.type == "IDAT") idats.push_back(c);
  }
  const Colours colours = read_colours(bytes, chunks, header);
  Image image(static_cast<int>(header.width), static_cast<int>(header.height),
              output_channels(header, colours));
  decode_image_data(bytes, idats, header, PixelWriter(header, colours, image), path);
  return image;
}

}  // namespace gridloc
