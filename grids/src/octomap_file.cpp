// OctoMap files read into memory and their headers parsed (see octomap_file.hpp). The header
// is read as octomap's AbstractOcTree::readHeader reads it: whitespace-separated keywords,
// each value the next token, '#' starting a comment to the end of its line, `data` ending the
// header at the end of its line; but an unknown or repeated keyword, a missing value or one
// that is not a number is an error here rather than a warning on stderr.
#include "octomap_file.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <new>
#include <optional>
#include <string_view>

#include "gridloc/grids/error.hpp"

namespace gridloc::octomap_detail {
namespace {

// The first line of each kind of OctoMap file (octomap's AbstractOcTree / AbstractOccupancyOcTree).
constexpr std::string_view kBinaryHeader = "# Octomap OcTree binary file";
constexpr std::string_view kFullHeader = "# Octomap OcTree file";
// Leaf sizes (m) whose voxel coordinates octomap's float points and our leaf-unit arithmetic
// hold exactly enough: 32768 leaves either side of the origin.
constexpr double kMinResolution = 1e-6, kMaxResolution = 1e6;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(path + ": " + what);
}

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r';
}

// At most 40 characters of `text` for a message, each unprintable one as '?'.
std::string shown(std::string_view text) {
  std::string out(text.substr(0, 40));
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  }
  return out;
}

// The file's bytes, once it is known to be a regular file within limits.max_file_mb.
std::string read_bytes(const std::string& path, bool binary, const ResourceLimits& limits) {
  const std::string what = binary ? "binary OctoMap (.bt)" : "full OctoMap (.ot)";
  try {
    return read_input_file(path, what, limits);
  } catch (const std::bad_alloc&) {
    fail(path, "not enough memory to read the " + what);
  }
}

// The tree's memory in octomap and the file's bytes, estimated before either is allocated.
void check_tree_memory(const std::string& path, std::uint64_t nodes, std::size_t file_bytes,
                       const ResourceLimits& limits) {
  const double bytes =
      kTreeBytesPerNode * static_cast<double>(nodes) + static_cast<double>(file_bytes);
  check_memory(bytes, limits, path + ": the OctoMap tree of " + std::to_string(nodes) + " nodes");
}

// Reads the header's tokens from the bytes after the first line.
class HeaderScanner {
 public:
  HeaderScanner(const std::string& bytes, std::size_t pos) : bytes_(bytes), pos_(pos) {}

  /// The next whitespace-separated token, or "" at the end of the bytes.
  std::string_view token() {
    while (pos_ < bytes_.size() && is_blank(bytes_[pos_])) ++pos_;
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && !is_blank(bytes_[pos_])) ++pos_;
    return std::string_view(bytes_).substr(start, pos_ - start);
  }
  /// The rest of the current line (without its '\n'), moving past the '\n'.
  std::string_view rest_of_line() {
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && bytes_[pos_] != '\n') ++pos_;
    const std::string_view rest = std::string_view(bytes_).substr(start, pos_ - start);
    if (pos_ < bytes_.size()) ++pos_;
    return rest;
  }
  std::size_t pos() const { return pos_; }

 private:
  const std::string& bytes_;
  std::size_t pos_;
};

// The header's values as written, before they are checked.
struct RawHeader {
  std::optional<std::string> id, size, res;
  bool data_seen = false;
};

// The keyword's value (the next token) into `slot`, once.
void take_value(const std::string& path, HeaderScanner& scan, std::string_view keyword,
                std::optional<std::string>& slot) {
  if (slot) fail(path, "the OctoMap header gives '" + std::string(keyword) + "' twice");
  const std::string_view value = scan.token();
  if (value.empty())
    fail(path, "the OctoMap header ends before the value of '" + std::string(keyword) + "'");
  slot = std::string(value);
}

// Scans keywords up to and including the `data` line; returns where the data starts.
std::size_t scan_header(const std::string& path, const std::string& bytes, std::size_t pos,
                        RawHeader& raw) {
  HeaderScanner scan(bytes, pos);
  while (!raw.data_seen) {
    const std::string_view token = scan.token();
    if (token.empty()) fail(path, "the OctoMap header ends without a 'data' line");
    if (token == "data") {
      const std::string_view rest = scan.rest_of_line();
      for (char c : rest) {
        if (!is_blank(c)) fail(path, "the OctoMap header's 'data' line holds more than 'data'");
      }
      raw.data_seen = true;
    } else if (token.front() == '#') {
      scan.rest_of_line();
    } else if (token == "id") {
      take_value(path, scan, token, raw.id);
    } else if (token == "size") {
      take_value(path, scan, token, raw.size);
    } else if (token == "res") {
      take_value(path, scan, token, raw.res);
    } else {
      fail(path, "unknown keyword '" + shown(token) +
                     "' in the OctoMap header (expected id, size, res, data)");
    }
  }
  return scan.pos();
}

std::uint64_t parse_size(const std::string& path, const std::optional<std::string>& text) {
  if (!text) fail(path, "the OctoMap header has no 'size' (the tree's node count)");
  std::uint64_t size = 0;
  const char* end = text->data() + text->size();
  const auto [ptr, ec] = std::from_chars(text->data(), end, size);
  if (ec != std::errc() || ptr != end || size > std::numeric_limits<std::uint32_t>::max()) {
    fail(path, "the OctoMap header's size '" + shown(*text) +
                   "' is not a node count (a whole number below 2^32)");
  }
  return size;
}

double parse_resolution(const std::string& path, const std::optional<std::string>& text) {
  if (!text) fail(path, "the OctoMap header has no 'res' (the leaf size)");
  double res = 0.0;
  const char* end = text->data() + text->size();
  const auto [ptr, ec] = std::from_chars(text->data(), end, res);
  if (ec != std::errc() || ptr != end || !std::isfinite(res)) {
    fail(path, "the OctoMap header's res '" + shown(*text) + "' is not a number");
  }
  if (!(res >= kMinResolution && res <= kMaxResolution)) {
    fail(path,
         "the OctoMap header's res " + shown(*text) + " is not a leaf size from 1e-6 to 1e6 m");
  }
  return res;
}

// The first line must be octomap's for the kind the extension names.
std::size_t check_first_line(const std::string& path, const std::string& bytes, bool binary) {
  const std::string_view header = binary ? kBinaryHeader : kFullHeader;
  const std::size_t eol = bytes.find('\n');
  const std::string_view first = std::string_view(bytes).substr(0, eol);
  if (first.substr(0, header.size()) != header) {
    fail(path, std::string("not an OctoMap ") + (binary ? "binary (.bt)" : "full (.ot)") +
                   " file: the first line is not '" + std::string(header) + "'");
  }
  return eol == std::string::npos ? bytes.size() : eol + 1;
}

}  // namespace

OctomapFile read_octomap_file(const std::string& path, bool binary, const ResourceLimits& limits) {
  std::string bytes = read_bytes(path, binary, limits);
  RawHeader raw;
  const std::size_t data_offset =
      scan_header(path, bytes, check_first_line(path, bytes, binary), raw);
  OctomapFile file;
  file.binary = binary;
  if (!raw.id) fail(path, "the OctoMap header has no 'id' (the tree type)");
  // A .bt holds occupancy codes whatever its id; a .ot holds each node's value, whose layout
  // depends on the type ("1": octomap's deprecated id of an OcTree).
  if (!binary && *raw.id != "OcTree" && *raw.id != "1") {
    fail(path, "holds an OctoMap " + shown(*raw.id) + ", not an OcTree");
  }
  file.id = *raw.id;
  file.size = parse_size(path, raw.size);
  check_tree_memory(path, file.size, bytes.size(), limits);
  file.resolution = parse_resolution(path, raw.res);
  file.data_offset = data_offset;
  bytes.erase(0, data_offset);
  file.data = std::move(bytes);
  return file;
}

}  // namespace gridloc::octomap_detail
