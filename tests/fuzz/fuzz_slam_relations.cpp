// Fuzz harness: a SLAM benchmark relations file read by load_slam_relations
// (sensors/src/slam_relations.cpp).
#include "fuzz_support.hpp"
#include "gridloc/sensors/slam_relations.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const gridloc::fuzz::ScratchFile file("fuzz.relations", data, size);
  const std::string path = file.path();
  gridloc::fuzz::expect_clean([&] { (void)gridloc::load_slam_relations(path); });
  return 0;
}
