#include "pnm_image.hpp"

#include <cctype>
#include <cstdint>
#include <vector>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

/// Values above this are reported as "too large" rather than accumulated further.
constexpr double kHugeNumber = 1e15;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(path + ": " + what);
}

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

/// Skips whitespace and, in the header, '#' comments running to the end of the line.
void skip_space(const std::string& bytes, std::size_t& at, bool comments) {
  while (at < bytes.size()) {
    if (is_space(bytes[at])) {
      ++at;
    } else if (comments && bytes[at] == '#') {
      while (at < bytes.size() && bytes[at] != '\n' && bytes[at] != '\r') ++at;
    } else {
      return;
    }
  }
}

/// The next decimal number at `at` (after whitespace), or -1 when there is none.
double read_number(const std::string& bytes, std::size_t& at, bool comments) {
  skip_space(bytes, at, comments);
  if (at >= bytes.size() || !std::isdigit(static_cast<unsigned char>(bytes[at]))) return -1.0;
  double value = 0.0;
  while (at < bytes.size() && std::isdigit(static_cast<unsigned char>(bytes[at]))) {
    if (value < kHugeNumber) value = value * 10.0 + (bytes[at] - '0');
    ++at;
  }
  return value;
}

std::string num(double v) {
  return v >= kHugeNumber ? std::string("a number too large") : std::to_string(std::int64_t(v));
}

double header_field(const std::string& bytes, std::size_t& at, const std::string& path,
                    const char* field) {
  const double value = read_number(bytes, at, true);
  if (value < 0.0) fail(path, std::string("the image header lacks its ") + field);
  return value;
}

/// Checks one sample against the maxval and scales it to 0..255.
std::uint8_t sample(double value, const PnmHeader& header, std::size_t index,
                    const std::string& path) {
  if (value > header.maxval) {
    const std::size_t pixel = index / header.channels;
    const auto width = static_cast<std::size_t>(header.width);
    fail(path, "pixel (row " + std::to_string(pixel / width) + ", column " +
                   std::to_string(pixel % width) + ") is " + num(value) + ", above the maxval " +
                   std::to_string(header.maxval));
  }
  const int v = static_cast<int>(value);
  return static_cast<std::uint8_t>(header.maxval == 255 ? v : v * 255 / header.maxval);
}

}  // namespace

bool looks_like_pnm(const std::string& bytes) {
  return bytes.size() >= 2 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '7';
}

PnmHeader read_pnm_header(const std::string& bytes, const std::string& path) {
  PnmHeader h;
  const char kind = looks_like_pnm(bytes) ? bytes[1] : '?';
  if (kind != '2' && kind != '3' && kind != '5' && kind != '6') {
    fail(path, "only PGM (P2, P5) and PPM (P3, P6) Netpbm images are supported");
  }
  h.ascii = kind == '2' || kind == '3';
  h.channels = (kind == '3' || kind == '6') ? 3 : 1;
  std::size_t at = 2;
  h.width = header_field(bytes, at, path, "width");
  h.height = header_field(bytes, at, path, "height");
  const double maxval = header_field(bytes, at, path, "maxval");
  if (!(h.width >= 1.0) || !(h.height >= 1.0)) {
    fail(path, "the image header declares " + num(h.width) + " x " + num(h.height) +
                   " pixels (a side of 0)");
  }
  if (maxval < 1.0) fail(path, "the image header declares a maxval of 0");
  if (maxval > 255.0) {
    fail(path, "16-bit images are not supported (maxval " + num(maxval) +
                   "); save the map with maxval 255");
  }
  h.maxval = static_cast<int>(maxval);
  if (at >= bytes.size() || !is_space(bytes[at])) {
    fail(path, "the image header must end with one whitespace character after the maxval");
  }
  h.data_at = at + 1;  // binary samples start right after that one character
  return h;
}

Image decode_pnm(const std::string& bytes, const PnmHeader& header, const std::string& path) {
  const auto width = static_cast<int>(header.width), height = static_cast<int>(header.height);
  const std::size_t samples =
      static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * header.channels;
  if (!header.ascii && bytes.size() - header.data_at < samples) {
    fail(path, "the image is truncated: " + std::to_string(bytes.size() - header.data_at) +
                   " bytes of pixels where the header declares " + std::to_string(width) + " x " +
                   std::to_string(height) + " (" + std::to_string(samples) + " bytes)");
  }
  Image image(width, height, header.channels);
  std::uint8_t* out = image.pixels.data();
  std::size_t at = header.data_at;
  for (std::size_t i = 0; i < samples; ++i) {
    double value = 0.0;
    if (header.ascii) {
      value = read_number(bytes, at, false);
      if (value < 0.0) {
        fail(path, "the image is truncated or malformed: sample " + std::to_string(i) + " of " +
                       std::to_string(samples) + " is not a number");
      }
    } else {
      value = static_cast<std::uint8_t>(bytes[at++]);
    }
    out[i] = sample(value, header, i, path);
  }
  return image;
}

}  // namespace gridloc
