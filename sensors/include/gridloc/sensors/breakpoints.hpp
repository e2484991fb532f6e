#pragma once
/// Where a scan's consecutive returns stop being one wall: the adaptive breakpoint detector
/// of Borges and Aldon, shared by ICP's segmentation (seed 004) and the one-scan maps of the
/// relations protocol (issue 30).
#include <limits>
#include <string>

namespace gridloc {

/// The growth of the breakpoint gap with range: neighbours on a wall seen at grazing angle
/// `grazing_rad` by beams `step_rad` apart lie range * sin(step) / sin(grazing - step) apart.
/// 0 when step > grazing / 2 (near the grazing angle the ratio explodes and would join every
/// beam) or grazing is 0; at most `cap_steps` beam spacings (sin(step) each).
double breakpoint_growth(double step_rad, double grazing_rad,
                         double cap_steps = std::numeric_limits<double>::infinity());

/// Throws gridloc::Error "<name> must lie in [0, pi/2), got <value>" for a grazing angle
/// outside [0, pi/2) or NaN.
void check_grazing_angle(double grazing_rad, const std::string& name);

}  // namespace gridloc
