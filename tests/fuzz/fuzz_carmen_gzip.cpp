// Fuzz harness: a CARMEN log file read by load_carmen_log, which inflates gzip content
// (sensors/src/gzip_stream.cpp) and reads plain text as it is (sensors/src/carmen_log.cpp).
// The decompressed size is capped at 64 MiB so that the harness stays within libFuzzer's
// memory limit; the cap itself is under test.
#include "fuzz_support.hpp"
#include "gridloc/sensors/carmen_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const gridloc::fuzz::ScratchFile file("fuzz.log.gz", data, size);
  const std::string path = file.path();
  gridloc::CarmenOptions options;
  options.max_decompressed_bytes = std::size_t{64} << 20;
  gridloc::fuzz::expect_clean([&] { (void)gridloc::load_carmen_log(path, options); });
  return 0;
}
