#include "gridloc/sensors/carmen_log.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "gridloc/grids/error.hpp"
#include "text_lines.hpp"

namespace gridloc {
namespace {

/// The fields of one line, read left to right with errors that name the line and field.
class Fields {
 public:
  Fields(std::vector<std::string> tokens, std::string where)
      : tokens_(std::move(tokens)), where_(std::move(where)) {}

  double number(const std::string& field) {
    const std::string& t = token(field);
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || end != t.c_str() + t.size()) {
      fail(field + " is not a number: '" + t + "'");
    }
    return v;
  }
  int count(const std::string& field) {
    const double v = number(field);
    if (!(v >= 0.0) || v > 100000.0 || v != std::floor(v)) {
      fail(field + " must be a whole number in [0, 100000], got " + token_at(next_ - 1));
    }
    return static_cast<int>(v);
  }
  Pose2 pose(const std::string& field) {
    const double x = number(field + " x"), y = number(field + " y"), t = number(field + " theta");
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(t)) fail(field + " is not finite");
    return {x, y, t};
  }
  /// The unit of the last digit of the field just read ("940.54" -> 0.01, "12" -> 1).
  double last_resolution() const {
    const std::string& t = tokens_[next_ - 1];
    const auto dot = t.find('.');
    if (dot == std::string::npos || t.find_first_of("eE") != std::string::npos) return 1.0;
    return std::pow(10.0, -static_cast<double>(t.size() - dot - 1));
  }
  void skip(std::size_t n) { next_ += n; }
  bool done() const { return next_ >= tokens_.size(); }
  [[noreturn]] void fail(const std::string& what) const { throw Error(where_ + ": " + what); }

 private:
  const std::string& token(const std::string& field) {
    if (next_ >= tokens_.size()) fail("the line ends before its " + field);
    return tokens_[next_++];
  }
  const std::string& token_at(std::size_t i) const { return tokens_[i]; }

  std::vector<std::string> tokens_;
  std::string where_;
  std::size_t next_ = 1;  // tokens_[0] is the message name
};

/// n ranges; a NaN or infinite one (real logs mark invalid beams so) becomes `no_return`
/// and is counted in `invalid`.
std::vector<double> ranges(Fields& f, int n, double no_return, int& invalid) {
  std::vector<double> r;
  r.reserve(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    double v = f.number("range " + std::to_string(k + 1) + " of " + std::to_string(n));
    if (!std::isfinite(v)) {
      v = no_return;
      ++invalid;
    }
    if (!(v >= 0.0)) {
      f.fail("range " + std::to_string(k + 1) + " is " + std::to_string(v) +
             "; ranges must be >= 0");
    }
    r.push_back(v);
  }
  return r;
}

LaserRecord flaser(Fields& f, const CarmenOptions& o) {
  LaserRecord rec;
  const int n = f.count("reading count");
  if (n < 2) f.fail("a FLASER line needs at least 2 readings, got " + std::to_string(n));
  rec.scan.ranges = ranges(f, n, o.max_range, rec.invalid_ranges);
  // 180 degrees from -90: odd counts include both ends, even ones stop a step short.
  const double step = std::numbers::pi / (n % 2 == 1 ? n - 1 : n);
  for (int k = 0; k < n; ++k) rec.scan.angles.push_back(-0.5 * std::numbers::pi + k * step);
  rec.scan.max_range = o.max_range;
  rec.laser_pose = f.pose("laser pose");
  rec.robot_pose = f.pose("odometry pose");
  rec.timestamp = f.number("ipc timestamp");
  rec.timestamp_resolution = f.last_resolution();
  return rec;
}

LaserRecord robotlaser(Fields& f) {
  LaserRecord rec;
  f.number("laser type");
  const double start = f.number("start angle"), fov = f.number("field of view");
  const double resolution = f.number("angular resolution");
  const double max_range = f.number("maximum range");
  f.number("accuracy");
  f.number("remission mode");
  if (!std::isfinite(start) || !std::isfinite(fov) || !std::isfinite(resolution)) {
    f.fail("the start angle, field of view and resolution must be finite");
  }
  if (!(max_range > 0.0) || !std::isfinite(max_range)) {
    f.fail("the maximum range must be > 0, got " + std::to_string(max_range));
  }
  const int n = f.count("reading count");
  if (n < 2) f.fail("a ROBOTLASER1 line needs at least 2 readings, got " + std::to_string(n));
  rec.scan.ranges = ranges(f, n, max_range, rec.invalid_ranges);
  f.skip(static_cast<std::size_t>(f.count("remission count")));
  for (int k = 0; k < n; ++k) rec.scan.angles.push_back(start + k * resolution);
  rec.scan.max_range = max_range;
  rec.laser_pose = f.pose("laser pose");
  rec.robot_pose = f.pose("robot pose");
  f.skip(5);  // tv, rv, forward and side safety distances, turn axis
  rec.timestamp = f.number("ipc timestamp");
  rec.timestamp_resolution = f.last_resolution();
  return rec;
}

OdometryRecord odom(Fields& f) {
  OdometryRecord rec;
  rec.pose = f.pose("pose");
  rec.tv = f.number("tv");
  rec.rv = f.number("rv");
  f.number("acceleration");
  rec.timestamp = f.number("ipc timestamp");
  return rec;
}

}  // namespace

CarmenLog parse_carmen_log(std::istream& in, const std::string& name, const CarmenOptions& o) {
  if (!(o.max_range > 0.0) || !std::isfinite(o.max_range)) {
    throw Error("CARMEN log options: max_range must be > 0, got " + std::to_string(o.max_range));
  }
  CarmenLog log;
  detail::for_each_word_line(in, [&](const std::vector<std::string>& tokens, std::size_t line) {
    const std::string& kind = tokens[0];
    if (kind != "FLASER" && kind != "ROBOTLASER1" && kind != "ODOM") return;
    Fields f(tokens, name + ":" + std::to_string(line) + ": " + kind);
    if (kind == "ODOM") {
      log.odometry.push_back(odom(f));
      log.odometry.back().line = line;
    } else {
      log.lasers.push_back(kind == "FLASER" ? flaser(f, o) : robotlaser(f));
      log.lasers.back().line = line;
    }
  });
  return log;
}

CarmenLog load_carmen_log(const std::string& path, const CarmenOptions& options) {
  if (!std::filesystem::exists(path)) throw Error(path + ": CARMEN log not found");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read the CARMEN log");
  if (in.peek() == 0x1f) {
    char magic[2] = {};
    in.read(magic, 2);
    if (static_cast<unsigned char>(magic[1]) == 0x8b) {
      throw Error(path + ": gzip-compressed; decompress it first (gunzip)");
    }
    in.seekg(0);
  }
  return parse_carmen_log(in, path, options);
}

}  // namespace gridloc
