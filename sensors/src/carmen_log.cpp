#include "gridloc/sensors/carmen_log.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>

#include "gridloc/grids/error.hpp"
#include "gzip_stream.hpp"
#include "text_lines.hpp"

namespace gridloc {
namespace {

/// The fields of one line, read left to right with errors that name the line and field.
class Fields {
 public:
  Fields(std::vector<std::string> tokens, std::string where)
      : tokens_(std::move(tokens)), where_(std::move(where)) {}

  double number(const std::string& field) {
    const std::string& text = token(field);
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size()) {
      fail(field + " is not a number: '" + text + "'");
    }
    return value;
  }
  /// A count of beams (readings, remissions): a whole number >= 0, at most limits.max_beams.
  int count(const std::string& field, const ResourceLimits& limits) {
    const double value = number(field);
    if (!(value >= 0.0) || value != std::floor(value)) {
      fail(field + " must be a whole number >= 0, got " + token_at(next_ - 1));
    }
    check_limit(value, limits.max_beams, where_ + ": " + field, "beams", LimitNames::beams);
    return static_cast<int>(value);
  }
  Pose2 pose(const std::string& field) {
    const double x = number(field + " x"), y = number(field + " y");
    const double theta = number(field + " theta");
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(theta)) {
      fail(field + " is not finite");
    }
    return {x, y, theta};
  }
  /// The unit of the last digit of the field just read ("940.54" -> 0.01, "12" -> 1,
  /// "1.13486e+09" -> 10000).
  double last_resolution() const {
    const std::string& text = tokens_[next_ - 1];
    const auto e = text.find_first_of("eE");
    const std::string mantissa = text.substr(0, e);
    const auto dot = mantissa.find('.');
    const double decimals = dot == std::string::npos ? 0.0 : double(mantissa.size() - dot - 1);
    const double exponent =
        e == std::string::npos ? 0.0 : std::strtod(text.c_str() + e + 1, nullptr);
    return std::pow(10.0, exponent - decimals);
  }
  void skip(std::size_t tokens) { next_ += tokens; }
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

/// `count` ranges; a NaN or infinite one (real logs mark invalid beams so) becomes
/// `no_return` and is counted in `invalid`.
std::vector<double> ranges(Fields& fields, int count, double no_return, int& invalid) {
  std::vector<double> result;
  result.reserve(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    double range = fields.number("range " + std::to_string(k + 1) + " of " + std::to_string(count));
    if (!std::isfinite(range)) {
      range = no_return;
      ++invalid;
    }
    if (!(range >= 0.0)) {
      fields.fail("range " + std::to_string(k + 1) + " is " + std::to_string(range) +
                  "; ranges must be >= 0");
    }
    result.push_back(range);
  }
  return result;
}

LaserRecord flaser(Fields& fields, const CarmenOptions& options) {
  LaserRecord record;
  const int count = fields.count("reading count", options.limits);
  if (count < 2) {
    fields.fail("a FLASER line needs at least 2 readings, got " + std::to_string(count));
  }
  record.scan.ranges = ranges(fields, count, options.max_range, record.invalid_ranges);
  // 180 degrees from -90: odd counts include both ends, even ones stop a step short.
  const double step = std::numbers::pi / (count % 2 == 1 ? count - 1 : count);
  for (int k = 0; k < count; ++k) record.scan.angles.push_back(-0.5 * std::numbers::pi + k * step);
  record.scan.max_range = options.max_range;
  record.laser_pose = fields.pose("laser pose");
  record.robot_pose = fields.pose("odometry pose");
  record.timestamp = fields.number("ipc timestamp");
  record.timestamp_resolution = fields.last_resolution();
  return record;
}

LaserRecord robotlaser(Fields& fields, const ResourceLimits& limits) {
  LaserRecord record;
  fields.number("laser type");
  const double start = fields.number("start angle"), fov = fields.number("field of view");
  const double resolution = fields.number("angular resolution");
  const double max_range = fields.number("maximum range");
  fields.number("accuracy");
  fields.number("remission mode");
  if (!std::isfinite(start) || !std::isfinite(fov) || !std::isfinite(resolution)) {
    fields.fail("the start angle, field of view and resolution must be finite");
  }
  if (!(max_range > 0.0) || !std::isfinite(max_range)) {
    fields.fail("the maximum range must be > 0, got " + std::to_string(max_range));
  }
  const int count = fields.count("reading count", limits);
  if (count < 2) {
    fields.fail("a ROBOTLASER1 line needs at least 2 readings, got " + std::to_string(count));
  }
  record.scan.ranges = ranges(fields, count, max_range, record.invalid_ranges);
  fields.skip(static_cast<std::size_t>(fields.count("remission count", limits)));
  for (int k = 0; k < count; ++k) record.scan.angles.push_back(start + k * resolution);
  record.scan.max_range = max_range;
  record.laser_pose = fields.pose("laser pose");
  record.robot_pose = fields.pose("robot pose");
  fields.skip(5);  // tv, rv, forward and side safety distances, turn axis
  record.timestamp = fields.number("ipc timestamp");
  record.timestamp_resolution = fields.last_resolution();
  return record;
}

OdometryRecord odom(Fields& fields) {
  OdometryRecord record;
  record.pose = fields.pose("pose");
  record.tv = fields.number("tv");
  record.rv = fields.number("rv");
  fields.number("acceleration");
  record.timestamp = fields.number("ipc timestamp");
  return record;
}

/// The longest line a log within the beam limit can hold: a ROBOTLASER1 line of max_beams
/// ranges and as many remissions, 64 bytes a number, and the rest of the line.
std::size_t max_line_bytes(const ResourceLimits& limits) {
  return static_cast<std::size_t>(4096.0 + 128.0 * std::min(limits.max_beams, 1e9));
}

/// The bytes a laser record holds: the record, its angles and ranges (their capacity).
double record_bytes(const LaserRecord& record) {
  return static_cast<double>(sizeof(LaserRecord)) +
         8.0 * static_cast<double>(record.scan.angles.capacity() + record.scan.ranges.capacity());
}

}  // namespace

CarmenLog parse_carmen_log(std::istream& in, const std::string& name,
                           const CarmenOptions& options) {
  if (!(options.max_range > 0.0) || !std::isfinite(options.max_range)) {
    throw Error("CARMEN log options: max_range must be > 0, got " +
                std::to_string(options.max_range));
  }
  options.limits.validate();
  CarmenLog log;
  double bytes = 0.0;  // of the records kept so far, checked as they grow
  detail::for_each_word_line(
      in, name, max_line_bytes(options.limits),
      [&](const std::vector<std::string>& tokens, std::size_t line) {
        const std::string& kind = tokens[0];
        if (kind != "FLASER" && kind != "ROBOTLASER1" && kind != "ODOM") return;
        Fields fields(tokens, name + ":" + std::to_string(line) + ": " + kind);
        if (kind == "ODOM") {
          log.odometry.push_back(odom(fields));
          log.odometry.back().line = line;
          bytes += sizeof(OdometryRecord);
        } else {
          log.lasers.push_back(kind == "FLASER" ? flaser(fields, options)
                                                : robotlaser(fields, options.limits));
          log.lasers.back().line = line;
          bytes += record_bytes(log.lasers.back());
        }
        check_memory(bytes, options.limits, name + ": the log's records");
      });
  return log;
}

CarmenLog load_carmen_log(const std::string& path, const CarmenOptions& options) {
  check_input_file(path, "CARMEN log", options.limits);
  if (options.max_decompressed_bytes == 0) {
    throw Error("CARMEN log options: max_decompressed_bytes must be > 0");
  }
  detail::GzipStream in(path, options.max_decompressed_bytes);
  try {
    CarmenLog log = parse_carmen_log(in, path, options);
    in.check();
    return log;
  } catch (const Error&) {
    in.check();  // a line cut short by corrupt data: the corruption is the error to report
    throw;
  }
}

}  // namespace gridloc
