#pragma once
// A read-only stream over a gzip-compressed or plain file (internal to gridloc::sensors):
// zlib's gzread decompresses gzip and passes plain files through unchanged. The bytes read
// are bounded, and a corrupt or truncated gzip is reported, not read as text.
#include <zlib.h>

#include <cstddef>
#include <istream>
#include <streambuf>
#include <string>
#include <vector>

namespace gridloc::detail {

/// The stream buffer: fills from gzread until the end, an error or `max_bytes`.
class GzipBuffer : public std::streambuf {
 public:
  GzipBuffer(const std::string& path, std::size_t max_bytes);
  ~GzipBuffer() override;
  GzipBuffer(const GzipBuffer&) = delete;
  GzipBuffer& operator=(const GzipBuffer&) = delete;

  /// What went wrong, or "" when the file was read to its end (or not yet).
  const std::string& problem() const { return problem_; }

 protected:
  int_type underflow() override;

 private:
  std::string path_;
  gzFile file_ = nullptr;
  std::vector<char> buffer_;
  std::size_t max_bytes_ = 0;
  std::size_t read_ = 0;
  std::string problem_;
};

/// An std::istream reading `path` through a GzipBuffer. Throws gridloc::Error naming the file
/// when it cannot be opened.
class GzipStream : public std::istream {
 public:
  GzipStream(const std::string& path, std::size_t max_bytes);

  /// Throws gridloc::Error naming the file when the read stopped short: a corrupt or truncated
  /// gzip, a read error, or more than max_bytes of (decompressed) text.
  void check() const;

 private:
  std::string path_;
  GzipBuffer buffer_;
};

}  // namespace gridloc::detail
