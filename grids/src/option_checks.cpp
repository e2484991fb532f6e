#include "gridloc/grids/option_checks.hpp"

#include <cmath>
#include <sstream>

#include "gridloc/grids/error.hpp"

namespace gridloc {

std::string message_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void require_option(bool ok, std::string_view owner, std::string_view field, double value,
                    std::string_view rule) {
  if (ok) return;
  std::string message(owner);
  message.append(": ").append(field).append(" ").append(rule);
  throw Error(message + ", got " + message_number(value));
}

void require_positive(double value, std::string_view owner, std::string_view field) {
  require_option(std::isfinite(value) && value > 0.0, owner, field, value,
                 "must be positive and finite");
}

void require_non_negative(double value, std::string_view owner, std::string_view field) {
  require_option(std::isfinite(value) && value >= 0.0, owner, field, value,
                 "must be finite and >= 0");
}

void require_share(double value, std::string_view owner, std::string_view field) {
  require_option(value >= 0.0 && value <= 1.0, owner, field, value, "must lie in [0, 1]");
}

}  // namespace gridloc
