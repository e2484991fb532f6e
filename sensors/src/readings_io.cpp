#include "gridloc/sensors/readings_io.hpp"

#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "gridloc/grids/error.hpp"

namespace gridloc {

std::vector<double> load_readings(const std::string& path) {
  if (!std::filesystem::exists(path)) throw Error(path + ": readings file not found");
  std::ifstream in(path);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": malformed JSON: " + e.what());
  }
  if (!j.is_object() || !j.contains("ranges_m") || !j["ranges_m"].is_array()) {
    throw Error(path + ": expected an object with an array 'ranges_m'");
  }
  std::vector<double> ranges;
  for (const auto& v : j["ranges_m"]) {
    // JSON has no NaN; null is read as NaN so that validation names it.
    if (v.is_null()) {
      ranges.push_back(std::numeric_limits<double>::quiet_NaN());
    } else if (v.is_number()) {
      ranges.push_back(v.get<double>());
    } else {
      throw Error(path + ": 'ranges_m' must hold numbers, found " + v.dump());
    }
  }
  return ranges;
}

}  // namespace gridloc
