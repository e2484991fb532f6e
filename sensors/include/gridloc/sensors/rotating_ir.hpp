#pragma once
/// The rotating infrared range sensor of seed 003 ch. VI: a Sharp GP2D12 on a servo, one
/// 360-degree scan of short range. Calibrated from 9 to 55 cm; its spread grows quickly with
/// range (Table II: 95 % intervals 0.42 cm at 11.4 cm, 1.25 cm at 22.5 cm, 2.21 cm at 30 cm,
/// 6.83 cm at 39.8 cm), so the thesis truncated the data at 30 cm and smoothed each reading
/// with the five before and after it. Readings at the truncation range are saturation points
/// (no wall within range).
#include <cstdint>
#include <string>

#include "gridloc/grids/geometry.hpp"
#include "gridloc/grids/grid.hpp"
#include "gridloc/grids/limits.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "gridloc/sensors/range_scan.hpp"

namespace gridloc {

struct IrSensorOptions {
  int readings = 360;             ///< per turn, evenly spaced from angle -pi (>= 8)
  double min_range_m = 0.09;      ///< closer walls read this (the calibration's near end)
  double max_range_m = 0.30;      ///< truncation: farther walls (and no wall) read this
  bool noise = true;              ///< Gaussian range noise of ir_range_sigma()
  int smoothing_half_window = 5;  ///< moving average over +-this many readings (0: none)
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const IrSensorOptions& options);

/// The standard deviation (m) of one reading at true range r (m): Table II's 95 % interval
/// widths divided by 2 x 1.96, linear between its ranges, the first value below 11.4 cm and
/// the last slope continued beyond 39.8 cm. Throws gridloc::Error for a NaN range.
double ir_range_sigma(double range_m);

/// A simulated scan from world pose `pose`: exact ray casting on the map's walls (polygon) or
/// its Occupied cells (occupancy; Unknown transparent, leaving the map is no return), then
/// noise, clamping and smoothing. A true range >= max_range_m reads exactly max_range_m
/// (saturated, no noise); a nearer wall reads true range + ir_range_sigma(true range) x one
/// Gaussian of Rng(seed) (one drawn per reading, in order), clamped to
/// [min_range_m, max_range_m - 1e-6] so that it stays a return. Reading k looks at angle
/// -pi + 2 pi k / readings (robot frame); max_range of the scan is max_range_m. Throws
/// gridloc::Error for bad options or a pose that is not finite.
RangeScan simulate_ir_scan(const PolygonMap& map, const Pose2& pose, const IrSensorOptions& options,
                           std::uint64_t seed);
RangeScan simulate_ir_scan(const OccupancyMap& map, const Pose2& pose,
                           const IrSensorOptions& options, std::uint64_t seed);

/// The thesis's moving-average filter: each return replaced by the mean of itself and the
/// half_window readings before and after it (around the turn: the scan is circular). The
/// window stays on one wall and symmetric: it shrinks, on both sides alike, so as not to
/// reach a saturated reading (>= max_range, which stays as it is) or cross a jump of more than
/// 5 cm between neighbours; a one-sided window would pull a wall's last returns off its line
/// where the sensor's range ends. 0 returns the scan as it is. Throws gridloc::Error for
/// half_window < 0 or angles and ranges of different sizes.
RangeScan smooth_ir_scan(const RangeScan& scan, int half_window);

/// Reads a real scan from a plain CSV: one reading per line, `angle,range`; a first line
/// `angle_deg,range_cm` (or any of angle_deg/angle_rad and range_m/range_cm) names the units,
/// otherwise radians and metres. `#` starts a comment; blank lines are skipped. Ranges are
/// clamped like the simulator's (>= options.max_range_m, inf included: saturated at
/// max_range_m; others into [min_range_m, max_range_m - 1e-6]); then smoothed with the
/// options' window. Throws gridloc::Error for bad options, naming the file for a missing,
/// unreadable or oversized file (check_input_file) or fewer than 8 readings, and the file and
/// line for a line that is not two fields, a bad header, a bad or non-finite angle, a range
/// that is not a number, NaN or negative, a line over 64 KiB, or more than limits.max_beams
/// readings.
RangeScan load_ir_scan_csv(const std::string& path, const IrSensorOptions& options,
                           const ResourceLimits& limits = {});

}  // namespace gridloc
