// Seed 000 §3: localization from a scan label and the sectors' labels.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "gridloc/engine/visibility_sectors.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

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
        Variant w;
        for (int k = 0; k < n; ++k) {
          if (k == i || k == j) continue;
          w.label.push_back(out[v].label[k]);
          w.index.push_back(out[v].index[k]);
        }
        const bool seen = std::any_of(out.begin(), out.end(),
                                      [&](const Variant& x) { return x.index == w.index; });
        if (!seen) out.push_back(std::move(w));
      }
    }
    from = to;
  }
  return out;
}

/// The vertex at an M reading: the intersection of the lines fitted to `k` readings on each
/// side (seed 000 eqs. (6)-(9)), or the reading itself when they are near parallel.
Eigen::Vector2d locate_vertex(const std::vector<Eigen::Vector2d>& pts, int beam, int k) {
  const int n = static_cast<int>(pts.size());
  const auto P = [&](int i) { return pts[((i % n) + n) % n]; };
  const auto fit = [&](int dir, Eigen::Vector2d& c, Eigen::Vector2d& d) {
    c.setZero();
    for (int s = 1; s <= k; ++s) c += P(beam + dir * s);
    c /= k;
    Eigen::Matrix2d S = Eigen::Matrix2d::Zero();
    for (int s = 1; s <= k; ++s) S += (P(beam + dir * s) - c) * (P(beam + dir * s) - c).transpose();
    d = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(S).eigenvectors().col(1);
  };
  Eigen::Vector2d c1, d1, c2, d2;
  fit(+1, c1, d1);
  fit(-1, c2, d2);
  const double den = d1.x() * d2.y() - d1.y() * d2.x();
  if (std::abs(den) < 0.05) return P(beam);  // < 3 deg apart: no corner to intersect
  const Eigen::Vector2d w = c2 - c1;
  const double t = (w.x() * d2.y() - w.y() * d2.x()) / den;
  const Eigen::Vector2d v = c1 + t * d1;
  // A corner far from its reading is a bad fit (another surface in the window).
  return (v - P(beam)).norm() < 0.3 + 0.05 * P(beam).norm() ? v : P(beam);
}

/// Rigid fit: the pose (R, t) with world = R * local + t, least squares.
Pose2 rigid_fit(const std::vector<Eigen::Vector2d>& local,
                const std::vector<Eigen::Vector2d>& world) {
  Eigen::Vector2d lc = Eigen::Vector2d::Zero(), wc = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < local.size(); ++k) lc += local[k], wc += world[k];
  lc /= static_cast<double>(local.size());
  wc /= static_cast<double>(world.size());
  double s = 0.0, c = 0.0;
  for (std::size_t k = 0; k < local.size(); ++k) {
    const Eigen::Vector2d a = local[k] - lc, b = world[k] - wc;
    c += a.dot(b);
    s += a.x() * b.y() - a.y() * b.x();
  }
  const double theta = std::atan2(s, c);
  const Eigen::Vector2d t = wc - Eigen::Rotation2Dd(theta) * lc;
  return {t.x(), t.y(), theta};
}

}  // namespace

SectorFix localize_in_sectors(const SectorMap& sectors, const RangeScan& scan,
                              const SectorLocalizationOptions& o) {
  validate(scan);
  if (o.max_deleted_pairs < 0 || o.line_points < 2) {
    throw Error("SectorLocalizationOptions: max_deleted_pairs must be >= 0, line_points >= 2");
  }
  const ScanLabel l = construct_scan_label(scan, o.label);
  SectorFix fix;
  fix.scan_label = l.label;
  const int n = static_cast<int>(scan.ranges.size());
  std::vector<Eigen::Vector2d> pts(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double r = std::min(scan.ranges[i], scan.max_range);
    pts[i] = r * Eigen::Vector2d(std::cos(scan.angles[i]), std::sin(scan.angles[i]));
  }
  double reach = 0.0;
  for (const auto& v : sectors.vertices) reach = std::max(reach, v.norm());
  // How well the map explains the scan at a pose: the median range difference, each beam
  // against the nearest beam of a dense noise-free scan (any beam layout works).
  constexpr int kDense = 3600;
  const auto residual_at = [&](const Pose2& pose) {
    const RangeScan expected =
        polygon_scan(sectors.map, pose, kDense, std::max(scan.max_range, 1.0));
    std::vector<double> diff;
    diff.reserve(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      double a = std::fmod(scan.angles[i], 2.0 * std::numbers::pi);
      if (a < 0.0) a += 2.0 * std::numbers::pi;
      const int k = static_cast<int>(std::lround(a / (2.0 * std::numbers::pi) * kDense)) % kDense;
      diff.push_back(std::abs(std::min(scan.ranges[i], scan.max_range) -
                              std::min(expected.ranges[k], scan.max_range)));
    }
    const auto mid = diff.begin() + static_cast<std::ptrdiff_t>(diff.size() / 2);
    std::nth_element(diff.begin(), mid, diff.end());
    return *mid;
  };
  struct Candidate {
    int sector;
    Pose2 pose;
    int deleted, matched;
    double residual;
  };
  std::vector<Candidate> found;
  // Deletions on either side: the scan may miss a shallow pair the sector's label has, or
  // resolve one its label lacks (extrema move with the position inside a sector).
  // A scan misses more than it invents: most deletions go to the sector's side.
  const int scan_side = std::min(1, o.max_deleted_pairs);
  const int sector_side = o.max_deleted_pairs - scan_side;
  const std::vector<Variant> scan_variants = variants(l.label, scan_side);
  // Only M m pairs are ever deleted: a sector whose label has other D and c counts cannot
  // match, and is skipped before its variants are built.
  const auto count = [](const std::string& x, char c) { return std::count(x.begin(), x.end(), c); };
  for (std::size_t s = 0; s < sectors.sectors.size(); ++s) {
    const Sector& sec = sectors.sectors[s];
    if (count(sec.label, 'D') != count(l.label, 'D') ||
        count(sec.label, 'c') != count(l.label, 'c')) {
      continue;
    }
    for (const Variant& sv : variants(sec.label, sector_side)) {
      for (const Variant& qv : scan_variants) {
        const int len = static_cast<int>(qv.label.size());
        if (static_cast<int>(sv.label.size()) != len || len == 0) continue;
        const int deleted = (static_cast<int>(sec.label.size()) - len) / 2 +
                            (static_cast<int>(l.label.size()) - len) / 2;
        if (deleted > o.max_deleted_pairs) continue;
        // Every turn that matches: a periodic label (a rectangle's mMmMmMmM) matches several,
        // and only the right one puts the vertices where the scan sees them.
        for (int k = 0; k < len; ++k) {
          bool equal = true;
          for (int j = 0; j < len && equal; ++j) equal = qv.label[j] == sv.label[(j + k) % len];
          if (!equal) continue;
          std::vector<Eigen::Vector2d> local, world;
          for (int j = 0; j < len; ++j) {
            if (qv.label[j] != 'M') continue;
            const int feature = sec.features[sv.index[(j + k) % len]];
            if (feature < 0) continue;
            local.push_back(locate_vertex(pts, l.beam[qv.index[j]], o.line_points));
            world.push_back(sectors.vertices[feature]);
          }
          if (local.size() < 2) continue;
          const Pose2 pose = rigid_fit(local, world);
          if (sectors.sector_at({pose.x, pose.y}) < 0) continue;  // off the free space
          found.push_back({static_cast<int>(s), pose, deleted, static_cast<int>(local.size()),
                           residual_at(pose)});
        }
      }
    }
  }
  fix.candidates = static_cast<int>(found.size());
  if (found.empty()) return fix;
  const auto best =
      std::min_element(found.begin(), found.end(), [](const Candidate& a, const Candidate& b) {
        return a.residual != b.residual ? a.residual < b.residual : a.deleted < b.deleted;
      });
  fix.found = true;
  fix.sector = best->sector;
  fix.pose = best->pose;
  fix.deleted_pairs = best->deleted;
  fix.matched_m = best->matched;
  fix.residual_m = best->residual;
  for (const auto& c : found) {
    if (c.sector != best->sector && c.residual <= best->residual + 0.02 &&
        std::hypot(c.pose.x - best->pose.x, c.pose.y - best->pose.y) > 0.3) {
      fix.ambiguous = true;
    }
  }
  return fix;
}

}  // namespace gridloc
