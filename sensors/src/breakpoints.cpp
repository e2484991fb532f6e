#include "gridloc/sensors/breakpoints.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "gridloc/grids/error.hpp"

namespace gridloc {

double breakpoint_growth(double step_rad, double grazing_rad, double cap_steps) {
  if (!(grazing_rad > 0.0) || !(step_rad <= 0.5 * grazing_rad)) return 0.0;
  return std::min(std::sin(step_rad) / std::sin(grazing_rad - step_rad),
                  cap_steps * std::sin(step_rad));
}

void check_grazing_angle(double grazing_rad, const std::string& name) {
  if (grazing_rad >= 0.0 && grazing_rad < 0.5 * std::numbers::pi) return;
  throw Error(name + " must lie in [0, pi/2), got " + std::to_string(grazing_rad));
}

}  // namespace gridloc
