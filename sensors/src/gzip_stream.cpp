#include "gzip_stream.hpp"

#include <cerrno>
#include <cstring>

#include "gridloc/grids/error.hpp"

namespace gridloc::detail {
namespace {

constexpr unsigned kChunk = 1u << 17;  // bytes per gzread

/// What a gzread error code means, in words; `message` is gzerror's, which starts with the
/// file's path (dropped: the caller names the file).
std::string describe_gzip_error(int code, std::string message, const std::string& path) {
  if (message.rfind(path + ": ", 0) == 0) message.erase(0, path.size() + 2);
  switch (code) {
    case Z_ERRNO:
      return std::string("read error: ") + std::strerror(errno);
    case Z_BUF_ERROR:
      return "truncated gzip (" + message + ")";
    case Z_MEM_ERROR:
      return "out of memory while decompressing";
    default:
      return "corrupt gzip data (" + message + ")";
  }
}

}  // namespace

GzipBuffer::GzipBuffer(const std::string& path, std::size_t max_bytes)
    : path_(path), buffer_(kChunk), max_bytes_(max_bytes) {
  file_ = gzopen(path.c_str(), "rb");
  if (file_ == nullptr) {
    throw Error(path + ": cannot open: " + std::strerror(errno != 0 ? errno : ENOMEM));
  }
  gzbuffer(file_, kChunk);
}

GzipBuffer::~GzipBuffer() {
  if (file_ != nullptr) gzclose(file_);
}

GzipBuffer::int_type GzipBuffer::underflow() {
  if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
  if (!problem_.empty()) return traits_type::eof();
  const int got = gzread(file_, buffer_.data(), kChunk);
  int code = Z_OK;
  const char* message = gzerror(file_, &code);
  // gzread returns -1 on an error, and 0 both at a clean end and when a gzip stream stops
  // early (truncated); gzerror tells them apart.
  if (got <= 0) {
    if (code != Z_OK && code != Z_STREAM_END) problem_ = describe_gzip_error(code, message, path_);
    return traits_type::eof();
  }
  read_ += static_cast<std::size_t>(got);
  if (read_ > max_bytes_) {
    problem_ = "more than " + std::to_string(max_bytes_) +
               " bytes of text (the limit CarmenOptions::max_decompressed_bytes)";
    return traits_type::eof();
  }
  setg(buffer_.data(), buffer_.data(), buffer_.data() + got);
  return traits_type::to_int_type(*gptr());
}

GzipStream::GzipStream(const std::string& path, std::size_t max_bytes)
    : std::istream(nullptr), path_(path), buffer_(path, max_bytes) {
  rdbuf(&buffer_);
}

void GzipStream::check() const {
  if (!buffer_.problem().empty()) {
    throw Error(path_ + ": cannot read the CARMEN log to its end: " + buffer_.problem());
  }
}

}  // namespace gridloc::detail
