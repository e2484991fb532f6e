// Tests of engine/src/sectors/scan_label.cpp (seed 000 §3.2): CONSTRUCT SCAN LABEL and cyclic
// matching.
#include "gridloc/engine/sectors/scan_label.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "test_support.hpp"

namespace gridloc {
namespace {

RangeScan ranges(const std::vector<double>& r, double max_range = 10.0) {
  RangeScan s;
  s.max_range = max_range;
  for (std::size_t k = 0; k < r.size(); ++k) {
    s.angles.push_back(2.0 * std::numbers::pi * static_cast<double>(k) / r.size());
    s.ranges.push_back(r[k]);
  }
  return s;
}

TEST(ScanLabel, ExtremaAndDiscontinuitiesInBeamOrder) {
  ScanLabelOptions o;
  o.median_window = 1;
  o.prominence_m = 0.0;
  // A rise to a maximum, a fall to a minimum, then a jump to far and back.
  const ScanLabel l =
      construct_scan_label(ranges({2.0, 2.5, 3.0, 2.5, 2.0, 1.5, 1.8, 6.0, 6.2, 1.9}, 10.0), o);
  // beam 2 M, beam 5 m, jump 6->7 (near 6: D, far 7: c), max at 8? 8 is next to the jump
  // back 8->9 (far 8: c, near 9: D). Beam 0 after 9 (1.9 -> 2.0) rises: no extremum at 0.
  EXPECT_EQ(l.label, "MmDccD");
  EXPECT_EQ(l.beam, (std::vector<int>{2, 5, 6, 7, 8, 9}));
}

TEST(ScanLabel, ProminenceDropsNoiseAndMedianSmooths) {
  // A flat wall at 3 m with +-1 cm wiggles: no characteristic point survives.
  std::vector<double> r;
  for (int k = 0; k < 90; ++k) r.push_back(3.0 + (k % 2 ? 0.01 : -0.01));
  r[40] = 3.5;  // one spike: the median filter removes it
  EXPECT_EQ(construct_scan_label(ranges(r)).label, "");
  ScanLabelOptions raw;
  raw.median_window = 1;
  raw.prominence_m = 0.0;
  EXPECT_GT(construct_scan_label(ranges(r), raw).label.size(), 40u);
  ScanLabelOptions bad;
  bad.median_window = 2;
  test::expect_error([&] { construct_scan_label(ranges(r), bad); }, {"median_window"});
}

TEST(ScanLabel, CyclicEqual) {
  int shift = -1;
  EXPECT_TRUE(cyclic_equal("DcMm", "MmDc", &shift));
  EXPECT_EQ(shift, 2);
  EXPECT_FALSE(cyclic_equal("DcMm", "cDMm"));  // a reversal is not a turn
  EXPECT_FALSE(cyclic_equal("Mm", "MmMm"));
}

}  // namespace
}  // namespace gridloc
