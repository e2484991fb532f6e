#include "gridloc/sensors/echo_filter.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

/// Median of sorted values [first, last): the middle one, or the mean of the two middle ones.
double median_of_sorted(const std::vector<double>& v, std::size_t first, std::size_t last) {
  const std::size_t n = last - first, mid = first + n / 2;
  return n % 2 == 1 ? v[mid] : 0.5 * (v[mid - 1] + v[mid]);
}

}  // namespace

void validate(const EchoFilterOptions& o) {
  auto bad = [](const std::string& field, double v, const std::string& rule) {
    std::ostringstream m;
    m << "echo filter options: " << field << " = " << v << " " << rule;
    throw Error(m.str());
  };
  if (!(o.tolerance_m >= 0.0) || !std::isfinite(o.tolerance_m)) {
    bad("tolerance_m", o.tolerance_m, "must be finite and >= 0");
  }
  if (!(o.tolerance_frac >= 0.0) || !std::isfinite(o.tolerance_frac)) {
    bad("tolerance_frac", o.tolerance_frac, "must be finite and >= 0");
  }
  if (o.min_agreeing < 2) bad("min_agreeing", o.min_agreeing, "must be >= 2");
}

FilteredReadings filter_echoes(const SonarRing& ring,
                               const std::vector<std::vector<double>>& firings,
                               const EchoFilterOptions& options) {
  validate(options);
  const std::size_t n = ring.sonars.size();
  if (firings.size() < 2) {
    throw Error("echo filter: needs at least 2 consecutive firings, got " +
                std::to_string(firings.size()));
  }
  for (std::size_t k = 0; k < firings.size(); ++k) {
    if (firings[k].size() != n) {
      throw Error("echo filter: firing " + std::to_string(k) + " has " +
                  std::to_string(firings[k].size()) + " ranges, expected " + std::to_string(n) +
                  " (one per sonar of ring '" + ring.name + "')");
    }
    for (std::size_t i = 0; i < n; ++i) {
      const double d = firings[k][i];
      if (std::isnan(d) || d < 0.0) {
        std::ostringstream m;
        m << "echo filter: firing " << k << ", sonar " << i << ": range " << d << " is "
          << (std::isnan(d) ? "NaN" : "negative");
        throw Error(m.str());
      }
    }
  }

  FilteredReadings out;
  out.ranges.resize(n);
  out.rejected.assign(n, false);
  std::vector<double> v(firings.size());
  for (std::size_t i = 0; i < n; ++i) {
    const double none = ring.sonars[i].max_range;
    for (std::size_t k = 0; k < firings.size(); ++k) v[k] = std::min(firings[k][i], none);
    std::sort(v.begin(), v.end());  // no echoes (exactly max_range) last
    // Largest run of sorted echoes whose extremes agree: every pair inside agrees too, as the
    // tolerance grows with the shorter range. The no-echo firings form one group of their own.
    std::size_t best_first = 0, best_last = 0;
    double best_spread = 0.0;
    auto consider = [&](std::size_t first, std::size_t last) {
      const std::size_t size = last - first, best = best_last - best_first;
      const double spread = v[last - 1] - v[first];
      if (size > best || (size == best && spread < best_spread)) {
        best_first = first;
        best_last = last;
        best_spread = spread;
      }
    };
    const auto echoes =
        static_cast<std::size_t>(std::lower_bound(v.begin(), v.end(), none) - v.begin());
    for (std::size_t first = 0, last = 0; first < echoes; ++first) {
      last = std::max(last, first + 1);
      while (last < echoes &&
             v[last] - v[first] <= options.tolerance_m + options.tolerance_frac * v[first]) {
        ++last;
      }
      consider(first, last);
    }
    if (echoes < v.size()) consider(echoes, v.size());
    if (best_last - best_first >= static_cast<std::size_t>(options.min_agreeing)) {
      out.ranges[i] = median_of_sorted(v, best_first, best_last);
    } else {
      out.ranges[i] = median_of_sorted(v, 0, v.size());
      out.rejected[i] = true;
      ++out.rejected_count;
    }
  }
  return out;
}

}  // namespace gridloc
