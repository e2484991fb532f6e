#include "gridloc/engine/correlation/search.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <tuple>

namespace gridloc {
namespace {

/// Lattice order used for ties: (it, iy, ix) ascending.
bool index_less(const LatticePose& a, const LatticePose& b) {
  return std::tie(a.it, a.iy, a.ix) < std::tie(b.it, b.iy, b.ix);
}

/// Scores `candidates` (sorted by index) on one level, building each heading's grid once.
void score_all(std::vector<LatticePose>& candidates, const Lattice& lattice,
               const SearchLevel& level, SearchResult& result) {
  // Candidates are sorted by heading: one group per heading, each built and scored alone,
  // so any number of threads computes the same scores.
  std::vector<std::size_t> starts;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    if (k == 0 || candidates[k].it != candidates[k - 1].it) starts.push_back(k);
  }
  starts.push_back(candidates.size());
  const auto groups = static_cast<std::ptrdiff_t>(starts.size()) - 1;
  std::vector<long long> cells(static_cast<std::size_t>(std::max<std::ptrdiff_t>(groups, 0)), 0);
#pragma omp parallel for schedule(dynamic) num_threads(level.threads) if (level.threads > 1)
  for (std::ptrdiff_t g = 0; g < groups; ++g) {
    const auto begin = starts[static_cast<std::size_t>(g)],
               end = starts[static_cast<std::size_t>(g) + 1];
    const PlacedLocalGrid placed = place_heading(level, lattice.theta(candidates[begin].it));
    for (std::size_t k = begin; k < end; ++k) {
      candidates[k].score = score(*level.global, placed, candidates[k].ix, candidates[k].iy);
    }
    cells[static_cast<std::size_t>(g)] =
        static_cast<long long>(placed.value.size()) * static_cast<long long>(end - begin);
  }
  for (long long c : cells) result.cells_scored += c;
  result.poses_scored += static_cast<long long>(candidates.size());
}

/// Fractional bits a float needs to be whole (0 for integers and 0); more than any limit
/// for NaN and infinities.
int fraction_bits(float v) {
  if (v == 0.0f) return 0;
  if (!std::isfinite(v)) return 1000;
  int exponent = 0;
  const float mantissa = std::frexp(v, &exponent);  // |mantissa| in [0.5, 1)
  // v = m * 2^(exponent - 24) with m the 24-bit integer mantissa.
  const auto m = static_cast<std::uint32_t>(std::abs(std::ldexp(mantissa, 24)));
  return std::max(0, 24 - exponent - std::countr_zero(m));
}

/// PlacedLocalGrid::order_free for values needing `shift` fractional bits: their
/// magnitudes sum below 2^53 after the shift (checked against 2^52: the double sum's own
/// rounding, below n * 2^-53 of it, stays far inside the factor 2).
bool sums_order_free(const std::vector<float>& values, int shift) {
  constexpr int kMaxShift = 1000;  // fraction_bits' answer for NaN and infinities
  if (shift >= kMaxShift) return false;
  double magnitude = 0.0;
  for (float v : values) magnitude += std::abs(static_cast<double>(v));
  return std::ldexp(magnitude, shift) < 0x1p52;
}

}  // namespace

void set_fixed_point(PlacedLocalGrid& local) {
  local.fixed.clear();
  local.fixed_shift = -1;
  local.order_free = false;
  // The fewest fractional bits that make every value whole (then multiplying by 2^shift is
  // exact), and the magnitude limit 2^15.
  constexpr int kMaxShift = 24;
  constexpr double kLimit = 32768.0;
  int shift = 0;
  float largest = 0.0f;
  float previous = 0.0f;  // values come in runs of equal ones: one look per run
  for (float v : local.value) {
    if (v == previous) continue;
    previous = v;
    shift = std::max(shift, fraction_bits(v));
    largest = std::max(largest, std::abs(v));
  }
  if (shift > kMaxShift || std::ldexp(static_cast<double>(largest), shift) > kLimit) {
    local.order_free = sums_order_free(local.value, shift);
    return;
  }
  local.fixed_shift = shift;
  // In float: a power of 2 times a value <= 2^15 is exact, and the loop vectorizes.
  const float scale = std::ldexp(1.0f, shift);
  local.fixed.resize(local.value.size());
  std::transform(local.value.begin(), local.value.end(), local.fixed.begin(),
                 [&](float v) { return static_cast<std::int32_t>(v * scale); });
}

double score_reference(const EvidenceGrid& global, const SparseLocalGrid& local, int cx, int cy,
                       ArcRule rule) {
  double positive = 0.0, negative = 0.0;
  for (std::size_t k = 0; k < local.size(); ++k) {
    const int x = cx + local.dx[k], y = cy + local.dy[k];
    if (!global.geometry.contains(x, y)) continue;
    const float v = local.value[k];
    float g = global.at(x, y);
    if (v > 0.0f) {
      if (rule == ArcRule::Neutral) g = std::max(g, 0.0f);
      positive += static_cast<double>(v * g);
    } else {
      negative += static_cast<double>(v * g);
    }
  }
  return positive + negative;
}

PlacedLocalGrid place(const SparseLocalGrid& local, const PaddedGrid& global) {
  PlacedLocalGrid p;
  p.offset.reserve(local.size());
  p.value.reserve(local.size());
  const int w = global.grid.width();  // |offset| < cells < 2^31 (pad_grid)
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t k = 0; k < local.size(); ++k) {
      if ((local.value[k] > 0.0f) != (pass == 0)) continue;
      p.offset.push_back(local.dy[k] * w + local.dx[k]);
      p.value.push_back(local.value[k]);
    }
    if (pass == 0) p.arc_count = p.value.size();
  }
  set_fixed_point(p);
  return p;
}

namespace {

// An AVX2 clone and the default, picked once by an ifunc resolver; a sanitizer build
// (GRIDLOC_SANITIZE, which defines GRIDLOC_NO_CLONES) keeps the default only: the resolver
// runs before ThreadSanitizer's runtime is ready.
#if defined(GRIDLOC_NO_CLONES)
#define GRIDLOC_AVX2_CLONES
#else
#define GRIDLOC_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#endif

/// point_cell() of n points (centre 0) in one loop the compiler vectorizes: the same
/// operations in the same order, so the same cells bit for bit (no FMA in either clone).
GRIDLOC_AVX2_CLONES void point_cells(const double* x, const double* y, std::size_t n, double c,
                                     double s, double inv, int* xs, int* ys) {
  for (std::size_t k = 0; k < n; ++k) {
    xs[k] = floor_to_int((c * x[k] - s * y[k]) * inv + 0.5);
    ys[k] = floor_to_int((s * x[k] + c * y[k]) * inv + 0.5);
  }
}

/// A small open-addressing table from cell offsets to entries (kept in L1/L2, unlike a table
/// over the grid), one per thread and reused: a slot whose epoch is this call's holds a cell
/// offset and its entry. No clearing: each call has a new epoch.
class CellTable {
 public:
  struct Slot {
    std::uint32_t epoch;
    std::int32_t offset;
    std::uint32_t entry;
  };

  /// The thread's table, sized for `points` points, every slot empty for this call.
  explicit CellTable(std::size_t points) {
    thread_local std::vector<Slot> table;
    thread_local std::uint32_t epoch = 0;
    std::size_t size = 64;
    while (size < 4 * points) size *= 2;
    if (table.size() < size || ++epoch == 0) {
      table.assign(std::max(size, table.size()), Slot{0, 0, 0});
      epoch = 1;
    }
    now_ = epoch;
    slots_ = table.data();
    mask_ = size - 1;
    shift_ = 64 - std::countr_zero(size);
  }

  /// The slot of cell `offset`: its entry's, or the empty one where it goes (its epoch stays
  /// old until enter() makes it an entry).
  Slot& slot_of(std::int32_t offset) {
    // Fibonacci hashing: the top bits of the product spread nearby offsets apart.
    std::size_t h = static_cast<std::size_t>(
        (static_cast<std::uint64_t>(static_cast<std::uint32_t>(offset)) * 0x9E3779B97F4A7C15ull) >>
        shift_);
    while (slots_[h].epoch == now_ && slots_[h].offset != offset) h = (h + 1) & mask_;
    Slot& slot = slots_[h];
    if (slot.epoch != now_) slot.offset = offset;
    return slot;
  }
  /// The slot holds an entry of this call.
  bool holds(const Slot& slot) const { return slot.epoch == now_; }
  /// Makes the slot this call's entry `entry`.
  void enter(Slot& slot, std::uint32_t entry) const {
    slot.epoch = now_;
    slot.entry = entry;
  }

 private:
  Slot* slots_ = nullptr;
  std::size_t mask_ = 0;
  int shift_ = 0;
  std::uint32_t now_ = 0;
};

/// Pass 2 of place_points: merges the points' cells (xs, ys from the robot's cell, in a grid
/// `width` cells wide) into entries of `placed`, sized for every point. A cell holding a beam
/// end is +1 (an arc cell, first); any other the float sum of its free samples in point
/// order, as the canvas adds them. Sets arc_count; returns the number of entries.
std::uint32_t merge_cells(const ScanPoints& points, const int* xs, const int* ys, int width,
                          PlacedLocalGrid& placed) {
  CellTable table(points.size());
  std::int32_t* const offset = placed.offset.data();
  float* const value = placed.value.data();
  std::uint32_t n = 0;  // entries so far
  for (std::size_t k = 0; k < points.hit_count; ++k) {
    CellTable::Slot& slot = table.slot_of(ys[k] * width + xs[k]);
    if (table.holds(slot)) continue;
    table.enter(slot, n);
    offset[n] = slot.offset;
    value[n++] = 1.0f;
  }
  placed.arc_count = n;
  for (std::size_t k = points.hit_count; k < points.size(); ++k) {
    CellTable::Slot& slot = table.slot_of(ys[k] * width + xs[k]);
    if (!table.holds(slot)) {
      table.enter(slot, n);
      offset[n] = slot.offset;
      value[n++] = points.weight[k];
    } else if (slot.entry >= placed.arc_count) {
      value[slot.entry] += points.weight[k];
    }
  }
  return n;
}

/// Keeps the first `entries` entries of `placed` but the free ones that sum to 0 (no cell),
/// in order.
void drop_empty_cells(PlacedLocalGrid& placed, std::size_t entries) {
  std::size_t kept = placed.arc_count;
  for (std::size_t e = placed.arc_count; e < entries; ++e) {
    if (placed.value[e] == 0.0f) continue;
    placed.offset[kept] = placed.offset[e];
    placed.value[kept++] = placed.value[e];
  }
  placed.offset.resize(kept);
  placed.value.resize(kept);
}

}  // namespace

PlacedLocalGrid place_points(const ScanPoints& points, double theta, const PaddedGrid& global) {
  const double inv = 1.0 / global.grid.geometry.resolution;
  const double c = std::cos(theta), s = std::sin(theta);
  // Pass 1, independent per point: the cells.
  thread_local std::vector<int> xs, ys;
  xs.resize(points.size());
  ys.resize(points.size());
  point_cells(points.x.data(), points.y.data(), points.size(), c, s, inv, xs.data(), ys.data());
  // Pass 2: merge points per cell.
  PlacedLocalGrid placed;
  placed.offset.resize(points.size());
  placed.value.resize(points.size());
  const std::uint32_t entries =
      merge_cells(points, xs.data(), ys.data(), global.grid.width(), placed);
  drop_empty_cells(placed, entries);
  set_fixed_point(placed);
  return placed;
}

PlacedLocalGrid place_heading(const SearchLevel& level, double theta) {
  if (level.points != nullptr) return place_points(*level.points, theta, *level.global);
  return place(level.make_local(theta, Eigen::Vector2d::Zero()), *level.global);
}

SearchResult search_exhaustive(const Lattice& lattice, const SearchLevel& finest) {
  SearchResult result;
  std::vector<LatticePose> candidates;
  candidates.reserve(static_cast<std::size_t>(lattice.headings) * (lattice.x1 - lattice.x0 + 1) *
                     (lattice.y1 - lattice.y0 + 1));
  for (int it = 0; it < lattice.headings; ++it) {
    for (int iy = lattice.y0; iy <= lattice.y1; ++iy) {
      for (int ix = lattice.x0; ix <= lattice.x1; ++ix) candidates.push_back({ix, iy, it, 0.0});
    }
  }
  score_all(candidates, lattice, finest, result);
  result.best = candidates.front();
  for (const auto& c : candidates) {
    if (better(c, result.best)) result.best = c;
  }
  result.upper_bound = result.best.score;  // every pose scored: proven
  result.scored = std::move(candidates);
  return result;
}

SearchResult search_multires(const Lattice& lattice, const std::vector<SearchLevel>& levels,
                             int keep) {
  SearchResult result;
  const int top = static_cast<int>(levels.size()) - 1;
  std::vector<LatticePose> kept;
  for (int l = top; l >= 0; --l) {
    // The lattice at level l: finest cells divided by 2^l (cells are >= 0 after clipping).
    const int x0 = lattice.x0 >> l, x1 = lattice.x1 >> l;
    const int y0 = lattice.y0 >> l, y1 = lattice.y1 >> l;
    const int nx = x1 - x0 + 1, ny = y1 - y0 + 1;
    std::vector<LatticePose> candidates;
    if (l == top) {
      for (int it = 0; it < lattice.headings; ++it) {
        for (int iy = y0; iy <= y1; ++iy) {
          for (int ix = x0; ix <= x1; ++ix) candidates.push_back({ix, iy, it, 0.0});
        }
      }
    } else {
      std::vector<char> seen(static_cast<std::size_t>(nx) * ny * lattice.headings, 0);
      for (const auto& p : kept) {
        for (int it = std::max(0, p.it - 1); it <= std::min(lattice.headings - 1, p.it + 1); ++it) {
          for (int iy = std::max(y0, 2 * p.iy - 1); iy <= std::min(y1, 2 * p.iy + 2); ++iy) {
            for (int ix = std::max(x0, 2 * p.ix - 1); ix <= std::min(x1, 2 * p.ix + 2); ++ix) {
              char& s = seen[(static_cast<std::size_t>(it) * ny + (iy - y0)) * nx + (ix - x0)];
              if (!s) {
                s = 1;
                candidates.push_back({ix, iy, it, 0.0});
              }
            }
          }
        }
      }
      std::sort(candidates.begin(), candidates.end(), index_less);
    }
    score_all(candidates, lattice, levels[l], result);
    const auto k =
        std::min<std::size_t>(static_cast<std::size_t>(std::max(1, keep)), candidates.size());
    kept = candidates;
    std::partial_sort(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(k), kept.end(),
                      better);
    kept.resize(k);
    if (l == 0) {
      result.best = kept.front();
      result.scored = std::move(candidates);
    }
  }
  return result;
}

namespace {

/// Vertex of the parabola through (-1, a), (0, b), (1, c), when b is a strict peak.
double parabola_vertex(double a, double b, double c) {
  const double curvature = a - 2.0 * b + c;
  if (!(curvature < 0.0) || b < a || b < c) return 0.0;
  return std::clamp(0.5 * (a - c) / curvature, -0.5, 0.5);
}

}  // namespace

LatticePose centre_of_heading_ties(
    const LatticePose& best, const Lattice& lattice, const SearchLevel& finest, int max_steps,
    const std::function<const PlacedLocalGrid*(int it)>& lattice_grid) {
  const auto ties = [&](int it) {
    if (it < 0 || it >= lattice.headings) return false;
    const PlacedLocalGrid* built = lattice_grid ? lattice_grid(it) : nullptr;
    const double s =
        built ? score(*finest.global, *built, best.ix, best.iy)
              : score(*finest.global, place_heading(finest, lattice.theta(it)), best.ix, best.iy);
    return s == best.score;
  };
  int low = best.it, high = best.it;
  while (best.it - low < max_steps && ties(low - 1)) --low;
  while (high - best.it < max_steps && ties(high + 1)) ++high;
  LatticePose centre = best;
  centre.it = low + (high - low) / 2;
  return centre;
}

RefinedPose refine(const LatticePose& best, const Lattice& lattice, const SearchLevel& finest,
                   int subdivisions,
                   const std::function<const PlacedLocalGrid*(int it)>& lattice_grid) {
  const PaddedGrid& g = *finest.global;
  const int sub = std::max(1, subdivisions);
  auto heading = [&](int j) { return lattice.theta(best.it + static_cast<double>(j) / sub); };
  auto inside = [&](int x, int y) { return x >= 0 && y >= 0 && x < g.width && y < g.height; };

  // Heading: 3 x 3 cells x (2 sub + 1) headings.
  std::vector<PlacedLocalGrid> placed;
  for (int j = -sub; j <= sub; ++j) {
    const int it = best.it + j / sub;  // the lattice heading, when j is a whole step
    const PlacedLocalGrid* built = j % sub == 0 && it >= 0 && it < lattice.headings && lattice_grid
                                       ? lattice_grid(it)
                                       : nullptr;
    placed.push_back(built ? *built : place_heading(finest, heading(j)));
  }
  auto placed_at = [&](int j) -> const PlacedLocalGrid& {
    const int index = j + sub;
    return placed[static_cast<std::size_t>(index)];
  };
  int bj = 0, bx = best.ix, by = best.iy;
  double top = best.score;
  for (int j = -sub; j <= sub; ++j) {
    for (int y = best.iy - 1; y <= best.iy + 1; ++y) {
      for (int x = best.ix - 1; x <= best.ix + 1; ++x) {
        if (!inside(x, y)) continue;
        const double s = score(g, placed_at(j), x, y);
        if (s > top) top = s, bj = j, bx = x, by = y;
      }
    }
  }
  double dt = 0.0;
  if (bj > -sub && bj < sub) {
    dt = parabola_vertex(score(g, placed_at(bj - 1), bx, by), top,
                         score(g, placed_at(bj + 1), bx, by));
  }

  // Position: a parabola through the chosen cell's neighbours along x and along y.
  const PlacedLocalGrid& at_heading = placed_at(bj);
  auto axis_offset = [&](int x0, int y0, int x1, int y1) {
    if (!inside(x0, y0) || !inside(x1, y1)) return 0.0;
    return parabola_vertex(score(g, at_heading, x0, y0), top, score(g, at_heading, x1, y1));
  };
  RefinedPose r;
  r.score = top;
  r.ix = bx + axis_offset(bx - 1, by, bx + 1, by);
  r.iy = by + axis_offset(bx, by - 1, bx, by + 1);
  r.it = best.it + (bj + dt) / sub;
  return r;
}

}  // namespace gridloc
