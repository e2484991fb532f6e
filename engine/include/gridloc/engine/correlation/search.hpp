#pragma once
/// The correlation search of seed 001 §2 as free functions: score S = sum L * G of a local
/// grid placed on a global grid, over a lattice of cells x headings.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <tuple>
#include <vector>

#include "gridloc/engine/correlation/fixed_point_kernel.hpp"
#include "gridloc/grids/grid.hpp"
#include "gridloc/grids/large_pages.hpp"
#include "gridloc/grids/likelihood_field.hpp"
#include "gridloc/sensors/local_grid.hpp"
#include "gridloc/sensors/range_scan.hpp"

namespace gridloc {

/// How an arc cell (local value > 0) scores on a global free cell. `Signed` is seed 001
/// eq. (1) literally: the product is negative. `Neutral` scores it 0: an arc says that *one*
/// of its cells is occupied, not that each is, so an arc cell over free space contradicts
/// nothing. Free-sector and footprint cells (local value < 0) always score signed.
/// Neutral removes a heading bias of the signed rule on oblique walls (see
/// engine/doc/correlation.md).
enum class ArcRule { Neutral, Signed };

/// Which cells a padded grid keeps: int8 alone where they hold the values exactly (4x less
/// memory; a float local grid then reads the floats they stand for, a little slower), or the
/// floats too (a sonar ring's float local grids read them directly).
enum class PaddedCells { Int8WhereExact, FloatsToo };

/// A global grid padded with `pad` unknown (0) cells on every side, so that any local grid
/// of extent <= pad placed on any cell of the map needs no bounds checks. The arc view is the
/// grid that arc cells read: max(G, 0) under ArcRule::Neutral, G itself under Signed.
/// The cells are kept as int8 times int8_scale when every value is a whole multiple of
/// 1 / int8_scale (int8_scale_for: a -1/0/1 evidence grid, a likelihood field), which give
/// the floats back exactly (cell(), float_cells()), and as floats when no scale fits or
/// PaddedCells::FloatsToo asks. The arc view is its own copy only where it differs from the
/// grid (Neutral with negative cells).
struct PaddedGrid {
  /// The padded grid's geometry (map cell (ix, iy) is grid cell (ix + pad, iy + pad)), and its
  /// cells as floats when kept (has_floats()).
  EvidenceGrid grid;
  /// The arc view's floats where it differs from the grid and floats are kept.
  std::vector<float> arc_cells;
  /// The grid and the arc view (where it differs) as int8 times int8_scale, each followed by
  /// kGatherSlack readable bytes; empty when the values are not whole multiples.
  Int8Cells grid8, arc_cells8;
  /// 1 for -1/0/1 evidence grids, kFieldLevels for a likelihood field (see int8_scale_for).
  float int8_scale = 1.0f;
  int pad = 0;
  int width = 0;            ///< the unpadded map's width, cells
  int height = 0;           ///< the unpadded map's height, cells
  bool arc_is_grid = true;  ///< the arc view equals the grid (Signed, or no negative cell)

  bool has_int8() const { return !grid8.empty(); }
  bool has_floats() const { return !grid.cells.empty(); }
  /// int8 copies of a grid whose values are all -1, 0 or 1.
  bool ternary() const { return has_int8() && int8_scale == 1.0f; }
  /// Cells of the padded grid.
  std::size_t cell_count() const { return grid.geometry.size(); }
  /// The arc view's floats: empty without has_floats() (see arc_float_cells).
  const std::vector<float>& arc_view() const { return arc_is_grid ? grid.cells : arc_cells; }
  /// The arc view as int8 (has_int8() only), followed by kGatherSlack bytes.
  const Int8Cells& arc_view8() const { return arc_is_grid ? grid8 : arc_cells8; }
  /// The float an int8 cell stands for, exactly (int8_scale_for).
  float decode(std::int8_t v) const { return static_cast<float>(v) / int8_scale; }
  /// The grid's and the arc view's value at flat index i, whichever way they are kept.
  float cell(std::size_t i) const { return has_floats() ? grid.cells[i] : decode(grid8[i]); }
  float arc_cell(std::size_t i) const {
    return has_floats() ? arc_view()[i] : decode(arc_view8()[i]);
  }
  /// Every cell of the grid and of the arc view as floats (a copy).
  std::vector<float> float_cells() const;
  std::vector<float> arc_float_cells() const;
};

/// The scale s that makes every value v of `cells` a whole number v * s in [-127, 127] that
/// gives v back exactly as float(v * s) / s: 1 (values -1, 0, 1) or kFieldLevels (a
/// likelihood field's levels); 0 when neither does.
float int8_scale_for(const std::vector<float>& cells);

/// The cells times `scale` as int8 (exact for the values int8_scale_for accepts with that
/// scale), followed by kGatherSlack zero bytes.
Int8Cells to_int8_with_slack(const std::vector<float>& cells, float scale = 1.0f);

/// Throws gridloc::Error when the padded grid would have 2^31 cells or more (offsets are
/// int32).
PaddedGrid pad_grid(const EvidenceGrid& grid, int pad, ArcRule rule = ArcRule::Neutral,
                    PaddedCells cells = PaddedCells::Int8WhereExact);

/// Reference score: sum over local cells of value * global cell (arc cells per `rule`), cells
/// outside the grid counting 0; positive cells and negative cells are summed separately, each
/// in the local grid's order, then added. Plain loops, kept as the oracle for the fast path.
double score_reference(const EvidenceGrid& global, const SparseLocalGrid& local, int cx, int cy,
                       ArcRule rule = ArcRule::Neutral);

/// A local grid turned into flat offsets in one padded grid (computed once per heading):
/// the first `arc_count` cells are the positive ones, then the negative ones, each group in
/// the local grid's order.
/// `fixed` holds value * 2^fixed_shift as integers when every value is such an integer of
/// magnitude <= 2^15 for some shift in [0, 24] (the smallest is used): scan grids (end cells
/// +1, free samples -k/n for n a power of 2) are, sonar cones usually are not (fixed empty,
/// fixed_shift -1). Sums of such products with -1/0/1 grids are exact integers, whatever
/// the order, which lets correlate() use integer SIMD lanes.
struct PlacedLocalGrid {
  std::vector<std::int32_t> offset;
  std::vector<float> value;
  std::size_t arc_count = 0;
  std::vector<std::int32_t> fixed;
  int fixed_shift = -1;
  /// Values without a `fixed` form (a sonar cone's 1/n) that are whole multiples of one
  /// power of two, their magnitudes summing below 2^53 of it: every partial sum of their
  /// products with -1/0/1 cells is then a double without rounding, so correlate_scalar's
  /// sums come out the same bit for bit in any order (correlate_scalar_unordered).
  bool order_free = false;
};

/// Fills `fixed` and `fixed_shift` from `value` (see PlacedLocalGrid).
void set_fixed_point(PlacedLocalGrid& local);

/// 2^-shift for a fixed_shift in [0, 24], exactly: multiplying an integer sum by it is
/// std::ldexp(sum, -shift) bit for bit (no rounding short of the subnormals), without the
/// library call a bound would otherwise make.
inline double fixed_point_unit(int shift) {
  static constexpr auto kUnits = [] {
    std::array<double, 25> units{};
    double unit = 1.0;
    for (double& u : units) {
      u = unit;
      unit *= 0.5;
    }
    return units;
  }();
  return kUnits[static_cast<std::size_t>(shift)];
}

PlacedLocalGrid place(const SparseLocalGrid& local, const PaddedGrid& global);

/// place(rasterize_points(points, theta, resolution), global) without the intermediate grid:
/// the same cells and values, bit for bit (tested), in another order: each group (arc cells,
/// then free cells) in the order of the points that first reach a cell. Every strategy
/// places rigid points with it (place_heading), so all sum in one order. `points` must not
/// reach beyond the padding.
PlacedLocalGrid place_points(const ScanPoints& points, double theta, const PaddedGrid& global);

/// The correlation of a placed local grid with two grids seen from one origin: arc cells
/// read `arc`, the others `all`; positives and negatives are summed apart, each in the local
/// grid's order, then added. score() and the branch-and-bound bounds both sum this way, which
/// is what makes a bound >= the score bit for bit. `T` is float, or int8 for copies of
/// grids whose values are all -1, 0 or 1 (the same values, so the same sums, from 4x less
/// memory).
template <typename T>
double correlate_scalar(const T* arc, const T* all, const PlacedLocalGrid& local) {
  double positive = 0.0, negative = 0.0;
  const std::size_t n = local.value.size();
  for (std::size_t k = 0; k < local.arc_count; ++k) {
    positive += static_cast<double>(local.value[k] * static_cast<float>(arc[local.offset[k]]));
  }
  for (std::size_t k = local.arc_count; k < n; ++k) {
    negative += static_cast<double>(local.value[k] * static_cast<float>(all[local.offset[k]]));
  }
  return positive + negative;
}

/// correlate_scalar's result for a local grid whose sums are order_free on -1/0/1 cells,
/// from four running sums a group instead of one (no chain of dependent additions): every
/// partial sum is exact, so the result is the same bit for bit.
template <typename T>
double correlate_scalar_unordered(const T* arc, const T* all, const PlacedLocalGrid& local) {
  auto group = [&local](const T* grid, std::size_t begin, std::size_t end) {
    double sums[4] = {0.0, 0.0, 0.0, 0.0};
    std::size_t k = begin;
    for (; k + 4 <= end; k += 4) {
      for (std::size_t lane = 0; lane < 4; ++lane) {
        sums[lane] += static_cast<double>(local.value[k + lane] *
                                          static_cast<float>(grid[local.offset[k + lane]]));
      }
    }
    for (; k < end; ++k) {
      sums[0] += static_cast<double>(local.value[k] * static_cast<float>(grid[local.offset[k]]));
    }
    return (sums[0] + sums[1]) + (sums[2] + sums[3]);
  };
  return group(arc, 0, local.arc_count) + group(all, local.arc_count, local.value.size());
}

/// correlate_scalar over int8 cells standing for v / scale: each term reads the float the
/// cell stands for (PaddedGrid::decode), so the sums are those of the float grid, bit for bit.
inline double correlate_scalar_decoded(const std::int8_t* arc, const std::int8_t* all,
                                       const PlacedLocalGrid& local, float scale) {
  double positive = 0.0, negative = 0.0;
  const std::size_t n = local.value.size();
  for (std::size_t k = 0; k < local.arc_count; ++k) {
    positive +=
        static_cast<double>(local.value[k] * (static_cast<float>(arc[local.offset[k]]) / scale));
  }
  for (std::size_t k = local.arc_count; k < n; ++k) {
    negative +=
        static_cast<double>(local.value[k] * (static_cast<float>(all[local.offset[k]]) / scale));
  }
  return positive + negative;
}

template <typename T>
double correlate(const T* arc, const T* all, const PlacedLocalGrid& local) {
  return correlate_scalar(arc, all, local);
}

/// On -1/0/1 grids (read with kGatherSlack bytes of slack) and a fixed-point local grid,
/// the same sums from integer lanes (correlate_fixed: SIMD where the CPU has it), which
/// are exact and so equal to correlate_scalar's bit for bit; correlate_scalar otherwise.
inline double correlate(const std::int8_t* arc, const std::int8_t* all,
                        const PlacedLocalGrid& local) {
  if (local.fixed_shift < 0) {
    return local.order_free ? correlate_scalar_unordered(arc, all, local)
                            : correlate_scalar(arc, all, local);
  }
  return static_cast<double>(correlate_fixed(arc, all, local.offset.data(), local.fixed.data(),
                                             local.arc_count, local.offset.size())) *
         fixed_point_unit(local.fixed_shift);
}

/// Fast score of `local` with the robot on map cell (cx, cy); the cell must lie in the map
/// and the local grid's extent must not exceed the padding. Equal to score_reference exactly
/// when both sum in the same order (place() keeps the local grid's order), and on the
/// fixed-point path whatever the order. On a likelihood field's int8 copies the exact
/// integer sum is divided by int8_scale (one rounding, monotone, as the bounds do).
inline double score(const PaddedGrid& global, const PlacedLocalGrid& local, int cx, int cy) {
  const std::ptrdiff_t origin =
      static_cast<std::ptrdiff_t>(cy + global.pad) * global.grid.width() + (cx + global.pad);
  if (global.has_int8() && local.fixed_shift >= 0) {
    return correlate(global.arc_view8().data() + origin, global.grid8.data() + origin, local) /
           static_cast<double>(global.int8_scale);
  }
  if (global.has_floats()) {
    return correlate(global.arc_view().data() + origin, global.grid.cells.data() + origin, local);
  }
  const std::int8_t* arc = global.arc_view8().data() + origin;
  const std::int8_t* all = global.grid8.data() + origin;
  // A float local grid reads the floats the int8 cells stand for: cast (scale 1) or decoded.
  if (global.int8_scale == 1.0f) return correlate(arc, all, local);
  return correlate_scalar_decoded(arc, all, local, global.int8_scale);
}

/// A candidate of the search lattice: map cell and heading index.
struct LatticePose {
  int ix = 0;
  int iy = 0;
  int it = 0;
  double score = 0.0;
};

/// The order every search ranks poses in: higher score first, ties to the lower index in
/// (it, iy, ix) order.
inline bool better(const LatticePose& a, const LatticePose& b) {
  if (a.score != b.score) return a.score > b.score;
  return std::tie(a.it, a.iy, a.ix) < std::tie(b.it, b.iy, b.ix);
}

/// The translation x heading lattice of one search, in finest-level cells.
struct Lattice {
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;  ///< inclusive cell ranges, clipped to the map
  int headings = 1;                    ///< heading index it in [0, headings)
  double theta0 = 0.0;                 ///< heading of index 0, grid frame (rad)
  double step_theta = 0.0;             ///< rad
  double theta(double it) const { return theta0 + it * step_theta; }
};

/// One resolution level of the search: padded global grid and a maker of local grids for a
/// heading (grid frame, rad) and a robot centre offset from its cell's centre (m), built
/// directly at this level's resolution (seed 001 §2).
struct SearchLevel {
  const PaddedGrid* global = nullptr;
  std::function<SparseLocalGrid(double theta, const Eigen::Vector2d& centre)> make_local;
  int threads = 1;  ///< OpenMP threads scoring this level, one heading per task (thread-safe
                    ///< make_local required); results do not depend on it
  /// Rigid points the local grids are made of, when they are: make_local(theta, 0) must then
  /// equal rasterize_points(*points, theta, the grid's resolution). Lets branch and bound
  /// bound whole heading intervals. nullptr: no such points (sonar, ray scans).
  const ScanPoints* points = nullptr;
};

struct SearchResult {
  LatticePose best;
  /// False when no pose was a candidate (branch and bound: all excluded, or none reached
  /// BranchAndBoundOptions::min_score and there was no incumbent); `best` is then no pose.
  bool found = true;
  bool proven_optimal = true;       ///< false when a budget stopped a search early
  double upper_bound = 0.0;         ///< no pose scores more (= best.score when proven optimal)
  std::vector<LatticePose> scored;  ///< every finest-level pose scored, in scoring order
  long long poses_scored = 0;
  long long cells_scored = 0;
};

/// The placed local grid of heading theta on `level`: place_points for rigid points,
/// place(make_local(theta, 0)) otherwise. Every strategy places headings with it.
PlacedLocalGrid place_heading(const SearchLevel& level, double theta);

/// Exhaustive search over the whole lattice on the finest level. Ties go to the lowest index
/// in (it, iy, ix) order.
SearchResult search_exhaustive(const Lattice& lattice, const SearchLevel& finest);

/// Multiresolution search (seed 001 §2): levels[l] has cells 2^l times the finest. The
/// coarsest level scores its whole lattice; every finer level scores the children (+-1 cell
/// margin, +-1 heading) of the `keep` best poses of the level above. Ties as exhaustive.
SearchResult search_multires(const Lattice& lattice, const std::vector<SearchLevel>& levels,
                             int keep);

/// The refined pose: lattice coordinates with fractions (ix + dx, iy + dy, it + dt).
struct RefinedPose {
  double ix = 0.0;
  double iy = 0.0;
  double it = 0.0;
  double score = 0.0;  ///< score at the best sub-lattice pose (before the parabola)
};

/// The middle of the run of lattice headings at the winner's cell that score exactly as much
/// as the winner (at most `max_steps` each way): with integer scores (hits) a scan often ties
/// over several headings, and the search's lowest-index winner sits at the run's start, where
/// refinement's parabola cannot reach the middle. The score is unchanged; the winner's own
/// pose when nothing ties; the run does not wrap around a full turn of headings. Estimate::pose
/// (refined from it) may then lie a few heading steps from Estimate::lattice_pose, which
/// stays the search's winner. `lattice_grid` as for refine().
LatticePose centre_of_heading_ties(
    const LatticePose& best, const Lattice& lattice, const SearchLevel& finest, int max_steps = 8,
    const std::function<const PlacedLocalGrid*(int it)>& lattice_grid = {});

/// Sub-cell refinement of the lattice winner, on the finest level: the winner's cell and its
/// 8 neighbours are scored at headings within +-1 lattice step in steps of 1/`subdivisions`;
/// the best of these is refined by a parabola through its neighbours along x, y and heading
/// (offset clamped to half a step; an axis whose neighbour leaves the map or scores higher
/// stays put). The model is rebuilt for every sub-step heading, never rotated. Returns
/// lattice units.
/// `lattice_grid`, when given, returns the already placed local grid of lattice heading it
/// (or nullptr): refinement then reuses it instead of building it again (the same grid).
RefinedPose refine(const LatticePose& best, const Lattice& lattice, const SearchLevel& finest,
                   int subdivisions = 4,
                   const std::function<const PlacedLocalGrid*(int it)>& lattice_grid = {});

}  // namespace gridloc
