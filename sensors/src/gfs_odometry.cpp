// The raw odometry of a GMapping .gfs file, paired scan by scan with a corrected log.
#include "gridloc/sensors/gfs_odometry.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

/// One LASER_READING line's fields after the keyword; throws naming the line.
GfsScan parse_reading(std::istringstream& fields, const std::string& where) {
  GfsScan scan;
  long long count = 0;
  if (!(fields >> count) || count < 1 || count > 100000) {
    throw Error(where + ": LASER_READING needs a beam count in [1, 100000]");
  }
  scan.ranges.resize(static_cast<std::size_t>(count));
  for (double& r : scan.ranges) {
    if (!(fields >> r)) throw Error(where + ": LASER_READING has fewer ranges than its count");
  }
  if (!(fields >> scan.odometry.x >> scan.odometry.y >> scan.odometry.theta >> scan.timestamp)) {
    throw Error(where + ": LASER_READING needs x y theta timestamp after its ranges");
  }
  const Pose2& p = scan.odometry;
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.theta)) {
    throw Error(where + ": LASER_READING's odometry pose must be finite");
  }
  return scan;
}

/// Whether two scans of one instant read the same.
bool same_scan(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  std::size_t off = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const bool returns = a[k] < 40.0 || b[k] < 40.0;  // far readings may be clipped on loading
    off += returns && !(std::abs(a[k] - b[k]) <= 0.01);
  }
  return off <= a.size() / 50;
}

}  // namespace

std::vector<GfsScan> load_gfs_scans(const std::string& path, const ResourceLimits& limits) {
  check_input_file(path, "GMapping .gfs file", limits);
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the GMapping .gfs file");
  std::vector<GfsScan> scans;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    std::istringstream fields(line);
    std::string keyword;
    if (!(fields >> keyword) || keyword != "LASER_READING") continue;
    scans.push_back(parse_reading(fields, path + ":" + std::to_string(number)));
    scans.back().line = number;
  }
  if (scans.empty()) throw Error(path + ": no LASER_READING line (not a GMapping .gfs file?)");
  return scans;
}

std::vector<Pose2> scan_odometry_from_gfs(const CarmenLog& log, const std::vector<GfsScan>& gfs) {
  if (gfs.size() != log.lasers.size()) {
    throw Error("raw odometry: the .gfs file has " + std::to_string(gfs.size()) +
                " scans, the log " + std::to_string(log.lasers.size()) + ": not the same run");
  }
  std::vector<Pose2> odometry;
  odometry.reserve(gfs.size());
  for (std::size_t k = 0; k < gfs.size(); ++k) {
    if (!same_scan(gfs[k].ranges, log.lasers[k].scan.ranges)) {
      throw Error("raw odometry: scan " + std::to_string(k) + " (.gfs line " +
                  std::to_string(gfs[k].line) + ", log line " + std::to_string(log.lasers[k].line) +
                  ") reads differently: not the same run");
    }
    odometry.push_back(gfs[k].odometry);
  }
  return odometry;
}

}  // namespace gridloc
