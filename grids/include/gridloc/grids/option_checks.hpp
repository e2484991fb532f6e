#pragma once
/// Checks of options and limits, with one message form for every family:
/// "<owner>: <field> <rule>, got <value>", the rule saying what the field must be (issue 31),
/// thrown as gridloc::Error.
#include <string>
#include <string_view>

namespace gridloc {

/// A number as every message prints it: std::ostream's shortest form ("0.5", "1e+300", "nan").
std::string message_number(double value);

/// Throws "<owner>: <field> <rule>, got <value>" unless `ok` (rule: "must be ...").
void require_option(bool ok, std::string_view owner, std::string_view field, double value,
                    std::string_view rule);
/// ... unless `value` is finite and > 0 ("must be positive and finite").
void require_positive(double value, std::string_view owner, std::string_view field);
/// ... unless `value` is finite and >= 0 ("must be finite and >= 0").
void require_non_negative(double value, std::string_view owner, std::string_view field);
/// ... unless `value` lies in [0, 1] ("must lie in [0, 1]").
void require_share(double value, std::string_view owner, std::string_view field);

}  // namespace gridloc
