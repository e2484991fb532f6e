// CONSTRUCT SCAN LABEL (seed 000 §3.2) and cyclic label matching.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "gridloc/engine/sectors/scan_label.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

void check(const ScanLabelOptions& o) {
  if (!(o.eps_abs_m > 0.0) || !(o.eps_rel >= 0.0) || !(o.prominence_m >= 0.0) ||
      !std::isfinite(o.eps_abs_m) || !std::isfinite(o.eps_rel) || !std::isfinite(o.prominence_m)) {
    throw Error("ScanLabelOptions: eps_abs_m must be positive, eps_rel and prominence_m >= 0");
  }
  if (o.bridge_beams < 0) {
    throw Error("ScanLabelOptions.bridge_beams must be >= 0, got " +
                std::to_string(o.bridge_beams));
  }
  if (o.median_window < 1 || o.median_window % 2 == 0) {
    throw Error("ScanLabelOptions.median_window must be odd and >= 1, got " +
                std::to_string(o.median_window));
  }
}

struct Event {
  int beam;
  int order;  // generation order, to keep a spike's two characters in sequence
  char kind;
};

}  // namespace

ScanLabel construct_scan_label(const RangeScan& scan, const ScanLabelOptions& o) {
  validate(scan);
  check(o);
  const int n = static_cast<int>(scan.ranges.size());
  // Beams without return read as the max range: far, so a jump to them is a discontinuity.
  std::vector<double> raw(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) raw[i] = std::min(scan.ranges[i], scan.max_range);
  // A short run of beams without return between two returns that continue each other is a
  // dropout (glass, a dark surface), not a view into the distance: bridged, it adds no jumps.
  for (int i = 0; i < n && o.bridge_beams > 0; ++i) {
    const int before = (i + n - 1) % n;
    if (scan.ranges[i] < scan.max_range || scan.ranges[before] >= scan.max_range) continue;
    int len = 0;
    while (len < n && scan.ranges[(i + len) % n] >= scan.max_range) ++len;
    const int after = (i + len) % n;
    if (len > o.bridge_beams || len >= n - 1) continue;
    const double a = raw[before], b = raw[after];
    if (std::abs(a - b) > o.eps_abs_m + o.eps_rel * std::min(a, b)) continue;
    for (int k = 0; k < len; ++k) raw[(i + k) % n] = a + (b - a) * (k + 1) / (len + 1);
  }
  std::vector<double> r(raw);
  if (o.median_window > 1 && n >= o.median_window) {
    const int h = o.median_window / 2;
    std::vector<double> w(static_cast<std::size_t>(o.median_window));
    for (int i = 0; i < n; ++i) {
      for (int k = -h; k <= h; ++k) w[k + h] = raw[((i + k) % n + n) % n];
      std::nth_element(w.begin(), w.begin() + h, w.end());
      r[i] = w[h];
    }
  }
  const auto at = [&](int i) { return r[((i % n) + n) % n]; };

  std::vector<Event> events;
  std::vector<char> jump_beam(static_cast<std::size_t>(n), 0);
  std::vector<int> run(static_cast<std::size_t>(n), 0);  // continuous run of each beam
  int order = 0, runs = 0;
  bool jump_at_wrap = false;  // between beam n-1 and beam 0
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const double near = std::min(r[i], r[j]);
    if (std::abs(r[i] - r[j]) > o.eps_abs_m + o.eps_rel * near) {
      // The nearer reading is the discontinuity D, the farther the connection c.
      events.push_back({i, order++, r[i] > r[j] ? 'c' : 'D'});
      events.push_back({j, order++, r[i] > r[j] ? 'D' : 'c'});
      jump_beam[i] = jump_beam[j] = 1;
      if (j != 0) ++runs;
      if (j == 0) jump_at_wrap = true;
    }
    if (j != 0) run[j] = runs;
  }
  // The last run continues into the first when no jump separates beam n-1 from beam 0.
  if (!jump_at_wrap) {
    for (int i = 0; i < n && run[i] == 0; ++i) run[i] = runs;
  }

  // Extrema of the smoothed readings, away from the jumps (a jump's readings are D and c).
  struct Extremum {
    int beam;
    char kind;
  };
  std::vector<Extremum> ext;
  for (int i = 0; i < n; ++i) {
    // A plateau (equal readings, common after the median filter) counts once, at its first
    // beam, against the nearest different readings on either side.
    if (jump_beam[i] || at(i - 1) == r[i]) continue;
    const double a = at(i - 1), b = r[i];
    double c = b;
    for (int k = 1; k < n && c == b; ++k) c = at(i + k);
    if (a < b && b > c) ext.push_back({i, 'M'});
    if (a > b && b < c) ext.push_back({i, 'm'});
  }
  // Noise makes pairs of shallow extrema: drop the flattest neighbouring pair of one run
  // while it differs by less than the prominence.
  while (ext.size() >= 2) {
    double best = std::numeric_limits<double>::infinity();
    std::size_t at_k = 0;
    for (std::size_t k = 0; k < ext.size(); ++k) {
      const std::size_t l = (k + 1) % ext.size();
      if (l == k || run[ext[k].beam] != run[ext[l].beam] || ext[k].kind == ext[l].kind) continue;
      const double d = std::abs(r[ext[k].beam] - r[ext[l].beam]);
      if (d < best) best = d, at_k = k;
    }
    if (!(best < o.prominence_m)) break;
    const std::size_t l = (at_k + 1) % ext.size();
    ext.erase(ext.begin() + static_cast<std::ptrdiff_t>(std::max(at_k, l)));
    ext.erase(ext.begin() + static_cast<std::ptrdiff_t>(std::min(at_k, l)));
  }
  for (const auto& e : ext) events.push_back({e.beam, order++, e.kind});
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
