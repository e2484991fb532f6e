#pragma once
/// The calibration measures of the evaluation protocols (issue 4): how well a confidence
/// separates successes (positives) from failures (negatives).
#include <vector>

namespace gridloc {

/// The AUROC of `scores` for telling positives from negatives (Mann-Whitney; ties count
/// half); NaN when either group is empty.
double auroc(const std::vector<double>& positives, const std::vector<double>& negatives);

/// The share of `negatives` strictly below the `recall` quantile of `positives` (the highest
/// threshold that keeps at least `recall` of the positives at or above it); NaN when either
/// group is empty.
double flagged_at_recall(const std::vector<double>& positives, const std::vector<double>& negatives,
                         double recall);

}  // namespace gridloc
