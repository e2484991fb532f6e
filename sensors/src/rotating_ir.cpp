#include "gridloc/sensors/rotating_ir.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <string_view>
#include <vector>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/rng.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "gridloc/sensors/segment_world.hpp"
#include "text_lines.hpp"

namespace gridloc {
namespace {

constexpr int kMinReadings = 8;
constexpr int kMaxReadings = 100'000;
/// A return never reads closer to max_range_m than this (m): it stays a return.
constexpr double kBelowMax = 1e-6;
/// The longest line of an IR scan CSV.
constexpr std::size_t kMaxIrLineBytes = std::size_t{64} * 1024;
/// The moving average does not cross a jump of more than this between neighbouring readings (m).
constexpr double kSmoothingJumpM = 0.05;

/// Table II of seed 003: nominal distance (cm) and width of its 95 % interval (cm).
struct IrCalibrationPoint {
  double range_cm;
  double width_cm;
};
constexpr std::array<IrCalibrationPoint, 4> kTableII{
    {{11.41, 0.42}, {22.52, 1.25}, {30.00, 2.21}, {39.82, 6.83}}};

/// The 95 % interval width (cm) at range r_cm: linear between the table's points, constant
/// before the first, the last segment continued after the last.
double interval_width_cm(double r_cm) {
  if (r_cm <= kTableII.front().range_cm) return kTableII.front().width_cm;
  std::size_t hi = 1;
  while (hi + 1 < kTableII.size() && r_cm > kTableII[hi].range_cm) ++hi;
  const IrCalibrationPoint a = kTableII[hi - 1], b = kTableII[hi];
  return a.width_cm + (r_cm - a.range_cm) * (b.width_cm - a.width_cm) / (b.range_cm - a.range_cm);
}

/// Angle (rad, robot frame) of reading k of n.
double reading_angle(int k, int n) {
  return -std::numbers::pi + 2.0 * std::numbers::pi * k / n;
}

/// The reading of a wall at true range r plus noise (m): saturated (exactly max_range_m) when
/// r >= max_range_m, else a return in [min_range_m, max_range_m - kBelowMax].
double clamp_reading(double true_range, double noise, const IrSensorOptions& options) {
  if (true_range >= options.max_range_m) return options.max_range_m;
  const double r = std::min(true_range + noise, options.max_range_m - kBelowMax);
  return std::max(r, options.min_range_m);
}

/// Noise, clamping and smoothing of a noise-free scan cast up to max_range_m; one Gaussian is
/// drawn per reading (returns or not), so reading k's noise does not depend on the others.
RangeScan finish_ir_scan(RangeScan truth, const IrSensorOptions& options, std::uint64_t seed) {
  Rng rng(seed);
  const int n = static_cast<int>(truth.ranges.size());
  for (int k = 0; k < n; ++k) {
    const double r = truth.ranges[k];
    const double gaussian = options.noise ? rng.gaussian() : 0.0;
    const double noise =
        options.noise && r < options.max_range_m ? ir_range_sigma(r) * gaussian : 0.0;
    truth.ranges[k] = clamp_reading(r, noise, options);
    truth.angles[k] = reading_angle(k, n);  // the same angles from both casters
  }
  truth.max_range = options.max_range_m;
  return smooth_ir_scan(truth, options.smoothing_half_window);
}

void check_pose(const Pose2& pose) {
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
    throw Error("simulate_ir_scan: pose must be finite, got (" + std::to_string(pose.x) + ", " +
                std::to_string(pose.y) + ", " + std::to_string(pose.theta) + ")");
  }
}

/// Where a CSV line is, for messages: "<file>:<line>".
std::string at_line(const std::string& path, std::size_t line) {
  return path + ":" + std::to_string(line);
}

/// The comma-separated fields of a line, blanks around each trimmed; empty for a blank or
/// comment-only line (`#` starts a comment).
std::vector<std::string> csv_fields(std::string line) {
  const auto hash = line.find('#');
  if (hash != std::string::npos) line.erase(hash);
  std::vector<std::string> fields;
  if (line.find_first_not_of(" \t\r") == std::string::npos) return fields;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    std::string field = line.substr(start, comma - start);
    const std::size_t b = field.find_first_not_of(" \t\r"), e = field.find_last_not_of(" \t\r");
    fields.push_back(b == std::string::npos ? std::string() : field.substr(b, e - b + 1));
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

/// The whole of `text` as a number (std::from_chars: no locale; "nan" and "inf" read).
bool parse_number(const std::string& text, double& value) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return !text.empty() && ec == std::errc() && ptr == end;
}

/// Factors from the file's units to radians and metres.
struct IrCsvUnits {
  double to_rad = 1.0;
  double to_m = 1.0;
};

/// The units a header line names; throws gridloc::Error naming the file and line otherwise.
IrCsvUnits parse_units_header(const std::vector<std::string>& fields, const std::string& where) {
  IrCsvUnits units;
  const bool angle_ok = fields[0] == "angle_deg" || fields[0] == "angle_rad";
  const bool range_ok = fields[1] == "range_m" || fields[1] == "range_cm";
  if (!angle_ok || !range_ok) {
    throw Error(where +
                ": expected 'angle,range' numbers or a header of angle_deg or angle_rad "
                "and range_m or range_cm, got '" +
                fields[0] + "," + fields[1] + "'");
  }
  if (fields[0] == "angle_deg") units.to_rad = std::numbers::pi / 180.0;
  if (fields[1] == "range_cm") units.to_m = 0.01;
  return units;
}

/// Reads one `angle,range` line into radians and metres (range unclamped); throws
/// gridloc::Error naming `where` for a bad number, a non-finite angle, a NaN or negative range.
std::pair<double, double> parse_reading(const std::vector<std::string>& fields,
                                        const IrCsvUnits& units, const std::string& where) {
  double angle = 0.0, range = 0.0;
  if (!parse_number(fields[0], angle) || !std::isfinite(angle)) {
    throw Error(where + ": the angle '" + fields[0] + "' is not a finite number");
  }
  if (!parse_number(fields[1], range)) {
    throw Error(where + ": the range '" + fields[1] + "' is not a number");
  }
  if (std::isnan(range)) throw Error(where + ": the range is NaN");
  if (range < 0.0) throw Error(where + ": the range " + fields[1] + " is negative");
  return {angle * units.to_rad, range * units.to_m};
}

}  // namespace

void validate(const IrSensorOptions& options) {
  if (options.readings < kMinReadings || options.readings > kMaxReadings) {
    throw Error("IR sensor: readings must lie in [8, 100000], got " +
                std::to_string(options.readings));
  }
  if (!(options.min_range_m > 0.0) || !std::isfinite(options.min_range_m)) {
    throw Error("IR sensor: min_range_m must be positive and finite, got " +
                std::to_string(options.min_range_m));
  }
  if (!(options.max_range_m > options.min_range_m) || !std::isfinite(options.max_range_m)) {
    throw Error("IR sensor: max_range_m must be finite and above min_range_m (" +
                std::to_string(options.min_range_m) + "), got " +
                std::to_string(options.max_range_m));
  }
  if (options.smoothing_half_window < 0 || 2 * options.smoothing_half_window >= options.readings) {
    throw Error("IR sensor: smoothing_half_window must lie in [0, readings / 2), got " +
                std::to_string(options.smoothing_half_window) + " for " +
                std::to_string(options.readings) + " readings");
  }
}

double ir_range_sigma(double range_m) {
  if (std::isnan(range_m)) throw Error("ir_range_sigma: the range is NaN");
  return interval_width_cm(range_m * 100.0) / (2.0 * 1.96) / 100.0;
}

RangeScan simulate_ir_scan(const PolygonMap& map, const Pose2& pose, const IrSensorOptions& options,
                           std::uint64_t seed) {
  validate(options);
  check_pose(pose);
  std::vector<WallSegment> walls;
  for (const auto& [a, b] : polygon_edges(map)) walls.push_back({a, b});
  const double step = 2.0 * std::numbers::pi / options.readings;
  return finish_ir_scan(simulate_segment_scan(walls, pose, options.readings, -std::numbers::pi,
                                              step, options.max_range_m),
                        options, seed);
}

RangeScan simulate_ir_scan(const OccupancyMap& map, const Pose2& pose,
                           const IrSensorOptions& options, std::uint64_t seed) {
  validate(options);
  check_pose(pose);
  return finish_ir_scan(simulate_scan(map, pose, options.readings, options.max_range_m, 0.0, 0),
                        options, seed);
}

RangeScan smooth_ir_scan(const RangeScan& scan, int half_window) {
  if (half_window < 0) {
    throw Error("smooth_ir_scan: half_window must be >= 0, got " + std::to_string(half_window));
  }
  if (scan.angles.size() != scan.ranges.size()) {
    throw Error("smooth_ir_scan: " + std::to_string(scan.angles.size()) + " angles but " +
                std::to_string(scan.ranges.size()) + " ranges");
  }
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(scan.ranges.size());
  if (half_window == 0 || n == 0) return scan;
  const std::ptrdiff_t h = std::min<std::ptrdiff_t>(half_window, (n - 1) / 2);
  const auto at = [&](std::ptrdiff_t k) { return scan.ranges[((k % n) + n) % n]; };
  // Readings k and k + 1 belong to one wall: both returns, no jump between them.
  const auto joined = [&](std::ptrdiff_t k) {
    return at(k) < scan.max_range && at(k + 1) < scan.max_range &&
           std::abs(at(k) - at(k + 1)) <= kSmoothingJumpM;
  };
  RangeScan out = scan;
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    if (!(scan.ranges[k] < scan.max_range)) continue;  // saturated (or NaN) stays
    std::ptrdiff_t reach = 0;  // symmetric: as far as both sides stay on the wall
    while (reach < h && joined(k - reach - 1) && joined(k + reach)) ++reach;
    double sum = 0.0;
    for (std::ptrdiff_t j = -reach; j <= reach; ++j) sum += at(k + j);
    out.ranges[k] = sum / static_cast<double>(2 * reach + 1);
  }
  return out;
}

RangeScan load_ir_scan_csv(const std::string& path, const IrSensorOptions& options,
                           const ResourceLimits& limits) {
  validate(options);
  check_input_file(path, "IR scan file", limits);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the IR scan file for reading");
  RangeScan scan;
  scan.max_range = options.max_range_m;
  IrCsvUnits units;
  bool first = true;
  std::string text;
  for (std::size_t line = 1; detail::read_bounded_line(in, text, kMaxIrLineBytes, path, line);
       ++line) {
    const std::vector<std::string> fields = csv_fields(text);
    if (fields.empty()) continue;
    const std::string where = at_line(path, line);
    if (fields.size() != 2) throw Error(where + ": expected 'angle,range'");
    double probe = 0.0;
    if (first && !parse_number(fields[0], probe)) {
      units = parse_units_header(fields, where);
      first = false;
      continue;
    }
    first = false;
    // Checked before the reading is kept: a huge file stops here, not after it is read.
    check_limit(static_cast<double>(scan.ranges.size() + 1), limits.max_beams,
                where + ": readings of the IR scan", "beams", LimitNames::beams);
    const auto [angle, range] = parse_reading(fields, units, where);
    scan.angles.push_back(angle);
    scan.ranges.push_back(clamp_reading(range, 0.0, options));
  }
  if (scan.ranges.size() < static_cast<std::size_t>(kMinReadings)) {
    throw Error(path + ": " + std::to_string(scan.ranges.size()) +
                " readings, an IR scan needs at least 8");
  }
  return smooth_ir_scan(scan, options.smoothing_half_window);
}

}  // namespace gridloc
