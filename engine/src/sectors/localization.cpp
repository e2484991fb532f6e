// Seed 000 §3: localization from a scan label and the sectors' labels.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "gridloc/engine/sectors/localization.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

bool is_pair(char a, char b) {
  return (a == 'M' && b == 'm') || (a == 'm' && b == 'M');
}

/// A label with some neighbouring M m pairs left out; `index` gives each kept character's
/// position in the full label.
struct Variant {
  std::string label;
  std::vector<int> index;
};

/// The label itself and every label with up to `pairs` neighbouring M m pairs deleted (the
/// label is cyclic: its last and first characters are neighbours too).
std::vector<Variant> variants(const std::string& label, int pairs) {
  std::vector<Variant> out;
  Variant full{label, {}};
  for (int i = 0; i < static_cast<int>(label.size()); ++i) full.index.push_back(i);
  out.push_back(full);
  std::size_t from = 0;
  for (int round = 0; round < pairs; ++round) {
    const std::size_t to = out.size();
    for (std::size_t v = from; v < to; ++v) {
      const int n = static_cast<int>(out[v].label.size());
      for (int i = 0; i < n && n >= 2; ++i) {
        const int j = (i + 1) % n;
        if (!is_pair(out[v].label[i], out[v].label[j])) continue;
        Variant shorter;
        for (int k = 0; k < n; ++k) {
          if (k == i || k == j) continue;
          shorter.label.push_back(out[v].label[k]);
          shorter.index.push_back(out[v].index[k]);
        }
        const bool seen = std::any_of(out.begin(), out.end(),
                                      [&](const Variant& x) { return x.index == shorter.index; });
        if (!seen) out.push_back(std::move(shorter));
      }
    }
    from = to;
  }
  return out;
}

/// The vertex at an M reading: the intersection of the lines fitted to `k` readings on each
/// side (seed 000 eqs. (6)-(9)), or the reading itself when they are near parallel.
Eigen::Vector2d locate_vertex(const std::vector<Eigen::Vector2d>& points, int beam,
                              int line_points) {
  const int n = static_cast<int>(points.size());
  const auto point = [&](int i) { return points[((i % n) + n) % n]; };
  // The line through `line_points` readings on one side (dir +1 or -1): centre, direction.
  const auto fit = [&](int dir, Eigen::Vector2d& centre, Eigen::Vector2d& direction) {
    centre.setZero();
    for (int s = 1; s <= line_points; ++s) centre += point(beam + dir * s);
    centre /= line_points;
    Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
    for (int s = 1; s <= line_points; ++s)
      scatter += (point(beam + dir * s) - centre) * (point(beam + dir * s) - centre).transpose();
    direction = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(scatter).eigenvectors().col(1);
  };
  Eigen::Vector2d c1, d1, c2, d2;
  fit(+1, c1, d1);
  fit(-1, c2, d2);
  const double den = d1.x() * d2.y() - d1.y() * d2.x();
  if (std::abs(den) < 0.05) return point(beam);  // < 3 deg apart: no corner to intersect
  const Eigen::Vector2d w = c2 - c1;
  const double t = (w.x() * d2.y() - w.y() * d2.x()) / den;
  const Eigen::Vector2d v = c1 + t * d1;
  // A corner far from its reading is a bad fit (another surface in the window).
  return (v - point(beam)).norm() < 0.3 + 0.05 * point(beam).norm() ? v : point(beam);
}

/// Rigid fit: the pose (R, t) with world = R * local + t, least squares.
Pose2 rigid_fit(const std::vector<Eigen::Vector2d>& local,
                const std::vector<Eigen::Vector2d>& world) {
  Eigen::Vector2d local_centre = Eigen::Vector2d::Zero(), world_centre = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < local.size(); ++k) local_centre += local[k], world_centre += world[k];
  local_centre /= static_cast<double>(local.size());
  world_centre /= static_cast<double>(world.size());
  double s = 0.0, c = 0.0;
  for (std::size_t k = 0; k < local.size(); ++k) {
    const Eigen::Vector2d a = local[k] - local_centre, b = world[k] - world_centre;
    c += a.dot(b);
    s += a.x() * b.y() - a.y() * b.x();
  }
  const double theta = std::atan2(s, c);
  const Eigen::Vector2d t = world_centre - Eigen::Rotation2Dd(theta) * local_centre;
  return {t.x(), t.y(), theta};
}

/// The positions of a label's D and c characters: the jumps of a scan, which a partial view
/// keeps while the extrema between them come and go.
std::vector<int> skeleton(const std::string& label) {
  std::vector<int> out;
  for (int i = 0; i < static_cast<int>(label.size()); ++i) {
    if (label[i] == 'D' || label[i] == 'c') out.push_back(i);
  }
  return out;
}

/// The skeleton itself and every skeleton with up to `pairs` neighbouring D c (or c D) pairs
/// left out (cyclic, like the label).
std::vector<std::vector<int>> skeleton_variants(const std::string& label,
                                                const std::vector<int>& skeleton, int pairs) {
  std::vector<std::vector<int>> out{skeleton};
  std::size_t from = 0;
  for (int round = 0; round < pairs; ++round) {
    const std::size_t to = out.size();
    for (std::size_t v = from; v < to; ++v) {
      const int n = static_cast<int>(out[v].size());
      for (int i = 0; i < n && n >= 4; ++i) {
        const int j = (i + 1) % n;
        if (label[out[v][i]] == label[out[v][j]]) continue;  // DD or cc: not a pair
        std::vector<int> shorter;
        for (int k = 0; k < n; ++k) {
          if (k != i && k != j) shorter.push_back(out[v][k]);
        }
        if (std::find(out.begin(), out.end(), shorter) == out.end())
          out.push_back(std::move(shorter));
      }
    }
    from = to;
  }
  return out;
}

/// The positions of the M characters strictly between positions `from` and `to` of a cyclic
/// label (from == to: the whole label but `from`).
std::vector<int> maxima_between(const std::string& label, int from, int to) {
  std::vector<int> out;
  const int n = static_cast<int>(label.size());
  for (int i = (from + 1) % n; i != to; i = (i + 1) % n) {
    if (label[i] == 'M') out.push_back(i);
  }
  return out;
}

/// A map edge ready for point-to-wall distances: its start, direction, 1 / length^2 and unit
/// normal, computed once per localization rather than per point and pass.
struct Wall {
  Eigen::Vector2d a, e, normal;
  double inv_len2;
};

std::vector<Wall> walls_of(const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& edges) {
  std::vector<Wall> out;
  for (const auto& [a, b] : edges) {
    const Eigen::Vector2d e = b - a;
    out.push_back({a, e, Eigen::Vector2d(-e.y(), e.x()).normalized(), 1.0 / e.squaredNorm()});
  }
  return out;
}

/// The Gauss-Newton normal equations of the scan's points (robot frame) at `pose` against
/// their nearest wall within `gate` (m): H, the gradient g, the sum of squared distances and
/// the points used.
struct NormalEquations {
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  double sum2 = 0.0;
  int used = 0;
};

NormalEquations normal_equations(const std::vector<Eigen::Vector2d>& points,
                                 const std::vector<Wall>& walls, const Pose2& pose, double gate) {
  NormalEquations equations;
  const Eigen::Rotation2Dd R(pose.theta);
  const Eigen::Vector2d t(pose.x, pose.y);
  for (const auto& p : points) {
    const Eigen::Vector2d rp = R * p, w = rp + t;
    double best = gate, r = 0.0;
    const Wall* nearest = nullptr;
    for (const Wall& wall : walls) {
      const double u = (w - wall.a).dot(wall.e) * wall.inv_len2;
      if (u < 0.0 || u > 1.0) continue;
      const double d = wall.normal.dot(w - wall.a);
      if (std::abs(d) < best) best = std::abs(d), r = d, nearest = &wall;
    }
    if (nearest == nullptr) continue;
    const Eigen::Vector2d& n = nearest->normal;
    const Eigen::Vector3d J(n.x(), n.y(), n.dot(Eigen::Vector2d(-rp.y(), rp.x())));
    equations.H += J * J.transpose();
    equations.g += J * r;
    equations.sum2 += r * r;
    ++equations.used;
  }
  return equations;
}

/// Gauss-Newton on the distances from the scan's points (robot frame) to their nearest map
/// wall, with a shrinking gate: a pose from a few located vertices, made exact by every
/// reading on the walls it explains.
Pose2 polish(const std::vector<Eigen::Vector2d>& points, const std::vector<Wall>& walls,
             Pose2 pose) {
  for (const double gate : {0.3, 0.15, 0.08, 0.04, 0.04}) {
    const NormalEquations equations = normal_equations(points, walls, pose, gate);
    if (equations.used < 3) break;
    const Eigen::Vector3d step = equations.H.ldlt().solve(-equations.g);
    if (!step.allFinite()) break;
    pose = {pose.x + step.x(), pose.y + step.y(), normalize_angle(pose.theta + step.z())};
  }
  return pose;
}

/// The Gauss-Newton covariance sigma^2 H^-1 of a pose fitted to the walls (polish()'s last
/// gate): sigma^2 from the residuals, infinite variances where the walls leave a direction
/// free (a corridor's axis).
Eigen::Matrix3d pose_covariance(const std::vector<Eigen::Vector2d>& points,
                                const std::vector<Wall>& walls, const Pose2& pose) {
  const NormalEquations equations = normal_equations(points, walls, pose, 0.04);
  const Eigen::Matrix3d& H = equations.H;
  const int used = equations.used;
  const double sum2 = equations.sum2;
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::Matrix3d cov = Eigen::Matrix3d::Constant(inf);
  if (used <= 3) return cov;
  // A floor on sigma: exact (noise-free) readings would claim an exact pose.
  const double sigma2 = std::max(sum2 / (used - 3), 1e-6);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(H);
  if (eig.eigenvalues().minCoeff() < 1e-9 * std::max(1.0, eig.eigenvalues().maxCoeff())) {
    return cov;
  }
  return sigma2 * H.inverse();
}

/// Seed 000 §3.1's scan is a full turn: angles increase and cover 360 deg without a large
/// gap. Throws gridloc::Error naming the fault otherwise (a 180 or 270 deg field of view, a
/// scan in degrees, clockwise beams).
void check_full_turn(const RangeScan& scan) {
  const std::size_t n = scan.angles.size();
  if (n < 3) throw Error("sectors: a scan of " + std::to_string(n) + " beams is no full turn");
  std::vector<double> steps;
  double widest = 0.0;
  std::size_t after = 0;
  for (std::size_t i = 1; i < n; ++i) {
    const double d = scan.angles[i] - scan.angles[i - 1];
    if (!(d > 0.0)) {
      throw Error("sectors: scan angles must increase (counter-clockwise beams); beam " +
                  std::to_string(i) + " is at " + std::to_string(scan.angles[i]) + " rad after " +
                  std::to_string(scan.angles[i - 1]));
    }
    steps.push_back(d);
    if (d > widest) widest = d, after = i - 1;
  }
  const double span = scan.angles.back() - scan.angles.front();
  if (span >= 2.0 * std::numbers::pi + 1e-9) {
    throw Error("sectors: scan angles span " + std::to_string(span) +
                " rad, more than a turn (radians expected)");
  }
  const double closing = 2.0 * std::numbers::pi - span;
  if (closing > widest) widest = closing, after = n - 1;
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2),
                   steps.end());
  const double step = steps[steps.size() / 2];
  if (widest > std::max(4.0 * step, 0.2)) {
    throw Error("sectors: the scan covers " +
                std::to_string(std::lround(rad2deg(2.0 * std::numbers::pi - widest))) +
                " deg (a gap of " + std::to_string(std::lround(rad2deg(widest))) +
                " deg after beam " + std::to_string(after) +
                "); visibility sectors need a full 360 deg turn");
  }
}

/// The options' ranges; throws gridloc::Error naming them.
void check_options(const SectorLocalizationOptions& options) {
  if (options.max_deleted_pairs < 0 || options.line_points < 2 ||
      !(options.ambiguity_residual_m >= 0.0) || !(options.residual_cap_m > 0.0) ||
      !(options.rough_residual_m > 0.0) || options.max_deleted_jumps < 0) {
    throw Error(
        "SectorLocalizationOptions: max_deleted_pairs and max_deleted_jumps must be >= 0, "
        "line_points >= 2, ambiguity_residual_m >= 0, residual_cap_m and rough_residual_m > 0");
  }
}

/// The scan as the localization reads it: its label, every beam as a point (robot frame, a
/// beam without return at the max range), the beams with a return and their points, and the
/// widest beam step.
struct ScanView {
  const RangeScan& scan;
  ScanLabel label;
  std::vector<Eigen::Vector2d> points;   ///< per beam
  std::vector<int> hits;                 ///< the beams with a return
  std::vector<Eigen::Vector2d> returns;  ///< their points
  double beam_step = 0.0;                ///< rad, at most 0.2
};

/// The scan's label, points, returns and beam step (see ScanView).
ScanView view_scan(const RangeScan& scan, const ScanLabelOptions& label_options) {
  ScanView view{scan, construct_scan_label(scan, label_options), {}, {}, {}, 0.0};
  const int n = static_cast<int>(scan.ranges.size());
  view.points.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double r = std::min(scan.ranges[i], scan.max_range);
    view.points[i] = r * Eigen::Vector2d(std::cos(scan.angles[i]), std::sin(scan.angles[i]));
  }
  for (int i = 0; i < n; ++i) {
    if (scan.ranges[i] < scan.max_range) view.hits.push_back(i);
  }
  for (int i = 0; i < n; ++i) {
    if (scan.ranges[i] < scan.max_range) view.returns.push_back(view.points[i]);
  }
  double beam_step = 2.0 * std::numbers::pi / n;
  for (int i = 1; i < n; ++i)
    beam_step = std::max(beam_step, std::abs(normalize_angle(scan.angles[i] - scan.angles[i - 1])));
  view.beam_step = std::min(beam_step, 0.2);
  return view;
}

/// What every step reads: the sectors, the options, the scan and the map's walls.
struct Problem {
  const SectorMap& sectors;
  const SectorLocalizationOptions& options;
  ScanView view;
  std::vector<Wall> walls;
};

/// How well the map explains the scan at a pose: each return's range (every `stride`-th)
/// against the range cast along its beam on the polygons, the difference capped, averaged.
/// Beams without return do not count: real scanners drop beams on glass and dark surfaces.
double range_residual(const Problem& problem, const Pose2& pose, int stride) {
  const RangeScan& scan = problem.view.scan;
  const std::vector<int>& hits = problem.view.hits;
  const Eigen::Vector2d origin(pose.x, pose.y);
  double sum = 0.0;
  int used = 0;
  for (std::size_t h = 0; h < hits.size(); h += static_cast<std::size_t>(stride), ++used) {
    const int i = hits[h];
    const double a = pose.theta + scan.angles[i];
    const Eigen::Vector2d dir(std::cos(a), std::sin(a));
    double expected = scan.max_range;
    for (const Wall& wall : problem.walls) {
      const Eigen::Vector2d &e = wall.e, w = wall.a - origin;
      const double den = cross2(dir, e);
      if (std::abs(den) < 1e-12) continue;  // parallel: not seen
      const double t = cross2(w, e) / den, u = cross2(w, dir) / den;
      if (t > 0.0 && t < expected && u >= 0.0 && u <= 1.0) expected = t;
    }
    sum += std::min(problem.options.residual_cap_m, std::abs(scan.ranges[i] - expected));
  }
  return sum / used;
}

/// Located vertices that a rigid motion cannot put near their map vertices are wrong
/// correspondences (a corner fitted across two surfaces) or a wrong match: cheap to rule out
/// before the residual. A D reading lies within a beam step of its corner, so the allowance
/// (m) grows with range.
double allowance(double beam_step, const Eigen::Vector2d& local) {
  return 0.3 + 1.5 * beam_step * local.norm();
}

/// The rigid fit with correspondences it cannot place left out, worst first (`local` keeps
/// the rest); nullopt when fewer than two remain.
std::optional<Pose2> trimmed_fit(std::vector<Eigen::Vector2d>& local,
                                 std::vector<Eigen::Vector2d> world, double beam_step) {
  while (local.size() >= 2) {
    const Pose2 pose = rigid_fit(local, world);
    const Eigen::Rotation2Dd R(pose.theta);
    const Eigen::Vector2d t(pose.x, pose.y);
    std::size_t worst = 0;
    double worst_excess = 0.0;
    for (std::size_t k = 0; k < local.size(); ++k) {
      const double excess = (R * local[k] + t - world[k]).norm() - allowance(beam_step, local[k]);
      if (excess > worst_excess) worst_excess = excess, worst = k;
    }
    if (worst_excess <= 0.0) return pose;
    local.erase(local.begin() + static_cast<std::ptrdiff_t>(worst));
    world.erase(world.begin() + static_cast<std::ptrdiff_t>(worst));
  }
  return std::nullopt;
}

/// The two caches of a localization: sectors with alike labels give the same pose from the
/// same vertices many times over (residuals, poses within 1e-9), and many sectors give the
/// same correspondences, hence the same rough pose (polishes, exact poses).
struct PoseMemo {
  std::vector<std::pair<Pose2, double>> residuals;  ///< pose, range_residual(pose, 1)
  std::vector<std::pair<Pose2, Pose2>> polishes;    ///< rough pose, polished pose

  /// range_residual() of every return at `pose`, remembered.
  double residual_at(const Problem& problem, const Pose2& pose) {
    for (const auto& [p, r] : residuals) {
      if (std::abs(p.x - pose.x) < 1e-9 && std::abs(p.y - pose.y) < 1e-9 &&
          std::abs(p.theta - pose.theta) < 1e-9) {
        return r;
      }
    }
    residuals.emplace_back(pose, range_residual(problem, pose, 1));
    return residuals.back().second;
  }

  /// `rough` polished on the walls, remembered; with `gated`, left rough when the scan
  /// refutes it.
  Pose2 polished(const Problem& problem, const Pose2& rough, bool gated) {
    for (const auto& [r, p] : polishes) {
      if (r.x == rough.x && r.y == rough.y && r.theta == rough.theta) return p;
    }
    // A rough pose from located corners that the scan plainly refutes (a quarter of the
    // returns, capped mean) is not worth a polish: wrong matches are most of the candidates,
    // and the polish most of the cost. Right matches are a few centimetres off before the
    // polish, far below the bar. Look-alike placements rest on two corners only and can be
    // tens of centimetres off: they are always polished.
    const bool refuted =
        gated && range_residual(problem, rough, 4) > problem.options.rough_residual_m;
    const Pose2 p = refuted ? rough : polish(problem.view.returns, problem.walls, rough);
    polishes.emplace_back(rough, p);
    return polishes.back().second;
  }
};

/// A match (sector and turn) that gave a pose.
struct Candidate {
  int sector;
  Pose2 pose;
  int deleted, matched;
  double residual;
  std::vector<Eigen::Vector2d> located;  ///< the vertices the pose was fitted to (robot frame)
};

/// How often `c` occurs in `label`.
std::ptrdiff_t count_of(const std::string& label, char c) {
  return std::count(label.begin(), label.end(), c);
}

/// The candidates of the scan's label variant `scan_variant` turned onto the sector's
/// `sector_variant`: one per turn that matches and whose pose lies in the free space.
void add_label_turns(const Problem& problem, PoseMemo& memo, std::size_t s,
                     const Variant& sector_variant, const Variant& scan_variant, int deleted,
                     std::vector<Candidate>& found) {
  const Sector& sector = problem.sectors.sectors[s];
  const ScanLabel& scan_label = problem.view.label;
  const int len = static_cast<int>(scan_variant.label.size());
  // Every turn that matches: a periodic label (a rectangle's mMmMmMmM) matches several,
  // and only the right one puts the vertices where the scan sees them.
  for (int k = 0; k < len; ++k) {
    bool equal = true;
    for (int j = 0; j < len && equal; ++j)
      equal = scan_variant.label[j] == sector_variant.label[(j + k) % len];
    if (!equal) continue;
    std::vector<Eigen::Vector2d> local, world;
    for (int j = 0; j < len; ++j) {
      if (scan_variant.label[j] != 'M') continue;
      const int feature = sector.features[sector_variant.index[(j + k) % len]];
      if (feature < 0) continue;
      local.push_back(locate_vertex(problem.view.points, scan_label.beam[scan_variant.index[j]],
                                    problem.options.line_points));
      world.push_back(problem.sectors.vertices[feature]);
    }
    if (local.size() < 2) continue;
    const std::optional<Pose2> fitted = trimmed_fit(local, world, problem.view.beam_step);
    if (!fitted) continue;
    const Pose2 pose = *fitted;
    if (problem.sectors.sector_at({pose.x, pose.y}) < 0) continue;  // off the free space
    found.push_back({static_cast<int>(s), pose, deleted, static_cast<int>(local.size()),
                     memo.residual_at(problem, pose), local});
  }
}

/// Seed 000's label match: every sector whose label equals the scan's turned, up to
/// max_deleted_pairs M m pairs left out, gives candidates.
void match_labels(const Problem& problem, PoseMemo& memo, std::vector<Candidate>& found) {
  const SectorLocalizationOptions& options = problem.options;
  const std::string& scan_label = problem.view.label.label;
  // Deletions on either side: the scan may miss a shallow pair the sector's label has, or
  // resolve one its label lacks (extrema move with the position inside a sector).
  // A scan misses more than it invents: most deletions go to the sector's side.
  const int scan_side = std::min(1, options.max_deleted_pairs);
  const int sector_side = options.max_deleted_pairs - scan_side;
  const std::vector<Variant> scan_variants = variants(scan_label, scan_side);
  // Only M m pairs are ever deleted: a sector whose label has other D and c counts cannot
  // match, and is skipped before its variants are built.
  for (std::size_t s = 0; s < problem.sectors.sectors.size(); ++s) {
    const Sector& sector = problem.sectors.sectors[s];
    if (count_of(sector.label, 'D') != count_of(scan_label, 'D') ||
        count_of(sector.label, 'c') != count_of(scan_label, 'c')) {
      continue;
    }
    for (const Variant& sector_variant : variants(sector.label, sector_side)) {
      for (const Variant& scan_variant : scan_variants) {
        const int len = static_cast<int>(scan_variant.label.size());
        if (static_cast<int>(sector_variant.label.size()) != len || len == 0) continue;
        const int deleted = (static_cast<int>(sector.label.size()) - len) / 2 +
                            (static_cast<int>(scan_label.size()) - len) / 2;
        if (deleted > options.max_deleted_pairs) continue;
        add_label_turns(problem, memo, s, sector_variant, scan_variant, deleted, found);
      }
    }
  }
}

/// The candidates of the scan's skeleton `scan_jumps` turned onto the sector's
/// `sector_jumps`: the D vertices and the M vertices of runs with as many M on both sides,
/// fitted, polished, one per turn that matches and lands in the free space.
void add_skeleton_turns(const Problem& problem, PoseMemo& memo, std::size_t s,
                        const std::vector<int>& scan_jumps, const std::vector<int>& sector_jumps,
                        int deleted, std::vector<Candidate>& found) {
  const Sector& sector = problem.sectors.sectors[s];
  const ScanLabel& scan_label = problem.view.label;
  const int ks = static_cast<int>(scan_jumps.size());
  for (int k = 0; k < ks; ++k) {
    bool equal = true;
    for (int j = 0; j < ks && equal; ++j)
      equal = scan_label.label[scan_jumps[j]] == sector.label[sector_jumps[(j + k) % ks]];
    if (!equal) continue;
    std::vector<Eigen::Vector2d> local, world;
    for (int j = 0; j < ks; ++j) {
      const int a = scan_jumps[j], b = sector_jumps[(j + k) % ks];
      if (scan_label.label[a] == 'D' && sector.features[b] >= 0) {
        local.push_back(problem.view.points[scan_label.beam[a]]);
        world.push_back(problem.sectors.vertices[sector.features[b]]);
      }
      const auto scan_maxima = maxima_between(scan_label.label, a, scan_jumps[(j + 1) % ks]);
      const auto sector_maxima = maxima_between(sector.label, b, sector_jumps[(j + k + 1) % ks]);
      if (scan_maxima.size() != sector_maxima.size()) continue;
      for (std::size_t q = 0; q < scan_maxima.size(); ++q) {
        if (sector.features[sector_maxima[q]] < 0) continue;
        local.push_back(locate_vertex(problem.view.points, scan_label.beam[scan_maxima[q]],
                                      problem.options.line_points));
        world.push_back(problem.sectors.vertices[sector.features[sector_maxima[q]]]);
      }
    }
    if (local.size() < 2) continue;
    const std::optional<Pose2> rough = trimmed_fit(local, world, problem.view.beam_step);
    if (!rough) continue;
    const Pose2 pose = memo.polished(problem, *rough, true);
    if (problem.sectors.sector_at({pose.x, pose.y}) < 0) continue;
    // Behind every label match: ties go to the seed's own matching.
    found.push_back({static_cast<int>(s), pose, problem.options.max_deleted_pairs + 1 + deleted,
                     static_cast<int>(local.size()), memo.residual_at(problem, pose), local});
  }
}

/// Partial views (seed 000's assumption (ii) failing: too few beams on a far, short or
/// grazing edge) add or drop extrema between the jumps but keep the jumps. A sector whose D c
/// skeleton is the scan's, turned, gives correspondences from its D vertices (the occluding
/// corners, read at the near side of each jump: within a beam step) and from the M vertices
/// of the runs between jumps that hold as many M as the scan's; polish() then fits the pose
/// to every reading.
/// A jump can also come or go: a wall seen at a grazing angle by coarse beams jumps by more
/// than epsilon_T between neighbours, a narrow gap falls between two beams. Up to
/// max_deleted_jumps neighbouring D c pairs of either skeleton are left out.
void match_skeletons(const Problem& problem, PoseMemo& memo, std::vector<Candidate>& found) {
  const SectorLocalizationOptions& options = problem.options;
  const std::string& scan_label = problem.view.label.label;
  const std::vector<int> scan_skeleton = skeleton(scan_label);
  if (!options.skeleton_matching || scan_skeleton.size() < 2) return;
  const auto jump_variants =
      skeleton_variants(scan_label, scan_skeleton, options.max_deleted_jumps);
  for (std::size_t s = 0; s < problem.sectors.sectors.size(); ++s) {
    const std::string& label = problem.sectors.sectors[s].label;
    const std::vector<int> sector_skeleton = skeleton(label);
    const std::size_t ks = scan_skeleton.size();
    if (sector_skeleton.size() == ks)
      add_skeleton_turns(problem, memo, s, scan_skeleton, sector_skeleton, 0, found);
    // One side's pairs left out, never both (that would match too much).
    if (sector_skeleton.size() < ks) {
      for (const auto& scan_jumps : jump_variants) {
        if (scan_jumps.size() == sector_skeleton.size())
          add_skeleton_turns(problem, memo, s, scan_jumps, sector_skeleton,
                             static_cast<int>(ks - scan_jumps.size()) / 2, found);
      }
    } else if (sector_skeleton.size() > ks) {
      for (const auto& sector_jumps :
           skeleton_variants(label, sector_skeleton, options.max_deleted_jumps)) {
        if (sector_jumps.size() == ks)
          add_skeleton_turns(problem, memo, s, scan_skeleton, sector_jumps,
                             static_cast<int>(sector_skeleton.size() - ks) / 2, found);
      }
    }
  }
}

/// 0 when the candidate's pose lies in the sector it matched, else 1.
int home(const SectorMap& sectors, const Candidate& candidate) {
  return sectors.sector_at({candidate.pose.x, candidate.pose.y}) == candidate.sector ? 0 : 1;
}

/// The best candidate: the smallest residual; sectors whose labels match alike often give
/// the same pose from the same vertices: among equal residuals, the candidate whose pose lies
/// in the sector it matched names the sector, then the fewest deletions.
std::vector<Candidate>::const_iterator best_candidate(const SectorMap& sectors,
                                                      const std::vector<Candidate>& found) {
  return std::min_element(found.begin(), found.end(), [&](const Candidate& a, const Candidate& b) {
    if (a.residual != b.residual) return a.residual < b.residual;
    if (home(sectors, a) != home(sectors, b)) return home(sectors, a) < home(sectors, b);
    return a.deleted < b.deleted;
  });
}

/// Whether `p` (robot frame) lies, at pose `at`, within its allowance of a map vertex.
bool near_vertex(const Problem& problem, const Pose2& at, const Eigen::Vector2d& p) {
  const auto& vertices = problem.sectors.vertices;
  const Eigen::Vector2d w = Eigen::Rotation2Dd(at.theta) * p + Eigen::Vector2d(at.x, at.y);
  return std::any_of(vertices.begin(), vertices.end(), [&](const Eigen::Vector2d& u) {
    return (u - w).norm() <= allowance(problem.view.beam_step, p);
  });
}

/// Look-alikes (seed 000 §4.1): the label names vertices by the sector they were read in, and
/// a look-alike place whose sector's label came out otherwise (labels vary inside a sector)
/// would never be tried. So the winner's two farthest located vertices are also put on every
/// other pair of map vertices as far apart; a placement that lands the other located vertices
/// on map vertices too is polished and scored like any candidate.
void add_lookalikes(const Problem& problem, PoseMemo& memo, std::vector<Candidate>& found) {
  if (!problem.options.lookalike_search || found.empty()) return;
  const Candidate winner = *best_candidate(problem.sectors, found);
  const auto& vertices = problem.sectors.vertices;
  // Only the located corners that land on a map vertex at the winner's own pose: the
  // polish may have moved it from where its rough fit put a wall point.
  std::vector<Eigen::Vector2d> corners;
  for (const auto& p : winner.located) {
    if (near_vertex(problem, winner.pose, p)) corners.push_back(p);
  }
  if (corners.size() < 2) return;
  std::size_t a = 0, b = 1;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    for (std::size_t j = i + 1; j < corners.size(); ++j) {
      if ((corners[i] - corners[j]).norm() > (corners[a] - corners[b]).norm()) a = i, b = j;
    }
  }
  const double spread = (corners[a] - corners[b]).norm();
  const double beam_step = problem.view.beam_step;
  const double tolerance =
      2.0 * std::max(allowance(beam_step, corners[a]), allowance(beam_step, corners[b])) - 0.3;
  if (!(spread > 0.3)) return;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    for (std::size_t j = 0; j < vertices.size(); ++j) {
      if (i == j || std::abs((vertices[i] - vertices[j]).norm() - spread) > tolerance) continue;
      const Pose2 rough = rigid_fit({corners[a], corners[b]}, {vertices[i], vertices[j]});
      const bool lands = std::all_of(corners.begin(), corners.end(), [&](const Eigen::Vector2d& p) {
        return near_vertex(problem, rough, p);
      });
      if (!lands) continue;
      const Pose2 pose = memo.polished(problem, rough, false);
      const int sector = problem.sectors.sector_at({pose.x, pose.y});
      if (sector < 0) continue;
      found.push_back({sector, pose, winner.deleted + 1, winner.matched,
                       memo.residual_at(problem, pose), corners});
    }
  }
}

/// The sector the fix names: one whose label matched with (nearly) the best pose and that
/// holds it, when there is one (a neighbour's alike label may explain the scan a hair
/// better), else the best candidate's.
int named_sector(const SectorMap& sectors, const std::vector<Candidate>& found,
                 const Candidate& best) {
  if (home(sectors, best) == 0) return best.sector;
  for (const auto& c : found) {
    if (home(sectors, c) == 0 &&
        std::hypot(c.pose.x - best.pose.x, c.pose.y - best.pose.y) < 0.02 &&
        std::abs(normalize_angle(c.pose.theta - best.pose.theta)) < 0.01) {
      return c.sector;
    }
  }
  return best.sector;
}

/// A distinct pose that explains the scan about as well: in another sector with the same
/// label (seed 000 §4.1), or in the same sector of a symmetric room (a rectangle's twin pose
/// turned by 180 deg). The alternatives are the best and those poses, best first, each
/// distinct from all before it.
std::vector<SectorFix::Alternative> alternatives(const std::vector<Candidate>& found,
                                                 const Candidate& best, double within) {
  const auto distinct = [](const Pose2& p, const Pose2& q) {
    return std::hypot(p.x - q.x, p.y - q.y) > 0.3 ||
           std::abs(normalize_angle(p.theta - q.theta)) > 0.26;
  };
  std::vector<const Candidate*> close;
  for (const auto& c : found) {
    if (c.residual <= best.residual + within) close.push_back(&c);
  }
  std::stable_sort(close.begin(), close.end(), [](const Candidate* a, const Candidate* b) {
    return a->residual < b->residual;
  });
  std::vector<SectorFix::Alternative> out{{best.pose, best.residual}};
  for (const Candidate* c : close) {
    if (std::all_of(out.begin(), out.end(),
                    [&](const SectorFix::Alternative& x) { return distinct(x.pose, c->pose); })) {
      out.push_back({c->pose, c->residual});
    }
  }
  return out;
}

/// The fix of the candidates: the best one's pose, sector and residual, the look-alikes and
/// the covariance; not found without candidates.
SectorFix make_fix(const Problem& problem, const std::vector<Candidate>& found) {
  SectorFix fix;
  fix.scan_label = problem.view.label.label;
  if (found.empty()) return fix;
  fix.candidates = static_cast<int>(found.size());
  const Candidate& best = *best_candidate(problem.sectors, found);
  fix.found = true;
  fix.sector = named_sector(problem.sectors, found, best);
  fix.pose = best.pose;
  fix.deleted_pairs = best.deleted;
  fix.matched_m = best.matched;
  fix.residual_m = best.residual;
  fix.alternatives = alternatives(found, best, problem.options.ambiguity_residual_m);
  fix.ambiguous = fix.alternatives.size() > 1;
  fix.covariance = pose_covariance(problem.view.returns, problem.walls, fix.pose);
  return fix;
}

}  // namespace

SectorFix localize_in_sectors(const SectorMap& sectors, const RangeScan& scan,
                              const SectorLocalizationOptions& options) {
  validate(scan);
  check_full_turn(scan);
  check_options(options);
  const Problem problem{sectors, options, view_scan(scan, options.label),
                        walls_of(polygon_edges(sectors.map))};
  PoseMemo memo;
  std::vector<Candidate> found;
  match_labels(problem, memo, found);
  match_skeletons(problem, memo, found);
  add_lookalikes(problem, memo, found);
  return make_fix(problem, found);
}

}  // namespace gridloc
