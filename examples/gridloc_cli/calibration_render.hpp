#pragma once
// The calibration plot (issue 19): for each configuration, the share of its `localized`
// answers whose position error lies within the reported covariance's p ellipse against p;
// a calibrated covariance follows the diagonal, a padded one runs above it, an optimistic
// one below.
#include <string>
#include <vector>

namespace gridloc::cli {

struct CoverageCurve {
  std::string label;             ///< the legend's text
  std::vector<double> observed;  ///< one per level (NaN: none localized)
};

/// Draws the curves over `levels` (the nominal probabilities, each in (0, 1)) under `title`
/// and `caption`, and writes the PNG; gridloc::Error naming `path` when it cannot.
void write_calibration_plot(const std::string& path, const std::string& title,
                            const std::string& caption, const std::vector<double>& levels,
                            const std::vector<CoverageCurve>& curves);

}  // namespace gridloc::cli
