// CONSTRUCT SCAN LABEL (seed 000 §3.2) and cyclic label matching.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "gridloc/engine/sectors/scan_label.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

/// The options' ranges; throws gridloc::Error naming the bad one.
void check_options(const ScanLabelOptions& options) {
  if (!(options.eps_abs_m > 0.0) || !(options.eps_rel >= 0.0) || !(options.prominence_m >= 0.0) ||
      !std::isfinite(options.eps_abs_m) || !std::isfinite(options.eps_rel) ||
      !std::isfinite(options.prominence_m)) {
    throw Error("ScanLabelOptions: eps_abs_m must be positive, eps_rel and prominence_m >= 0");
  }
  if (options.bridge_beams < 0) {
    throw Error("ScanLabelOptions.bridge_beams must be >= 0, got " +
                std::to_string(options.bridge_beams));
  }
  if (options.median_window < 1 || options.median_window % 2 == 0) {
    throw Error("ScanLabelOptions.median_window must be odd and >= 1, got " +
                std::to_string(options.median_window));
  }
}

/// A characteristic point at a beam, before sorting.
struct Event {
  int beam;
  int order;  // generation order, to keep a spike's two characters in sequence
  char kind;
};

/// Two neighbouring readings differ by a jump: a discontinuity (seed 000's epsilon_T).
bool is_jump(double a, double b, const ScanLabelOptions& options) {
  return std::abs(a - b) > options.eps_abs_m + options.eps_rel * std::min(a, b);
}

/// The readings with beams without return at the max range: far, so a jump to them is a
/// discontinuity. A short run of beams without return between two returns that continue each
/// other is a dropout (glass, a dark surface), not a view into the distance: bridged, it adds
/// no jumps.
std::vector<double> bridged_readings(const RangeScan& scan, const ScanLabelOptions& options) {
  const int n = static_cast<int>(scan.ranges.size());
  std::vector<double> raw(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) raw[i] = std::min(scan.ranges[i], scan.max_range);
  for (int i = 0; i < n && options.bridge_beams > 0; ++i) {
    const int before = (i + n - 1) % n;
    if (scan.ranges[i] < scan.max_range || scan.ranges[before] >= scan.max_range) continue;
    int len = 0;
    while (len < n && scan.ranges[(i + len) % n] >= scan.max_range) ++len;
    const int after = (i + len) % n;
    if (len > options.bridge_beams || len >= n - 1) continue;
    const double a = raw[before], b = raw[after];
    if (is_jump(a, b, options)) continue;
    for (int k = 0; k < len; ++k) raw[(i + k) % n] = a + (b - a) * (k + 1) / (len + 1);
  }
  return raw;
}

/// The cyclic median over `window` beams (odd; 1 or more than the beams: unchanged).
std::vector<double> median_filtered(const std::vector<double>& raw, int window) {
  const int n = static_cast<int>(raw.size());
  std::vector<double> r(raw);
  if (window <= 1 || n < window) return r;
  const int h = window / 2;
  std::vector<double> w(static_cast<std::size_t>(window));
  for (int i = 0; i < n; ++i) {
    for (int k = -h; k <= h; ++k) w[k + h] = raw[((i + k) % n + n) % n];
    std::nth_element(w.begin(), w.begin() + h, w.end());
    r[i] = w[h];
  }
  return r;
}

/// The jumps of the readings: their D and c events, the beams they sit on, and each beam's
/// continuous run (runs are split by jumps; the last continues into the first when no jump
/// separates beam n-1 from beam 0).
struct Jumps {
  std::vector<Event> events;
  std::vector<char> at_beam;
  std::vector<int> run;
};

Jumps find_jumps(const std::vector<double>& r, const ScanLabelOptions& options) {
  const int n = static_cast<int>(r.size());
  Jumps out;
  out.at_beam.assign(static_cast<std::size_t>(n), 0);
  out.run.assign(static_cast<std::size_t>(n), 0);
  int order = 0, runs = 0;
  bool jump_at_wrap = false;  // between beam n-1 and beam 0
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    if (is_jump(r[i], r[j], options)) {
      // The nearer reading is the discontinuity D, the farther the connection c.
      out.events.push_back({i, order++, r[i] > r[j] ? 'c' : 'D'});
      out.events.push_back({j, order++, r[i] > r[j] ? 'D' : 'c'});
      out.at_beam[i] = out.at_beam[j] = 1;
      if (j != 0) ++runs;
      if (j == 0) jump_at_wrap = true;
    }
    if (j != 0) out.run[j] = runs;
  }
  if (!jump_at_wrap) {
    for (int i = 0; i < n && out.run[i] == 0; ++i) out.run[i] = runs;
  }
  return out;
}

/// A local maximum (M) or minimum (m) at a beam.
struct Extremum {
  int beam;
  char kind;
};

/// The extrema of the smoothed readings, away from the jumps (a jump's readings are D and c).
/// A plateau (equal readings, common after the median filter) counts once, at its first beam,
/// against the nearest different readings on either side.
std::vector<Extremum> find_extrema(const std::vector<double>& r, const std::vector<char>& jump) {
  const int n = static_cast<int>(r.size());
  const auto at = [&](int i) { return r[((i % n) + n) % n]; };
  std::vector<Extremum> out;
  for (int i = 0; i < n; ++i) {
    if (jump[i] || at(i - 1) == r[i]) continue;
    const double a = at(i - 1), b = r[i];
    double c = b;
    for (int k = 1; k < n && c == b; ++k) c = at(i + k);
    if (a < b && b > c) out.push_back({i, 'M'});
    if (a > b && b < c) out.push_back({i, 'm'});
  }
  return out;
}

/// Noise makes pairs of shallow extrema: drops the flattest neighbouring pair of one run
/// while it differs by less than `prominence_m`.
void drop_shallow_pairs(std::vector<Extremum>& ext, const std::vector<double>& r,
                        const std::vector<int>& run, double prominence_m) {
  while (ext.size() >= 2) {
    double best = std::numeric_limits<double>::infinity();
    std::size_t at_k = 0;
    for (std::size_t k = 0; k < ext.size(); ++k) {
      const std::size_t l = (k + 1) % ext.size();
      if (l == k || run[ext[k].beam] != run[ext[l].beam] || ext[k].kind == ext[l].kind) continue;
      const double d = std::abs(r[ext[k].beam] - r[ext[l].beam]);
      if (d < best) best = d, at_k = k;
    }
    if (!(best < prominence_m)) break;
    const std::size_t l = (at_k + 1) % ext.size();
    ext.erase(ext.begin() + static_cast<std::ptrdiff_t>(std::max(at_k, l)));
    ext.erase(ext.begin() + static_cast<std::ptrdiff_t>(std::min(at_k, l)));
  }
}

/// The label of the events in beam order (a beam's events in generation order).
ScanLabel label_of(std::vector<Event> events) {
  std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
    return a.beam != b.beam ? a.beam < b.beam : a.order < b.order;
  });
  ScanLabel out;
  for (const auto& e : events) {
    out.label.push_back(e.kind);
    out.beam.push_back(e.beam);
  }
  return out;
}

}  // namespace

ScanLabel construct_scan_label(const RangeScan& scan, const ScanLabelOptions& options) {
  validate(scan);
  check_options(options);
  const std::vector<double> readings =
      median_filtered(bridged_readings(scan, options), options.median_window);
  Jumps jumps = find_jumps(readings, options);
  std::vector<Extremum> extrema = find_extrema(readings, jumps.at_beam);
  drop_shallow_pairs(extrema, readings, jumps.run, options.prominence_m);
  int order = static_cast<int>(jumps.events.size());  // the jumps' events come first
  for (const auto& e : extrema) jumps.events.push_back({e.beam, order++, e.kind});
  return label_of(std::move(jumps.events));
}

bool cyclic_equal(const std::string& a, const std::string& b, int* shift) {
  if (a.size() != b.size()) return false;
  if (a.empty()) {
    if (shift != nullptr) *shift = 0;
    return true;
  }
  const std::string bb = b + b;
  const std::size_t k = bb.find(a);
  if (k == std::string::npos) return false;
  if (shift != nullptr) *shift = static_cast<int>(k);
  return true;
}

}  // namespace gridloc
