#include "gridloc/engine/correlation_search.hpp"

#include <algorithm>
#include <optional>
#include <tuple>

namespace gridloc {
namespace {

/// Lattice order used for ties: (it, iy, ix) ascending.
bool index_less(const LatticePose& a, const LatticePose& b) {
  return std::tie(a.it, a.iy, a.ix) < std::tie(b.it, b.iy, b.ix);
}
/// Better = higher score, then lower index.
bool better(const LatticePose& a, const LatticePose& b) {
  if (a.score != b.score) return a.score > b.score;
  return index_less(a, b);
}

/// Scores `candidates` (sorted by index) on one level, building each heading's grid once.
void score_all(std::vector<LatticePose>& candidates, const SearchLevel& level,
               SearchResult& result) {
  std::optional<int> current;
  PlacedLocalGrid placed;
  for (auto& c : candidates) {
    if (current != c.it) {
      placed = place(level.make_local(c.it), *level.global);
      current = c.it;
    }
    c.score = score(*level.global, placed, c.ix, c.iy);
    result.cells_scored += static_cast<long long>(placed.value.size());
  }
  result.poses_scored += static_cast<long long>(candidates.size());
}

}  // namespace

PaddedGrid pad_grid(const EvidenceGrid& grid, int pad) {
  PaddedGrid p;
  p.pad = pad;
  p.width = grid.width();
  p.height = grid.height();
  GridGeometry g = grid.geometry;
  g.width += 2 * pad;
  g.height += 2 * pad;
  g.origin -= Eigen::Vector2d(pad * g.resolution, pad * g.resolution);  // ignoring yaw: unused
  p.grid = EvidenceGrid(g, 0.0f);
  for (int iy = 0; iy < grid.height(); ++iy) {
    std::copy(grid.row(iy), grid.row(iy) + grid.width(), p.grid.row(iy + pad) + pad);
  }
  return p;
}

double score_reference(const EvidenceGrid& global, const SparseLocalGrid& local, int cx, int cy) {
  double s = 0.0;
  for (std::size_t k = 0; k < local.size(); ++k) {
    const int x = cx + local.dx[k], y = cy + local.dy[k];
    if (global.geometry.contains(x, y)) {
      s += static_cast<double>(local.value[k] * global.at(x, y));
    }
  }
  return s;
}

PlacedLocalGrid place(const SparseLocalGrid& local, const PaddedGrid& global) {
  PlacedLocalGrid p;
  p.offset.resize(local.size());
  p.value = local.value;
  const std::ptrdiff_t w = global.grid.width();
  for (std::size_t k = 0; k < local.size(); ++k) p.offset[k] = local.dy[k] * w + local.dx[k];
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
  score_all(candidates, finest, result);
  result.best = candidates.front();
  for (const auto& c : candidates) {
    if (better(c, result.best)) result.best = c;
  }
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
    score_all(candidates, levels[l], result);
    const auto k = std::min<std::size_t>(static_cast<std::size_t>(std::max(1, keep)), candidates.size());
    kept = candidates;
    std::partial_sort(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(k), kept.end(), better);
    kept.resize(k);
    if (l == 0) {
      result.best = kept.front();
      result.scored = std::move(candidates);
    }
  }
  return result;
}

}  // namespace gridloc
