#include "gridloc/grids/evidence.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "gridloc/grids/error.hpp"

namespace gridloc {

namespace {

/// The cells of one side of the resampled grid, as a double (checked before any cast). A
/// tolerance keeps an exact ratio (e.g. 0.05 -> 0.10) from gaining a spurious column.
double resampled_side(int cells, double from, double to) {
  return std::max(1.0, std::ceil(cells * from / to - 1e-9));
}

}  // namespace

OccupancyMap resample(const OccupancyMap& map, double resolution, const ResourceLimits& limits) {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw Error("grid resolution must be positive, got " + std::to_string(resolution));
  }
  const GridGeometry& src = map.geometry;
  const double width = resampled_side(src.width, src.resolution, resolution);
  const double height = resampled_side(src.height, src.resolution, resolution);
  check_grid_cells(width, height, limits,
                   "the map resampled at " + std::to_string(resolution) + " m");
  GridGeometry g = src;
  g.resolution = resolution;
  g.width = static_cast<int>(width);
  g.height = static_cast<int>(height);

  if (resolution < src.resolution) {
    OccupancyMap out(g, CellState::Unknown);
    for (int iy = 0; iy < g.height; ++iy) {
      for (int ix = 0; ix < g.width; ++ix) {
        const Eigen::Vector2d c = g.cell_center(ix, iy);
        const Cell s = src.cell_of(c.x(), c.y());
        if (src.contains(s.ix, s.iy)) out.at(ix, iy) = map.at(s.ix, s.iy);
      }
    }
    return out;
  }

  // Per target cell: bit 0 any occupied, bit 1 any free, bit 2 any unknown.
  Grid<std::uint8_t> flags(g, 0);
  for (int sy = 0; sy < src.height; ++sy) {
    const int ty =
        std::min(g.height - 1, static_cast<int>((sy + 0.5) * src.resolution / resolution));
    for (int sx = 0; sx < src.width; ++sx) {
      const int tx =
          std::min(g.width - 1, static_cast<int>((sx + 0.5) * src.resolution / resolution));
      const CellState s = map.at(sx, sy);
      flags.at(tx, ty) |= s == CellState::Occupied ? 1 : s == CellState::Free ? 2 : 4;
    }
  }
  OccupancyMap out(g, CellState::Unknown);
  for (std::size_t i = 0; i < out.cells.size(); ++i) {
    const auto f = flags.cells[i];
    out.cells[i] = (f & 1) ? CellState::Occupied : (f == 2) ? CellState::Free : CellState::Unknown;
  }
  return out;
}

EvidenceGrid make_evidence(const OccupancyMap& map) {
  EvidenceGrid e(map.geometry, 0.0f);
  for (std::size_t i = 0; i < map.cells.size(); ++i) {
    const CellState s = map.cells[i];
    e.cells[i] = s == CellState::Occupied ? 1.0f : s == CellState::Free ? -1.0f : 0.0f;
  }
  return e;
}

EvidenceGrid make_thinned_evidence(const OccupancyMap& map) {
  EvidenceGrid e = make_evidence(map);
  const int w = map.width(), h = map.height();
  for (int iy = 0; iy < h; ++iy) {
    for (int ix = 0; ix < w; ++ix) {
      if (map.at(ix, iy) != CellState::Occupied) continue;
      bool faces_free = false;
      for (int dy = -1; dy <= 1 && !faces_free; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = ix + dx, ny = iy + dy;
          if (map.geometry.contains(nx, ny) && map.at(nx, ny) == CellState::Free) {
            faces_free = true;
            break;
          }
        }
      }
      if (!faces_free) e.at(ix, iy) = 0.0f;
    }
  }
  return e;
}

EvidenceGrid make_global_grid(const OccupancyMap& map, double resolution, GlobalModel model,
                              const LikelihoodFieldOptions& field, const ResourceLimits& limits) {
  const OccupancyMap level = resample(map, resolution, limits);
  switch (model) {
    case GlobalModel::Thinned:
      return make_thinned_evidence(level);
    case GlobalModel::LikelihoodField:
      return make_likelihood_field(level, field);
    case GlobalModel::Raw:
      break;
  }
  return make_evidence(level);
}

}  // namespace gridloc
