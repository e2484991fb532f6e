// Fuzz harness: a full OctoMap tree (.ot) read by load_octomap (grids/src/octomap_io.cpp,
// AbstractOcTree::read) and sliced with the default band.
#include "fuzz_support.hpp"
#include "gridloc/grids/octomap_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const gridloc::fuzz::ScratchFile file("tree.ot", data, size);
  const std::string path = file.path();
  gridloc::fuzz::expect_clean([&] { (void)gridloc::load_octomap(path); });
  return 0;
}
