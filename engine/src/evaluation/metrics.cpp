// The calibration measures of the evaluation protocols (metrics.hpp).
#include "gridloc/engine/evaluation/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace gridloc {

double auroc(const std::vector<double>& positives, const std::vector<double>& negatives) {
  if (positives.empty() || negatives.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> neg = negatives;
  std::sort(neg.begin(), neg.end());
  double wins = 0.0;  // pairs where the positive scores higher, ties counting half
  for (double p : positives) {
    const auto below = std::lower_bound(neg.begin(), neg.end(), p) - neg.begin();
    const auto not_above = std::upper_bound(neg.begin(), neg.end(), p) - neg.begin();
    wins += static_cast<double>(below) + 0.5 * static_cast<double>(not_above - below);
  }
  return wins / (static_cast<double>(positives.size()) * static_cast<double>(neg.size()));
}

double flagged_at_recall(const std::vector<double>& positives, const std::vector<double>& negatives,
                         double recall) {
  if (positives.empty() || negatives.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> pos = positives;
  std::sort(pos.begin(), pos.end(), std::greater<>());
  // The highest threshold with at least `recall` of the positives at or above it.
  const auto keep = static_cast<std::size_t>(std::ceil(recall * static_cast<double>(pos.size())));
  const double threshold = pos[std::clamp<std::size_t>(keep, 1, pos.size()) - 1];
  const auto flagged =
      std::count_if(negatives.begin(), negatives.end(), [&](double v) { return v < threshold; });
  return static_cast<double>(flagged) / static_cast<double>(negatives.size());
}

}  // namespace gridloc
