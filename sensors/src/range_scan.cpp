#include "gridloc/sensors/range_scan.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "canvas.hpp"
#include "gridloc/grids/error.hpp"
#include "text_lines.hpp"

namespace gridloc {
namespace {

/// The longest line of a scan CSV: an `angle,range` line with a comment is far shorter.
constexpr std::size_t kMaxScanLineBytes = std::size_t{64} * 1024;

/// Cells crossed by the segment from (x0, y0) to (x1, y1), in cell units with cell (i, j)
/// covering [i - 0.5, i + 0.5) x [j - 0.5, j + 0.5) (the robot centre is a cell centre);
/// Amanatides-Woo traversal, the end cell excluded.
template <typename Visit>
void cells_before(double x0, double y0, double x1, double y1, Visit visit) {
  int ix = static_cast<int>(std::floor(x0 + 0.5)), iy = static_cast<int>(std::floor(y0 + 0.5));
  const int ex = static_cast<int>(std::floor(x1 + 0.5)),
            ey = static_cast<int>(std::floor(y1 + 0.5));
  const double dx = x1 - x0, dy = y1 - y0;
  const int sx = dx > 0 ? 1 : -1, sy = dy > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  const double tdx = dx != 0 ? 1.0 / std::abs(dx) : inf, tdy = dy != 0 ? 1.0 / std::abs(dy) : inf;
  double tx = dx != 0 ? ((ix + 0.5 * sx) - x0) / dx : inf;
  double ty = dy != 0 ? ((iy + 0.5 * sy) - y0) / dy : inf;
  // At most |ex - ix| + |ey - iy| steps reach the end cell.
  for (int steps = std::abs(ex - ix) + std::abs(ey - iy); steps > 0; --steps) {
    visit(ix, iy);
    if (tx < ty) {
      tx += tdx;
      ix += sx;
    } else {
      ty += tdy;
      iy += sy;
    }
  }
}

}  // namespace

void validate(const RangeScan& scan) {
  if (scan.ranges.empty()) throw Error("scan: no beams");
  if (scan.angles.size() != scan.ranges.size()) {
    throw Error("scan: " + std::to_string(scan.angles.size()) + " angles but " +
                std::to_string(scan.ranges.size()) + " ranges");
  }
  if (!(scan.max_range > 0.0) || !std::isfinite(scan.max_range)) {
    throw Error("scan: max range must be positive and finite, got " +
                std::to_string(scan.max_range));
  }
  bool any_return = false;
  for (std::size_t k = 0; k < scan.ranges.size(); ++k) {
    const double a = scan.angles[k], r = scan.ranges[k];
    if (!std::isfinite(a))
      throw Error("scan: angle of beam " + std::to_string(k) + " is not finite");
    if (std::isnan(r)) throw Error("scan: range of beam " + std::to_string(k) + " is NaN");
    if (r < 0.0) {
      throw Error("scan: range of beam " + std::to_string(k) + " is negative (" +
                  std::to_string(r) + ")");
    }
    any_return = any_return || r < scan.max_range;
  }
  if (!any_return) {
    throw Error("scan: no beam has a return below the max range " + std::to_string(scan.max_range) +
                " m; nothing to match");
  }
}

RangeScan load_scan_csv(const std::string& path, double max_range, const ResourceLimits& limits) {
  check_input_file(path, "scan file", limits);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the scan file for reading");
  RangeScan scan;
  scan.max_range = max_range;
  std::string line;
  for (std::size_t number = 1; detail::read_bounded_line(in, line, kMaxScanLineBytes, path, number);
       ++number) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    double angle = 0.0, range = 0.0;
    std::string rest;
    if (!(fields >> angle >> range) || (fields >> rest)) {
      throw Error(path + ":" + std::to_string(number) + ": expected 'angle_rad,range_m'");
    }
    // Checked before the beam is kept: a huge scan stops here, not after it is read.
    check_limit(static_cast<double>(scan.ranges.size() + 1), limits.max_beams,
                path + ":" + std::to_string(number) + ": beams of the scan", "beams",
                LimitNames::beams);
    scan.angles.push_back(angle);
    scan.ranges.push_back(range);
  }
  try {
    validate(scan);
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  return scan;
}

std::string to_string(ScanModel model) {
  switch (model) {
    case ScanModel::Rays:
      return "rays";
    case ScanModel::Samples:
      return "samples";
    case ScanModel::Hits:
      return "hits";
  }
  return "unknown";
}

void validate(const ScanModelOptions& options) {
  if (options.model == ScanModel::Samples &&
      (options.free_samples < 1 || options.free_samples > 1000)) {
    throw Error("scan model: free_samples must lie in [1, 1000], got " +
                std::to_string(options.free_samples));
  }
}

ScanPoints scan_points(const RangeScan& scan, const ScanModelOptions& options, const Pose2& mount) {
  validate(options);
  if (options.model == ScanModel::Rays) {
    throw Error("scan model: the ray model marks every crossed cell; it has no rigid points");
  }
  const int samples = options.model == ScanModel::Samples ? options.free_samples : 0;
  ScanPoints p;
  const std::size_t n = scan.ranges.size();
  p.x.reserve(n * static_cast<std::size_t>(1 + samples));
  p.y.reserve(p.x.capacity());
  p.norm.reserve(p.x.capacity());
  p.weight.reserve(p.x.capacity());
  // A sensor at the centre keeps norm = r exactly (hypot may differ in the last bit).
  const bool centred = mount.x == 0.0 && mount.y == 0.0;
  auto add = [&](double r, double a, float w) {
    const double x = mount.x + r * std::cos(a + mount.theta);
    const double y = mount.y + r * std::sin(a + mount.theta);
    const double norm = centred ? r : std::hypot(x, y);
    p.x.push_back(x);
    p.y.push_back(y);
    p.norm.push_back(norm);
    p.weight.push_back(w);
    p.max_norm = std::max(p.max_norm, norm);
  };
  for (std::size_t k = 0; k < n; ++k) {
    if (scan.ranges[k] < scan.max_range) add(scan.ranges[k], scan.angles[k], 1.0f);
  }
  p.hit_count = p.size();
  if (samples > 0) {
    // The midpoints of `samples` equal pieces of the free part of each beam.
    const float w = -1.0f / static_cast<float>(samples);
    for (std::size_t k = 0; k < n; ++k) {
      const double r = std::min(scan.ranges[k], scan.max_range);
      for (int j = 0; j < samples; ++j) add(r * (j + 0.5) / samples, scan.angles[k], w);
    }
  }
  return p;
}

namespace {

/// Appends points [first, last) of `from` to `to`.
void append_points(ScanPoints& to, const ScanPoints& from, std::size_t first, std::size_t last) {
  for (std::size_t k = first; k < last; ++k) {
    to.x.push_back(from.x[k]);
    to.y.push_back(from.y[k]);
    to.norm.push_back(from.norm[k]);
    to.weight.push_back(from.weight[k]);
  }
  to.max_norm = std::max(to.max_norm, from.max_norm);
}

}  // namespace

ScanPoints merge_points(const std::vector<ScanPoints>& parts) {
  ScanPoints merged;
  for (const ScanPoints& part : parts) append_points(merged, part, 0, part.hit_count);
  merged.hit_count = merged.size();
  for (const ScanPoints& part : parts) append_points(merged, part, part.hit_count, part.size());
  return merged;
}

SparseLocalGrid rasterize_points(const ScanPoints& points, double theta, double resolution,
                                 const Eigen::Vector2d& centre) {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw Error("local grid resolution must be positive, got " + std::to_string(resolution));
  }
  const double inv = 1.0 / resolution;
  const double cx = centre.x() * inv, cy = centre.y() * inv;
  detail::Canvas& canvas = detail::Canvas::for_this_thread(
      points.max_norm * inv + std::hypot(cx, cy), 2, centre, resolution);
  const double c = std::cos(theta), s = std::sin(theta);
  for (std::size_t k = points.hit_count; k < points.size(); ++k) {
    const Eigen::Vector2i cell = point_cell(points, k, c, s, inv, cx, cy);
    canvas.add_free(canvas.index_of_cell(cell.x(), cell.y()), points.weight[k]);
  }
  for (std::size_t k = 0; k < points.hit_count; ++k) {
    const Eigen::Vector2i cell = point_cell(points, k, c, s, inv, cx, cy);
    canvas.set(canvas.index_of_cell(cell.x(), cell.y()), 1.0f, 0.0f);
  }
  return canvas.collect(theta);
}

SparseLocalGrid rasterize_scan(const RangeScan& scan, double theta, double resolution,
                               const Eigen::Vector2d& centre, const ScanModelOptions& options) {
  validate(options);
  if (options.model != ScanModel::Rays) {
    return rasterize_points(scan_points(scan, options), theta, resolution, centre);
  }
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw Error("local grid resolution must be positive, got " + std::to_string(resolution));
  }
  const double inv = 1.0 / resolution;
  const double x0 = centre.x() * inv, y0 = centre.y() * inv;
  detail::Canvas& canvas = detail::Canvas::for_this_thread(
      scan.max_range * inv + std::hypot(x0, y0), 2, centre, resolution);
  thread_local std::vector<int> crossed;
  for (std::size_t k = 0; k < scan.ranges.size(); ++k) {
    const bool hit = scan.ranges[k] < scan.max_range;
    const double r = (hit ? scan.ranges[k] : scan.max_range) * inv;
    const double a = theta + scan.angles[k];
    const double x1 = x0 + r * std::cos(a), y1 = y0 + r * std::sin(a);
    crossed.clear();
    cells_before(x0, y0, x1, y1,
                 [&](int x, int y) { crossed.push_back(canvas.index_of_cell(x, y)); });
    if (!crossed.empty()) {
      const float v = -1.0f / static_cast<float>(crossed.size());
      for (int idx : crossed) canvas.add_free(idx, v);
    }
    if (hit) {
      // An end cell is +1 however many beams end in it.
      const int end = canvas.index_of_cell(static_cast<int>(std::floor(x1 + 0.5)),
                                           static_cast<int>(std::floor(y1 + 0.5)));
      canvas.set(end, 1.0f, 0.0f);
    }
  }
  return canvas.collect(theta);
}

}  // namespace gridloc
