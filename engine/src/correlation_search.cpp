#include "gridloc/engine/correlation_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "gridloc/grids/radix_sort.hpp"

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
    const PlacedLocalGrid placed =
        place(level.make_local(lattice.theta(candidates[begin].it), Eigen::Vector2d::Zero()),
              *level.global);
    for (std::size_t k = begin; k < end; ++k) {
      candidates[k].score = score(*level.global, placed, candidates[k].ix, candidates[k].iy);
    }
    cells[static_cast<std::size_t>(g)] =
        static_cast<long long>(placed.value.size()) * static_cast<long long>(end - begin);
  }
  for (long long c : cells) result.cells_scored += c;
  result.poses_scored += static_cast<long long>(candidates.size());
}

}  // namespace

PaddedGrid pad_grid(const EvidenceGrid& grid, int pad, ArcRule rule) {
  PaddedGrid p;
  p.pad = pad;
  p.width = grid.width();
  p.height = grid.height();
  GridGeometry g = grid.geometry;
  g.width += 2 * pad;
  g.height += 2 * pad;
  p.grid = EvidenceGrid(g, 0.0f);
  for (int iy = 0; iy < grid.height(); ++iy) {
    std::copy(grid.row(iy), grid.row(iy) + grid.width(), p.grid.row(iy + pad) + pad);
  }
  p.arc_view = p.grid.cells;
  if (rule == ArcRule::Neutral) {
    for (float& v : p.arc_view) v = std::max(v, 0.0f);
  }
  return p;
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
  const std::ptrdiff_t w = global.grid.width();
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t k = 0; k < local.size(); ++k) {
      if ((local.value[k] > 0.0f) != (pass == 0)) continue;
      p.offset.push_back(local.dy[k] * w + local.dx[k]);
      p.value.push_back(local.value[k]);
    }
    if (pass == 0) p.arc_count = p.value.size();
  }
  return p;
}

PlacedLocalGrid place_points(const ScanPoints& points, double theta, const PaddedGrid& global) {
  const double inv = 1.0 / global.grid.geometry.resolution;
  const double c = std::cos(theta), s = std::sin(theta);
  const std::ptrdiff_t w = global.grid.width();
  auto offset_of = [&](std::size_t k) {
    const Eigen::Vector2i cell = point_cell(points, k, c, s, inv);
    return static_cast<std::ptrdiff_t>(cell.y()) * w + cell.x();
  };
  // Offsets sort as (dy, dx) do (|dx| <= pad < w / 2): place()'s order. A cell holding a beam
  // end is +1; any other cell the float sum of its free samples in point order, as the
  // canvas adds them.
  // Keys: the offset made non-negative in the high 32 bits, the point index below, so that
  // a stable sort on the high bits keeps point order within a cell.
  const std::ptrdiff_t bias = static_cast<std::ptrdiff_t>(global.pad) * w + global.pad;
  const int bits = bits_below(static_cast<std::uint64_t>(global.grid.cells.size()));
  thread_local std::vector<std::uint64_t> keys, scratch;
  auto sorted_keys = [&](std::size_t k0, std::size_t k1) -> std::vector<std::uint64_t>& {
    keys.clear();
    for (std::size_t k = k0; k < k1; ++k) {
      keys.push_back(static_cast<std::uint64_t>(offset_of(k) + bias) << 32 | k);
    }
    radix_sort(keys, scratch, 32, bits);
    return keys;
  };
  auto offset_in = [&](std::uint64_t key) { return static_cast<std::ptrdiff_t>(key >> 32) - bias; };
  PlacedLocalGrid p;
  p.offset.reserve(points.size());
  p.value.reserve(points.size());
  for (std::uint64_t key : sorted_keys(0, points.hit_count)) {
    const std::ptrdiff_t o = offset_in(key);
    if (p.offset.empty() || p.offset.back() != o) p.offset.push_back(o);
  }
  p.arc_count = p.offset.size();
  p.value.assign(p.arc_count, 1.0f);
  const auto& frees = sorted_keys(points.hit_count, points.size());
  std::size_t h = 0;  // walks the hit offsets alongside (both sorted)
  for (std::size_t i = 0; i < frees.size();) {
    const std::ptrdiff_t o = offset_in(frees[i]);
    float sum = 0.0f;
    for (; i < frees.size() && offset_in(frees[i]) == o; ++i) {
      sum += points.weight[static_cast<std::size_t>(frees[i] & 0xffffffffu)];
    }
    while (h < p.arc_count && p.offset[h] < o) ++h;
    if (sum != 0.0f && !(h < p.arc_count && p.offset[h] == o)) {
      p.offset.push_back(o);
      p.value.push_back(sum);
    }
  }
  return p;
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

RefinedPose refine(const LatticePose& best, const Lattice& lattice, const SearchLevel& finest,
                   int subdivisions,
                   const std::function<const PlacedLocalGrid*(int it)>& lattice_grid) {
  const PaddedGrid& g = *finest.global;
  const int sub = std::max(1, subdivisions);
  const Eigen::Vector2d zero = Eigen::Vector2d::Zero();
  auto heading = [&](int j) { return lattice.theta(best.it + static_cast<double>(j) / sub); };
  auto inside = [&](int x, int y) { return x >= 0 && y >= 0 && x < g.width && y < g.height; };

  // Heading: 3 x 3 cells x (2 sub + 1) headings.
  std::vector<PlacedLocalGrid> placed;
  for (int j = -sub; j <= sub; ++j) {
    const int it = best.it + j / sub;  // the lattice heading, when j is a whole step
    const PlacedLocalGrid* built = j % sub == 0 && it >= 0 && it < lattice.headings && lattice_grid
                                       ? lattice_grid(it)
                                       : nullptr;
    placed.push_back(built ? *built : place(finest.make_local(heading(j), zero), g));
  }
  auto placed_at = [&](int j) -> const PlacedLocalGrid& {
    return placed[static_cast<std::size_t>(j + sub)];
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
