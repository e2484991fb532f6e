// Seed 000 §3: localization from a scan label and the sectors' labels: the label and skeleton
// matches, the look-alikes and the fix.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>

#include "gridloc/engine/sectors/localization.hpp"
#include "label_variants.hpp"
#include "localization_problem.hpp"
#include "pose_fit.hpp"

namespace gridloc {
using namespace sectors_detail;
namespace {

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
