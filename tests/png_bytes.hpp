#pragma once
// Hand-made PNG files for the map image tests: a valid grey image written with a stored
// (uncompressed) zlib stream, so that tests can cut, damage or resize it byte by byte without
// linking an image library.
#include <cstdint>
#include <string>
#include <vector>

namespace gridloc::test {

inline std::uint32_t png_crc(const std::string& bytes) {
  std::uint32_t crc = 0xffffffffu;
  for (unsigned char b : bytes) {
    crc ^= b;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return crc ^ 0xffffffffu;
}

inline std::string be32(std::uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
          static_cast<char>(v)};
}

/// One chunk: length, type, data, CRC.
inline std::string png_chunk(const std::string& type, const std::string& data) {
  return be32(static_cast<std::uint32_t>(data.size())) + type + data + be32(png_crc(type + data));
}

/// The IHDR chunk of an 8-bit grey image of width x height.
inline std::string png_ihdr(std::uint32_t width, std::uint32_t height) {
  return png_chunk("IHDR", be32(width) + be32(height) + std::string("\x08\x00\x00\x00\x00", 5));
}

/// A zlib stream of `raw` in one stored block (raw must be under 65536 bytes).
inline std::string zlib_stored(const std::string& raw) {
  std::uint32_t a = 1, b = 0;
  for (unsigned char c : raw) a = (a + c) % 65521, b = (b + a) % 65521;
  const auto len = static_cast<std::uint16_t>(raw.size());
  std::string z = "\x78\x01\x01";
  z += static_cast<char>(len & 0xff);
  z += static_cast<char>(len >> 8);
  z += static_cast<char>(~len & 0xff);
  z += static_cast<char>((~len >> 8) & 0xff);
  return z + raw + be32((b << 16) | a);
}

/// An 8-bit grey PNG of `rows` (each a row of pixels from the top, all of one width).
inline std::string grey_png(const std::vector<std::vector<std::uint8_t>>& rows) {
  std::string raw;
  for (const auto& row : rows) {
    raw += '\0';  // filter type None
    raw.append(row.begin(), row.end());
  }
  const auto width = static_cast<std::uint32_t>(rows.empty() ? 0 : rows.front().size());
  return "\x89PNG\r\n\x1a\n" + png_ihdr(width, static_cast<std::uint32_t>(rows.size())) +
         png_chunk("IDAT", zlib_stored(raw)) + png_chunk("IEND", "");
}

}  // namespace gridloc::test
