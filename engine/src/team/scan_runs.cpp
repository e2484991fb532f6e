// The runs of a scan: its readings ordered by angle round the (circular) scan, cut at every
// saturated reading and at every jump between neighbouring returns (seed 003 ch. III A: the
// saturation points; a jump is an occlusion).
#include "scan_runs.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace gridloc::team_detail {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

struct OrderedReading {
  double angle = 0.0;  ///< normalized to [0, 2 pi)
  double range = 0.0;
  bool returned = false;  ///< range below the max range
  Eigen::Vector2d beam = Eigen::Vector2d::UnitX();
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  ///< scan frame (m); returns only
};

std::vector<OrderedReading> ordered_readings(const RangeScan& scan) {
  std::vector<OrderedReading> readings;
  readings.reserve(scan.ranges.size());
  for (std::size_t k = 0; k < scan.ranges.size(); ++k) {
    OrderedReading r;
    r.angle = std::fmod(scan.angles[k], kTwoPi);
    if (r.angle < 0.0) r.angle += kTwoPi;
    if (r.angle >= kTwoPi) r.angle = 0.0;  // -tiny + 2 pi rounds up to 2 pi
    r.range = scan.ranges[k];
    r.returned = r.range < scan.max_range;
    r.beam = {std::cos(scan.angles[k]), std::sin(scan.angles[k])};
    if (r.returned) r.point = r.range * r.beam;
    readings.push_back(r);
  }
  std::stable_sort(
      readings.begin(), readings.end(),
      [](const OrderedReading& a, const OrderedReading& b) { return a.angle < b.angle; });
  return readings;
}

/// Whether the last reading is followed by the first: the gap round from the last angle to the
/// first is no wider than 1.5 of the widest step between neighbours.
bool full_turn(const std::vector<OrderedReading>& readings) {
  if (readings.size() < 3) return false;
  double widest = 0.0;
  for (std::size_t i = 1; i < readings.size(); ++i) {
    widest = std::max(widest, readings[i].angle - readings[i - 1].angle);
  }
  return kTwoPi - (readings.back().angle - readings.front().angle) <= 1.5 * widest;
}

/// Whether neighbouring readings a, b lie on one run: both returns, at most gap_m apart.
bool joined(const OrderedReading& a, const OrderedReading& b, double gap_m) {
  return a.returned && b.returned && (a.point - b.point).norm() <= gap_m;
}

RunNeighbour neighbour_of(const OrderedReading& r) {
  RunNeighbour n;
  n.exists = true;
  n.saturated = !r.returned;
  n.beam = r.beam;
  n.range = r.range;
  return n;
}

ScanRun closed_run(const std::vector<OrderedReading>& readings) {
  ScanRun run;
  run.closed = true;
  for (const OrderedReading& r : readings) run.points.push_back(r.point);
  return run;
}

}  // namespace

const Eigen::Vector2d& ScanRun::at(std::ptrdiff_t i) const {
  const std::ptrdiff_t n = size();
  return points[static_cast<std::size_t>(((i % n) + n) % n)];
}

std::vector<ScanRun> scan_runs(const RangeScan& scan, double gap_m) {
  const std::vector<OrderedReading> readings = ordered_readings(scan);
  const auto n = static_cast<std::ptrdiff_t>(readings.size());
  const bool turn = full_turn(readings);
  // A full turn is walked from just after a break, so that no run is cut at the seam; a turn
  // without a break is one closed run.
  std::ptrdiff_t start = 0;
  if (turn) {
    start = -1;
    for (std::ptrdiff_t i = 0; i < n && start < 0; ++i) {
      if (!joined(readings[i], readings[(i + 1) % n], gap_m)) start = (i + 1) % n;
    }
    if (start < 0) return {closed_run(readings)};
  }
  std::vector<ScanRun> runs;
  ScanRun run;
  for (std::ptrdiff_t s = 0; s < n; ++s) {
    const std::ptrdiff_t i = (start + s) % n;
    if (!readings[i].returned) continue;
    if (run.points.empty() && (turn || i > 0)) run.before = neighbour_of(readings[(i + n - 1) % n]);
    run.points.push_back(readings[i].point);
    const bool scan_edge = !turn && i == n - 1;
    if (!scan_edge && joined(readings[i], readings[(i + 1) % n], gap_m)) continue;
    if (!scan_edge) run.after = neighbour_of(readings[(i + 1) % n]);
    runs.push_back(std::move(run));
    run = ScanRun{};
  }
  return runs;
}

}  // namespace gridloc::team_detail
