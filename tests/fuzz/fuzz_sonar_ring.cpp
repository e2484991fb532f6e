// Fuzz harness: a sonar ring YAML file read by load_sonar_ring (sensors/src/sonar_ring.cpp).
#include "fuzz_support.hpp"
#include "gridloc/sensors/sonar_ring.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const gridloc::fuzz::ScratchFile file("ring.yaml", data, size);
  const std::string path = file.path();
  gridloc::fuzz::expect_clean([&] { (void)gridloc::load_sonar_ring(path); });
  return 0;
}
