#include "gridloc/sensors/readings_io.hpp"

#include <algorithm>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "gridloc/grids/error.hpp"

namespace gridloc {

namespace {

/// Parses the file, counting its JSON values as they are read: more than limits.max_beams
/// (a readings file is one observation, its firings included) stops the parse there, so a
/// huge array never becomes a huge document.
nlohmann::json parse_file(const std::string& path, const ResourceLimits& limits) {
  check_input_file(path, "readings file", limits);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the readings file for reading");
  double values = 0.0;
  const auto count_values = [&](int, nlohmann::json::parse_event_t event, nlohmann::json&) {
    if (event == nlohmann::json::parse_event_t::value) {
      check_limit(++values, limits.max_beams, path + ": values in the readings file", "values",
                  LimitNames::beams);
    }
    return true;
  };
  try {
    return nlohmann::json::parse(in, count_values);
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": malformed JSON: " + e.what());
  }
}

/// The numbers of a JSON array; null reads as NaN so that validation names it (JSON has no
/// NaN).
std::vector<double> ranges_of(const nlohmann::json& array, const std::string& path,
                              const std::string& key) {
  std::vector<double> ranges;
  for (const auto& v : array) {
    if (v.is_null()) {
      ranges.push_back(std::numeric_limits<double>::quiet_NaN());
    } else if (v.is_number()) {
      ranges.push_back(v.get<double>());
    } else {
      throw Error(path + ": '" + key + "' must hold numbers, found " + v.dump());
    }
  }
  return ranges;
}

}  // namespace

std::vector<double> load_readings(const std::string& path, const ResourceLimits& limits) {
  const nlohmann::json j = parse_file(path, limits);
  if (!j.is_object() || !j.contains("ranges_m") || !j["ranges_m"].is_array()) {
    throw Error(path + ": expected an object with an array 'ranges_m'");
  }
  return ranges_of(j["ranges_m"], path, "ranges_m");
}

std::vector<std::vector<double>> load_firings(const std::string& path,
                                              const ResourceLimits& limits) {
  const nlohmann::json j = parse_file(path, limits);
  if (j.is_object() && j.contains("firings_m")) {
    const nlohmann::json& f = j["firings_m"];
    if (!f.is_array() || f.empty() ||
        !std::all_of(f.begin(), f.end(), [](const auto& x) { return x.is_array(); })) {
      throw Error(path + ": 'firings_m' must be a non-empty array of arrays of ranges");
    }
    std::vector<std::vector<double>> firings;
    for (const auto& firing : f) firings.push_back(ranges_of(firing, path, "firings_m"));
    return firings;
  }
  if (!j.is_object() || !j.contains("ranges_m") || !j["ranges_m"].is_array()) {
    throw Error(path + ": expected an object with an array 'ranges_m' or 'firings_m'");
  }
  return {ranges_of(j["ranges_m"], path, "ranges_m")};
}

}  // namespace gridloc
