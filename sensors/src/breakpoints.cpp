#include "gridloc/sensors/breakpoints.hpp"

#include <algorithm>
#include <cmath>

namespace gridloc {

double breakpoint_growth(double step_rad, double grazing_rad, double cap_steps) {
  if (!(grazing_rad > 0.0) || !(step_rad <= 0.5 * grazing_rad)) return 0.0;
  return std::min(std::sin(step_rad) / std::sin(grazing_rad - step_rad),
                  cap_steps * std::sin(step_rad));
}

}  // namespace gridloc
