#include "gridloc/sensors/sonar_ring.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/geometry.hpp"

namespace gridloc {
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw Error(where + ": " + what);
}

void check_keys(const YAML::Node& node, const std::set<std::string>& known,
                const std::string& where) {
  if (!node.IsMap()) fail(where, "expected a mapping");
  for (const auto& kv : node) {
    if (!kv.first.IsScalar()) fail(where, "every key must be a plain name, found a non-scalar key");
    const auto key = kv.first.as<std::string>();
    if (!known.count(key)) fail(where, "unknown key '" + key + "'");
  }
}

double number(const YAML::Node& node, const std::string& key, const std::string& where) {
  try {
    const double v = node[key].as<double>();
    if (!std::isfinite(v)) fail(where, "key '" + key + "' must be finite");
    return v;
  } catch (const YAML::Exception&) {
    fail(where, "key '" + key + "' must be a number, got '" + YAML::Dump(node[key]) + "'");
  }
}

double number_or(const YAML::Node& node, const std::string& key, double fallback,
                 const std::string& where) {
  return node[key] ? number(node, key, where) : fallback;
}

Eigen::Vector2d point(const YAML::Node& node, const std::string& where) {
  if (!node.IsSequence() || node.size() != 2) fail(where, "a point must be a list [x, y]");
  try {
    Eigen::Vector2d p(node[0].as<double>(), node[1].as<double>());
    if (!p.allFinite()) fail(where, "point coordinates must be finite");
    return p;
  } catch (const YAML::Exception&) {
    fail(where, "point coordinates must be numbers");
  }
}

}  // namespace

double SonarRing::reach() const {
  double r = 0.0;
  for (const auto& s : sonars) r = std::max(r, s.radius + s.max_range);
  for (const auto& p : footprint.polygon) r = std::max(r, p.norm());
  return r;
}

bool footprint_contains(const Footprint& footprint, const Eigen::Vector2d& p) {
  const auto& poly = footprint.polygon;
  bool inside = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const auto& a = poly[i];
    const auto& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

void validate(const SonarRing& ring) {
  const std::string where = "sonar ring '" + ring.name + "'";
  if (ring.sonars.empty()) fail(where, "has no sonars");
  for (std::size_t i = 0; i < ring.sonars.size(); ++i) {
    const auto& s = ring.sonars[i];
    const std::string w = where + " sonar " + std::to_string(i);
    if (!std::isfinite(s.bearing) || !std::isfinite(s.heading)) fail(w, "angles must be finite");
    if (!(s.radius >= 0.0) || !std::isfinite(s.radius)) fail(w, "radius_m must be >= 0");
    if (!(s.cone > 0.0 && s.cone < std::numbers::pi)) fail(w, "cone_deg must be in (0, 180)");
    if (!(s.min_range >= 0.0)) fail(w, "min_range_m must be >= 0");
    if (!(s.max_range > s.min_range) || !std::isfinite(s.max_range)) {
      fail(w, "max_range_m must be finite and greater than min_range_m");
    }
  }
  if (!ring.footprint.polygon.empty() && ring.footprint.polygon.size() < 3) {
    fail(where, "footprint needs at least 3 points");
  }
}

void validate_readings(const SonarRing& ring, const std::vector<double>& ranges,
                       const std::vector<bool>& rejected) {
  if (ranges.size() != ring.sonars.size()) {
    throw Error("readings: expected " + std::to_string(ring.sonars.size()) +
                " ranges (one per sonar of ring '" + ring.name + "'), got " +
                std::to_string(ranges.size()));
  }
  if (!rejected.empty()) {
    if (rejected.size() != ring.sonars.size()) {
      throw Error("readings: the rejection mask has " + std::to_string(rejected.size()) +
                  " flags, expected " + std::to_string(ring.sonars.size()) +
                  " (one per sonar of ring '" + ring.name + "') or none");
    }
    if (std::all_of(rejected.begin(), rejected.end(), [](bool r) { return r; })) {
      throw Error("readings: every reading was rejected by the echo filter (" +
                  std::to_string(rejected.size()) + " of " + std::to_string(rejected.size()) +
                  " sonars); nothing is left to localize with");
    }
  }
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    const double d = ranges[i];
    const auto& s = ring.sonars[i];
    std::ostringstream msg;
    msg << "readings: range " << i << " = " << d;
    if (std::isnan(d)) throw Error(msg.str() + " is NaN");
    if (d < 0.0) throw Error(msg.str() + " is negative");
    if (d > s.max_range + 1e-9) {
      msg << " is beyond the sonar's max range " << s.max_range << " (use " << s.max_range
          << " for no echo)";
      throw Error(msg.str());
    }
    if (d < s.min_range) {
      msg << " is below the sonar's min range " << s.min_range;
      throw Error(msg.str());
    }
  }
}

static SonarRing parse_sonar_ring(const std::string& yaml_path, const ResourceLimits& limits) {
  const std::string text = read_input_file(yaml_path, "sonar ring file", limits);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    fail(yaml_path, std::string("malformed YAML: ") + e.what());
  }
  check_keys(root, {"name", "defaults", "footprint", "sonars"}, yaml_path);

  SonarRing ring;
  if (root["name"] && !root["name"].IsScalar()) fail(yaml_path, "key 'name' must be a string");
  ring.name = root["name"] ? root["name"].as<std::string>() : yaml_path;
  SonarSpec defaults;
  if (root["defaults"]) {
    const auto d = root["defaults"];
    const std::string w = yaml_path + ": defaults";
    check_keys(d, {"cone_deg", "min_range_m", "max_range_m"}, w);
    defaults.cone = deg2rad(number_or(d, "cone_deg", rad2deg(defaults.cone), w));
    defaults.min_range = number_or(d, "min_range_m", defaults.min_range, w);
    defaults.max_range = number_or(d, "max_range_m", defaults.max_range, w);
  }
  if (!root["sonars"] || !root["sonars"].IsSequence()) {
    fail(yaml_path, "key 'sonars' must be a list");
  }
  check_limit(static_cast<double>(root["sonars"].size()), limits.max_beams, yaml_path + ": sonars",
              "sonars", LimitNames::beams);
  int i = 0;
  for (const auto& node : root["sonars"]) {
    const std::string w = yaml_path + ": sonars[" + std::to_string(i++) + "]";
    check_keys(node,
               {"bearing_deg", "radius_m", "heading_deg", "cone_deg", "min_range_m", "max_range_m"},
               w);
    for (const char* req : {"bearing_deg", "radius_m", "heading_deg"}) {
      if (!node[req]) fail(w, std::string("missing key '") + req + "'");
    }
    SonarSpec s = defaults;
    s.bearing = deg2rad(number(node, "bearing_deg", w));
    s.radius = number(node, "radius_m", w);
    s.heading = deg2rad(number(node, "heading_deg", w));
    s.cone = deg2rad(number_or(node, "cone_deg", rad2deg(defaults.cone), w));
    s.min_range = number_or(node, "min_range_m", defaults.min_range, w);
    s.max_range = number_or(node, "max_range_m", defaults.max_range, w);
    ring.sonars.push_back(s);
  }
  if (root["footprint"]) {
    const auto fp = root["footprint"];
    if (!fp.IsSequence()) fail(yaml_path, "key 'footprint' must be a list of [x, y] points");
    check_limit(static_cast<double>(fp.size()), limits.max_vertices, yaml_path + ": footprint",
                "vertices", LimitNames::vertices);
    for (const auto& p : fp) ring.footprint.polygon.push_back(point(p, yaml_path + ": footprint"));
  }
  try {
    validate(ring);
  } catch (const Error& e) {
    fail(yaml_path, e.what());
  }
  return ring;
}

SonarRing load_sonar_ring(const std::string& yaml_path, const ResourceLimits& limits) {
  try {
    return parse_sonar_ring(yaml_path, limits);
  } catch (const YAML::Exception& e) {
    // Conversions not caught field by field (e.g. a non-scalar key or name) name the file.
    fail(yaml_path, std::string("invalid sonar ring YAML: ") + e.what());
  }
}

}  // namespace gridloc
