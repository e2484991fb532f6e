#include "gridloc/sensors/echo_filter.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

/// Median of sorted values [first, last): the middle one, or the mean of the two middle ones.
double median_of_sorted(const std::vector<double>& values, std::size_t first, std::size_t last) {
  const std::size_t n = last - first, mid = first + n / 2;
  return n % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

/// Throws gridloc::Error for fewer than 2 firings, a firing whose size is not the ring's, or
/// a NaN or negative range.
void check_firings(const SonarRing& ring, const std::vector<std::vector<double>>& firings) {
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
      const double range = firings[k][i];
      if (std::isnan(range) || range < 0.0) {
        std::ostringstream message;
        message << "echo filter: firing " << k << ", sonar " << i << ": range " << range << " is "
                << (std::isnan(range) ? "NaN" : "negative");
        throw Error(message.str());
      }
    }
  }
}

/// The largest run [first, last) of sorted ranges found so far, ties to the tighter one.
struct AgreeingRun {
  std::size_t first = 0, last = 0;
  double spread = 0.0;

  /// Takes the run [from, to) of `sorted` when it is larger, or as large and tighter.
  void consider(const std::vector<double>& sorted, std::size_t from, std::size_t to) {
    const std::size_t size = to - from, best = last - first;
    const double run_spread = sorted[to - 1] - sorted[from];
    if (size > best || (size == best && run_spread < spread)) {
      first = from;
      last = to;
      spread = run_spread;
    }
  }
};

/// Largest run of sorted echoes whose extremes agree: every pair inside agrees too, as the
/// tolerance grows with the shorter range. The no-echo firings (exactly `none`, sorted last)
/// form one group of their own.
AgreeingRun largest_agreeing_run(const std::vector<double>& sorted, double none,
                                 const EchoFilterOptions& options) {
  AgreeingRun run;
  const auto echoes = static_cast<std::size_t>(
      std::lower_bound(sorted.begin(), sorted.end(), none) - sorted.begin());
  for (std::size_t first = 0, last = 0; first < echoes; ++first) {
    last = std::max(last, first + 1);
    while (last < echoes && sorted[last] - sorted[first] <=
                                options.tolerance_m + options.tolerance_frac * sorted[first]) {
      ++last;
    }
    run.consider(sorted, first, last);
  }
  if (echoes < sorted.size()) run.consider(sorted, echoes, sorted.size());
  return run;
}

}  // namespace

void validate(const EchoFilterOptions& options) {
  auto bad = [](const std::string& field, double value, const std::string& rule) {
    std::ostringstream message;
    message << "echo filter options: " << field << " = " << value << " " << rule;
    throw Error(message.str());
  };
  if (!(options.tolerance_m >= 0.0) || !std::isfinite(options.tolerance_m)) {
    bad("tolerance_m", options.tolerance_m, "must be finite and >= 0");
  }
  if (!(options.tolerance_frac >= 0.0) || !std::isfinite(options.tolerance_frac)) {
    bad("tolerance_frac", options.tolerance_frac, "must be finite and >= 0");
  }
  if (options.min_agreeing < 2) bad("min_agreeing", options.min_agreeing, "must be >= 2");
}

FilteredReadings filter_echoes(const SonarRing& ring,
                               const std::vector<std::vector<double>>& firings,
                               const EchoFilterOptions& options) {
  validate(options);
  check_firings(ring, firings);
  const std::size_t n = ring.sonars.size();
  FilteredReadings out;
  out.ranges.resize(n);
  out.rejected.assign(n, false);
  std::vector<double> sorted(firings.size());
  for (std::size_t i = 0; i < n; ++i) {
    const double none = ring.sonars[i].max_range;
    for (std::size_t k = 0; k < firings.size(); ++k) sorted[k] = std::min(firings[k][i], none);
    std::sort(sorted.begin(), sorted.end());  // no echoes (exactly max_range) last
    const AgreeingRun run = largest_agreeing_run(sorted, none, options);
    if (run.last - run.first >= static_cast<std::size_t>(options.min_agreeing)) {
      out.ranges[i] = median_of_sorted(sorted, run.first, run.last);
    } else {
      out.ranges[i] = median_of_sorted(sorted, 0, sorted.size());
      out.rejected[i] = true;
      ++out.rejected_count;
    }
  }
  return out;
}

}  // namespace gridloc
