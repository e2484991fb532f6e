// Fuzz harness: a readings JSON file read by load_readings and load_firings
// (sensors/src/readings_io.cpp).
#include "fuzz_support.hpp"
#include "gridloc/sensors/readings_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const gridloc::fuzz::ScratchFile file("readings.json", data, size);
  const std::string path = file.path();
  gridloc::fuzz::expect_clean([&] { (void)gridloc::load_readings(path); });
  gridloc::fuzz::expect_clean([&] { (void)gridloc::load_firings(path); });
  return 0;
}
