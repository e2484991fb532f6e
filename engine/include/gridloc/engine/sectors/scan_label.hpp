#pragma once
/// Scan labels (seed 000 §3.2, Lee, Amato and Fellers): a 360-degree scan read as a string of
/// characteristic points (M local maximum, m local minimum, D discontinuity, c connection) in
/// counter-clockwise order from beam 0, and the cyclic match of two labels.
#include <string>
#include <vector>

#include "gridloc/sensors/range_scan.hpp"

namespace gridloc {

/// What CONSTRUCT SCAN LABEL (seed 000 §3.2) needs to read a noisy scan.
struct ScanLabelOptions {
  /// A jump between neighbouring readings larger than eps_abs_m + eps_rel * (nearer range) is
  /// a discontinuity (seed 000's epsilon_T, which it leaves open).
  double eps_abs_m = 0.3;
  double eps_rel = 0.15;
  /// Readings are median-filtered over this many beams first (odd, 1 = off). Seed 003 (ch. VI B)
  /// smooths its real IR data with a moving average over +-5 readings; a median removes the
  /// same spikes but keeps the jumps that D and c need.
  int median_window = 3;
  /// A local maximum and minimum of a continuous run that differ by less than this (m) are
  /// noise and dropped in pairs, the flattest first.
  double prominence_m = 0.05;
  /// Runs of at most this many beams without return, between two returns that continue each
  /// other (no discontinuity), are dropouts and are bridged (0 = off).
  int bridge_beams = 3;
};

/// A scan's label: one character per characteristic point, with the beam it was read at.
struct ScanLabel {
  std::string label;
  std::vector<int> beam;  ///< per character
};

/// CONSTRUCT SCAN LABEL of seed 000 §3.2 with its two slips fixed (the loop visits each beam
/// once; the two readings of a jump are D and c, never also m or M), the readings smoothed and
/// extrema of less than prominence_m dropped. Beams without return are "far" (a jump to them
/// is a discontinuity). The label starts at beam 0. Throws gridloc::Error for a scan that
/// fails validate() or bad options.
ScanLabel construct_scan_label(const RangeScan& scan, const ScanLabelOptions& options = {});

/// Whether `a` equals `b` turned: a cyclic shift of it. `shift` receives the k with
/// a[i] == b[(i + k) % n].
bool cyclic_equal(const std::string& a, const std::string& b, int* shift = nullptr);

}  // namespace gridloc
