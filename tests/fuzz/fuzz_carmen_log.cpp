// Fuzz harness: CARMEN log text parsed by parse_carmen_log from a stream
// (sensors/src/carmen_log.cpp).
#include <sstream>

#include "fuzz_support.hpp"
#include "gridloc/sensors/carmen_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in{std::string(gridloc::fuzz::as_text(data, size))};
  gridloc::fuzz::expect_clean([&] { (void)gridloc::parse_carmen_log(in, "fuzz.log"); });
  return 0;
}
