// Tests of engine/src/evaluation/metrics.cpp: the calibration measures of the evaluation
// (AUROC, failures flagged at 95 % recall).
#include "gridloc/engine/evaluation/metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace gridloc {
namespace {

TEST(Calibration, AurocAndFlaggedByHand) {
  // Positives 0.9, 0.8, 0.7; negatives 0.8, 0.1: pairs won 2 + 1 + 0.5(tie) + 1 + ... =
  // (0.9 > both: 2) + (0.8 > 0.1, tie with 0.8: 1.5) + (0.7 > 0.1: 1) = 4.5 of 6.
  EXPECT_DOUBLE_EQ(auroc({0.9, 0.8, 0.7}, {0.8, 0.1}), 0.75);
  EXPECT_DOUBLE_EQ(auroc({1.0}, {0.0, 0.5}), 1.0);
  EXPECT_TRUE(std::isnan(auroc({}, {0.1})));
  // 20 positives 0.05 .. 1.0: keeping 95 % (19) puts the threshold at 0.10; negatives 0.02
  // and 0.08 fall below it, 0.5 does not.
  std::vector<double> pos;
  for (int i = 1; i <= 20; ++i) pos.push_back(0.05 * i);
  EXPECT_NEAR(flagged_at_recall(pos, {0.02, 0.08, 0.5}, 0.95), 2.0 / 3.0, 1e-12);
  EXPECT_TRUE(std::isnan(flagged_at_recall(pos, {}, 0.95)));
}

}  // namespace
}  // namespace gridloc
