#pragma once
/// Exact branch and bound over translations and headings (DESIGN.md, "Global grid"): blocks
/// of 2^h x 2^h translations, and for rigid scans intervals of 2^a headings, are bounded from
/// above with max / min pooled global grids and pruned against the best pose found so far.
/// Returns what search_exhaustive returns, bit for bit, while scoring far fewer poses.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "gridloc/engine/correlation/search.hpp"
#include "gridloc/grids/grid.hpp"

namespace gridloc {

/// Bound grids of one PaddedGrid, built once. At level h (blocks of 2^h x 2^h translations),
/// arc_max[h] is the PaddedGrid's arc_view max-pooled and grid_min[h] its grid min-pooled,
/// cell (x, y) covering [x, x + 2^h) x [y, y + 2^h); both keep the padded geometry, so a
/// PlacedLocalGrid's offsets apply unchanged. Level 0 is the PaddedGrid itself and is not
/// copied: arc_max[0] and grid_min[0] are empty. A ternary pyramid (below) keeps its levels
/// only as int8, which is all its bounds read: its arc_max[h] and grid_min[h] then hold the
/// geometry and no cells. A plain value, safe to copy or move.
struct BoundPyramid {
  std::vector<EvidenceGrid> arc_max;   ///< [h] for h = 1..depth; [0] empty
  std::vector<EvidenceGrid> grid_min;  ///< [h] for h = 1..depth; [0] empty
  int pad = 0;                         ///< the source PaddedGrid's pad, width and height:
  int width = 0;                       ///< checked against the grid searched
  int height = 0;
  float arc_max_all = 0.0f;   ///< max of the arc view and min of the grid over the whole
  float grid_min_all = 0.0f;  ///< padded grid: the bound of a window wider than any level
  float abs_max = 0.0f;       ///< max |value| of the grid and arc view (rounding slack)
  /// When every value of the grid is a whole multiple of 1 / s for the int8_scale s of
  /// int8_scale_for (-1/0/1 evidence grids: s = 1; a likelihood field: kFieldLevels):
  /// levels 0..depth again as int8 times s, which the bounds read: the same values from 4x
  /// less memory, so the same sums with fewer cache misses, and from the fixed-point
  /// kernel's integer lanes. Each ends in kGatherSlack bytes. [0] is empty: level 0 is the
  /// PaddedGrid's own int8 copies (arc_view8(), grid8), read from there. Empty otherwise.
  std::vector<Int8Cells> arc_max8;
  std::vector<Int8Cells> grid_min8;
  float int8_scale = 1.0f;
  bool has_int8() const { return !arc_max8.empty(); }
  /// int8 levels of a grid whose values are all -1, 0 or 1.
  bool ternary() const { return has_int8() && int8_scale == 1.0f; }

  /// Whether grid_min holds each level's min-pooled grid. Without them (a search whose local
  /// grids are all positive, a scan's hits, reads none) every level above 0 is one grid of
  /// grid_min_all, a looser bound that still holds: grid_min[1] and grid_min8[1].
  bool min_levels = true;
  /// Whether arc_max[h] and grid_min[h] hold float cells. Without them (a ternary grid, or
  /// an int8 pyramid without min levels) the bounds read the int8 levels; a local grid the
  /// fixed-point kernel cannot read is then bounded by the whole grid's extremes.
  bool float_levels = true;

  /// The top level h (0 when only level 0 exists).
  int depth() const { return static_cast<int>(arc_max.size()) - 1; }
  /// The level the negative cells of a bound at level h read (h >= 1).
  std::size_t min_level(int h) const { return min_levels ? static_cast<std::size_t>(h) : 1; }
};

/// Which grids a bound pyramid pools: both, or only the max-pooled arc view (then the
/// negative cells of a bound read the whole grid's minimum; BoundPyramid::min_levels).
enum class PyramidLevels { MaxAndMin, MaxOnly };

/// Builds levels 1..depth of `global`'s bound pyramid (depth >= 0; throws gridloc::Error
/// otherwise), O(padded cells) per level. Needs no padding beyond what score() needs
/// (pad >= the local grids' extent), whatever the depth: the search only makes blocks that
/// start inside the lattice, and the pooled windows are clipped at the padded grid's edge.
BoundPyramid make_bound_pyramid(const PaddedGrid& global, int depth,
                                PyramidLevels levels = PyramidLevels::MaxAndMin);

/// The smallest depth whose top-level blocks cover the lattice's translations in one block
/// per heading: ceil(log2(max(columns, rows))); a deeper pyramid adds nothing for it.
int bound_depth_for(const Lattice& lattice);

/// Upper bound on the score of `local` anywhere on the grid: each positive cell times the
/// arc view's maximum, each negative one times the grid's minimum.
inline double extremes_bound(const BoundPyramid& pyramid, const PlacedLocalGrid& local) {
  double bound = 0.0;
  for (std::size_t k = 0; k < local.value.size(); ++k) {
    const double v = local.value[k];
    bound += v * (k < local.arc_count ? std::max(pyramid.arc_max_all, 0.0f)
                                      : std::min(pyramid.grid_min_all, 0.0f));
  }
  return bound + 1e-6 * (1.0 + std::abs(bound));  // float rounding of the exact sums
}

/// Upper bound on score(global, local, x, y) for every (x, y) in [ix, ix + 2^h) x
/// [iy, iy + 2^h) that lies in the map, at level 1 <= h <= pyramid.depth(); (ix, iy) must
/// lie in the map. Computed exactly as score() computes a score, with pooled values: each
/// term is then >= the matching score term after float rounding, and so is each partial sum
/// after double rounding (rounding is monotone), so the bound holds bit for bit, no epsilon.
inline double block_bound(const BoundPyramid& pyramid, const PlacedLocalGrid& local, int h, int ix,
                          int iy) {
  const auto& arc_grid = pyramid.arc_max[static_cast<std::size_t>(h)];
  const std::ptrdiff_t origin =
      static_cast<std::ptrdiff_t>(iy + pyramid.pad) * arc_grid.width() + (ix + pyramid.pad);
  const auto level = static_cast<std::size_t>(h);
  // score() reads int8 copies scaled by 1 / s only for fixed-point local grids: so here.
  if (pyramid.has_int8() && (pyramid.int8_scale == 1.0f || local.fixed_shift >= 0)) {
    return correlate(pyramid.arc_max8[level].data() + origin,
                     pyramid.grid_min8[pyramid.min_level(h)].data() + origin, local) /
           static_cast<double>(pyramid.int8_scale);
  }
  if (!pyramid.float_levels) return extremes_bound(pyramid, local);
  return correlate(arc_grid.cells.data() + origin,
                   pyramid.grid_min[pyramid.min_level(h)].cells.data() + origin, local);
}

/// Poses left out of a search: those within `radius_cells` (Euclidean, in cells) and
/// `radius_headings` (heading indices) of `center`. Used to find the best pose *distinct*
/// from a winner, exactly.
struct Exclusion {
  LatticePose center;
  double radius_cells = 0.0;
  int radius_headings = 0;
  /// Heading steps per full turn (2 pi / step, not always whole) when the lattice covers
  /// every heading, so that the zone wraps around +-pi; 0 when it does not.
  double turn_headings = 0.0;

  /// Heading steps from the centre's heading to `it`, the short way round when wrapping.
  double heading_distance(int it) const {
    const double d = std::abs(it - center.it);
    return turn_headings > 0.0 ? std::min(d, std::abs(turn_headings - d)) : d;
  }
  bool contains(int ix, int iy, int it) const {
    return heading_distance(it) <= radius_headings + 1e-9 &&
           std::hypot(ix - center.ix, iy - center.iy) <= radius_cells;
  }
  /// True when every translation of [x0, x1] x [y0, y1] at every heading of [it0, it1] is
  /// excluded: the heading and disc tests are independent, so the interval's two ends and
  /// the rectangle's four corners (a disc holds a rectangle when it holds its corners) do.
  /// When wrapping, an interval whose ends lie in the zone lies in it if it is no longer than
  /// the zone and the zone is shorter than half a turn (it cannot go round the other way).
  bool contains_block(int it0, int it1, int x0, int y0, int x1, int y1) const {
    if (turn_headings > 0.0 &&
        (it1 - it0 > 2 * radius_headings || 4.0 * radius_headings >= turn_headings)) {
      return false;
    }
    return contains(x0, y0, it0) && contains(x0, y0, it1) && contains(x1, y0, it0) &&
           contains(x0, y1, it0) && contains(x1, y1, it0);
  }
};

/// The local grids of a lattice's headings, made on first use and kept, so that a search
/// builds only the headings it opens and several searches share them. Thread-safe. With
/// rigid points (SearchLevel::points) it also keeps, per heading, every point's cell, which
/// the heading-interval bounds read.
class HeadingGrids {
 public:
  /// Throws gridloc::Error when `finest` has no grid, or its points reach beyond the padding.
  HeadingGrids(const Lattice& lattice, const SearchLevel& finest);

  /// Heading it's local grid placed on the level's grid; throws gridloc::Error when it
  /// reaches beyond the padding.
  const PlacedLocalGrid& placed(int it) const;
  /// Heading it's rigid points, not merged: beam ends and free samples apart, each sorted by
  /// offset (requires points()).
  struct PointCells {
    std::vector<std::ptrdiff_t> hit_offset, free_offset;  ///< in the padded grid
    std::vector<int> hit_x, hit_y, free_x, free_y;        ///< cells from the robot's cell
  };
  const PointCells& point_cells(int it) const;
  /// Makes every heading now (in parallel with the level's threads).
  void make_all() const;

  const Lattice& lattice() const { return lattice_; }
  const SearchLevel& level() const { return level_; }
  const ScanPoints* points() const { return level_.points; }

 private:
  /// A heading's grids, each made once by the first thread that asks (double-checked: a
  /// made grid costs one atomic load; std::call_once's glibc path ended every first call in a
  /// futex system call, 161 of them a windowed search on the apartment).
  struct Entry {
    std::atomic<bool> placed_made{false}, cells_made{false};
    std::mutex making;
    PlacedLocalGrid placed;
    PointCells cells;
  };
  Lattice lattice_;
  SearchLevel level_;
  std::unique_ptr<Entry[]> entries_;
};

struct BranchAndBoundOptions {
  /// Poses never candidates (those in any of the zones): the result is the exhaustive best
  /// among the others. Zones found one after another give the top distinct hypotheses.
  std::vector<Exclusion> exclude;
  /// A lattice pose with its exact score, known before the search (e.g. the best pose outside
  /// `exclude` that an earlier search scored): prunes from the start. It must lie outside
  /// `exclude`; the result is it when nothing beats it.
  std::optional<LatticePose> incumbent;
  /// Only poses scoring at least this are candidates: a node whose bound is below it is
  /// dropped (a valid bound: none of its poses reaches it). When no pose reaches it the
  /// result is the incumbent, or a pose scoring less (SearchResult::best.score < min_score
  /// says so); a second peak below a share of the winner changes no verdict.
  double min_score = -std::numeric_limits<double>::infinity();
  /// Below 1: also expand every node whose bound reaches this share of the incumbent's
  /// (positive) score, so that SearchResult::scored holds every pose scoring at least this
  /// share of the best (the incumbent only rises: none is dropped). The best pose is the
  /// same; the hypotheses after it come from `scored` in the same pass.
  double keep_share = 1.0;
  /// With keep_share: the neighbourhood of the best pose (its radii; the centre is ignored)
  /// whose poses keep_share need not keep. A node kept only by keep_share that lies wholly
  /// within this neighbourhood of the incumbent is set aside, and once the best pose is
  /// known only those not wholly within its neighbourhood are searched: `scored` then holds
  /// every pose scoring keep_share of the best outside that neighbourhood (and the best),
  /// which is all the hypotheses after the best need when they must lie outside it.
  std::optional<Exclusion> keep_outside;
  /// Anytime search: stop after about this many milliseconds (0: no limit) and return the
  /// best pose so far, with SearchResult::proven_optimal false when open blocks could still
  /// hold a better one, and SearchResult::upper_bound the most any pose could score.
  double budget_ms = 0.0;
  /// Bound intervals of headings too when the level has rigid points (see below). Exact
  /// either way; on the apartment peer case it prunes more headings unopened but its bounds
  /// are looser, so it was slower than one node per heading (bench/RESULTS.md).
  bool heading_intervals = false;
  /// Threads, each making the top-level nodes of its share of the headings and searching them
  /// best first in its own heap, pruning with the shared incumbent and stealing from the
  /// others' heaps when its own runs dry. The result does not depend on it (exact); the
  /// counters and `scored` do.
  int threads = 1;
};

/// Exact branch-and-bound search over the whole lattice on the finest level: the same best
/// pose and score as search_exhaustive(lattice, finest), ties to the lowest (it, iy, ix), unless
/// a budget stops it. The grids must be of `lattice`; `pyramid` must come from the level's
/// grid (checked by geometry only); the lattice must be non-empty and inside the map, and
/// every local grid's extent <= pad (gridloc::Error otherwise).
///
/// Nodes are blocks of 2^h x 2^h translations times one heading, bounded with the heading's
/// local grid on pooled level h (block_bound), or, when the level has rigid points, times an
/// interval of 2^a headings: rotating the robot within the interval moves a point by at most
/// w = floor(max |p| * (angle to the interval's middle heading) / resolution) + 1 cells per
/// axis from its cell at the middle heading, so each point's term is bounded by pooling over
/// the block widened by w on every side (the level whose blocks cover 2^h + 2w cells, read
/// w cells before the block): + max(arc view, 0) for a beam end, weight * min(grid, 0) for
/// a free sample (beam ends merged in one cell and free samples under an end count at most
/// that). The free samples' weights must all be equal (scan_points makes them so). These
/// sums differ in structure from score()'s, so they get a rounding slack of (points + 4) * 2^-24 *
/// sum |weight| * max |grid|, which only loosens. Any depth is exact; translations start at
/// min(pyramid.depth(), bound_depth_for(lattice)), headings at the widest interval whose widening
/// stays within half that block. Intervals are split while their widening is at least half the
/// block, blocks otherwise.
///
/// Best first (highest bound, then lowest first pose; one heap per thread) down to blocks of
/// 32 cells a side that lie at least 5 levels below the top, whose subtrees are then searched
/// depth first, children best first (the order changes the work, never the result); a node
/// is dropped
/// when its bound is below the best score so far, or equal to it while it holds no pose of
/// lower index; the search ends when no heap's best node can win. Result: `scored` holds
/// only the leaf poses scored exactly (a partial score volume); poses_scored counts them;
/// cells_scored counts local cells or points multiplied by leaf scores and by bounds alike.
/// An empty result (every pose excluded, no incumbent) has poses_scored == 0.
SearchResult search_branch_and_bound(const Lattice& lattice, const HeadingGrids& grids,
                                     const BoundPyramid& pyramid,
                                     const BranchAndBoundOptions& options = {});

/// search_branch_and_bound run a budget at a time (issue 34: a tracker's re-search spread
/// over its updates, so that none stalls): on one thread (options.threads and budget_ms are
/// ignored), each advance() reads about `cells` local cells or points (bounds and scores,
/// SearchResult::cells_scored's unit) and keeps every open node for the next. Its result is
/// search_branch_and_bound's: the same best pose and score, and with keep_share below 1
/// every pose scoring that share of the best among `scored` (the order of the work differs,
/// never the answer). `lattice`, `grids` and `pyramid` must outlive it.
class ResumableBranchAndBound {
 public:
  /// Checks as search_branch_and_bound does and makes the top nodes (gridloc::Error).
  ResumableBranchAndBound(const Lattice& lattice, const HeadingGrids& grids,
                          const BoundPyramid& pyramid, BranchAndBoundOptions options);
  ~ResumableBranchAndBound();
  ResumableBranchAndBound(const ResumableBranchAndBound&) = delete;
  ResumableBranchAndBound& operator=(const ResumableBranchAndBound&) = delete;

  /// Runs until about `cells` more cells are read or the search is over; true once over.
  bool advance(long long cells);
  bool done() const;
  /// The share of the lattice's poses still in open nodes that could hold the best (1 at the
  /// start, 0 when done): the search's progress.
  double open_share() const;
  /// The result once done() (moved out: call once); gridloc::Error before.
  SearchResult take_result();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The same search, making its own HeadingGrids (with `exclude` only).
SearchResult search_branch_and_bound(const Lattice& lattice, const SearchLevel& finest,
                                     const BoundPyramid& pyramid,
                                     const std::optional<Exclusion>& exclude = std::nullopt);

}  // namespace gridloc
