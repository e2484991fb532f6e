#include "grid_useful.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "gridloc/grids/cell_walk.hpp"

namespace gridloc {
namespace {

/// Casting rays for U from one internal cell through OI, marking the cells they cross.
struct UsefulRays {
  const GridOverlay& overlay;
  std::vector<std::uint8_t>& useful;  ///< the marks
  int& marked;                        ///< cells marked so far
  Cell from;                          ///< the internal cell the rays start at (its centre)
  double limit = 0.0;                 ///< the range (cells)
};

/// Marks the OI cells a ray from `rays.from` at angle a crosses before it leaves OI, whose
/// centres lie within the range (Amanatides-Woo traversal); returns where it left OI or passed
/// the range (cells from the start).
double cast_useful_ray(const UsefulRays& rays, double a) {
  const GridGeometry& g = rays.overlay.grid;
  // The ray starts at the cell centre.
  CellWalk walk(rays.from.ix + 0.5, rays.from.iy + 0.5, std::cos(a), std::sin(a));
  while (walk.t <= rays.limit) {
    const std::size_t i = g.index(walk.ix, walk.iy);
    const double cx = walk.ix - rays.from.ix, cy = walk.iy - rays.from.iy;
    if (!rays.useful[i] && cx * cx + cy * cy <= rays.limit * rays.limit) {
      rays.useful[i] = 1;
      ++rays.marked;
    }
    walk.step();
    if (!g.contains(walk.ix, walk.iy) || !rays.overlay.in_oi[g.index(walk.ix, walk.iy)]) break;
  }
  return std::min(walk.t, rays.limit);
}

/// Adds rays between angles a0 < a1 (whose rays reached t0 and t1 cells) until neighbouring
/// rays are at most a cell apart where the longer one ends, so no opening a cell wide is
/// stepped over and distant cells are not missed.
void fill_between(const UsefulRays& rays, double a0, double t0, double a1, double t1) {
  if (std::max(t0, t1) * (a1 - a0) <= 1.0) return;
  const double middle = 0.5 * (a0 + a1);
  const double t = cast_useful_ray(rays, middle);
  fill_between(rays, a0, t0, middle, t);
  fill_between(rays, middle, t, a1, t1);
}

/// Casts the rays of one internal cell: 128 evenly spread, then more where they diverge.
void cast_from(const UsefulRays& rays) {
  constexpr int kBaseRays = 128;
  const double step = 2.0 * std::numbers::pi / kBaseRays;
  std::array<double, kBaseRays + 1> reach{};
  for (int k = 0; k < kBaseRays; ++k) reach[k] = cast_useful_ray(rays, k * step);
  reach[kBaseRays] = reach[0];  // the circle closes
  for (int k = 0; k < kBaseRays; ++k) {
    fill_between(rays, k * step, reach[k], (k + 1) * step, reach[k + 1]);
  }
}

}  // namespace

/// U: the OI cells that see an internal cell within range (seed 002 §IV-D steps 5-6, the weak
/// visibility polygon of the internal edges clipped to the range). Returns the count.
int mark_useful(GridOverlay& overlay) {
  const GridGeometry& g = overlay.grid;
  const double limit = std::min(overlay.range / g.resolution, std::hypot(g.width, g.height));
  int marked = 0;
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      if (marked == overlay.oi_count) return marked;  // all of OI is useful already
      if (!overlay.internal[g.index(ix, iy)]) continue;
      cast_from(UsefulRays{overlay, overlay.useful, marked, {ix, iy}, limit});
    }
  }
  return marked;
}

}  // namespace gridloc
