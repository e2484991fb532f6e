// Fuzz harness: a scan CSV file read by load_scan_csv (sensors/src/range_scan.cpp) with the
// CLI's default maximum range.
#include "fuzz_support.hpp"
#include "gridloc/sensors/range_scan.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const gridloc::fuzz::ScratchFile file("scan.csv", data, size);
  const std::string path = file.path();
  gridloc::fuzz::expect_clean([&] { (void)gridloc::load_scan_csv(path, 8.0); });
  return 0;
}
