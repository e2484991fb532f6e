// Drawing the trials of seed 001's evaluation protocol (trials.hpp).
#include "gridloc/engine/evaluation/trials.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

/// True when every cell of the box from cell `a` to cell `z` is on the map and free.
bool box_free(const OccupancyMap& map, const Cell& a, const Cell& z) {
  bool free = true;
  for (int iy = a.iy; iy <= z.iy && free; ++iy) {
    for (int ix = a.ix; ix <= z.ix && free; ++ix) {
      free = map.geometry.contains(ix, iy) && map.at(ix, iy) == CellState::Free;
    }
  }
  return free;
}

/// `center` pulled back onto the map of `geometry`, in the grid frame.
Pose2 clamped_onto_map(const Pose2& center, const GridGeometry& geometry) {
  const Pose2 g = geometry.to_grid_frame(center);
  const double eps = 1e-6;
  return {std::clamp(g.x, eps, geometry.width * geometry.resolution - eps),
          std::clamp(g.y, eps, geometry.height * geometry.resolution - eps), g.theta};
}

}  // namespace

OccupancyMap add_furniture(const OccupancyMap& map, const Pose2& keep, double keep_clear,
                           Rng& rng) {
  OccupancyMap world = map;
  const GridGeometry& geometry = map.geometry;
  const Pose2 k = geometry.to_grid_frame(keep);
  const int boxes = 2 + static_cast<int>(rng.next() % 3);
  for (int b = 0, attempts = 0; b < boxes && attempts < 200; ++attempts) {
    const double w = rng.uniform(0.3, 0.8), h = rng.uniform(0.3, 0.8);
    const double x0 = rng.uniform(0.0, geometry.width * geometry.resolution - w);
    const double y0 = rng.uniform(0.0, geometry.height * geometry.resolution - h);
    // The box's nearest point to the kept pose must be keep_clear away.
    const double nx = std::clamp(k.x, x0, x0 + w) - k.x, ny = std::clamp(k.y, y0, y0 + h) - k.y;
    if (std::hypot(nx, ny) < keep_clear) continue;
    const Cell a = geometry.cell_of(x0, y0), z = geometry.cell_of(x0 + w, y0 + h);
    if (!box_free(map, a, z)) continue;
    for (int iy = a.iy; iy <= z.iy; ++iy) {
      for (int ix = a.ix; ix <= z.ix; ++ix) world.at(ix, iy) = CellState::Occupied;
    }
    ++b;
  }
  return world;
}

PerturbedPrior perturb_prior(SearchWindow window, const Pose2& truth, bool wrong_prior,
                             const GridGeometry& geometry, Rng& rng) {
  window.center = {
      truth.x + rng.uniform(-window.half_xy, window.half_xy),
      truth.y + rng.uniform(-window.half_xy, window.half_xy),
      normalize_angle(truth.theta + rng.uniform(-window.half_theta, window.half_theta))};
  if (wrong_prior) {  // one axis 1.5-3 half sizes off: the truth is outside the window
    // Kept as one expression: the order of its two draws is the compiler's, and the protocol's.
    const double off = window.half_xy * rng.uniform(1.5, 3.0) * (rng.next() % 2 ? 1 : -1);
    if (rng.next() % 2) {
      window.center.x = truth.x + off;
    } else {
      window.center.y = truth.y + off;
    }
  }
  // A perturbed prior can leave a map whose edge is close; pull it back onto the map.
  const Pose2 clamped = clamped_onto_map(window.center, geometry);
  window.center = geometry.to_world_frame(clamped);
  // Pulled back onto the map, a wrong prior may hold the truth again: then it is not one.
  const Pose2 truth_g = geometry.to_grid_frame(truth);
  wrong_prior = wrong_prior && std::max(std::abs(truth_g.x - clamped.x),
                                        std::abs(truth_g.y - clamped.y)) > window.half_xy;
  return {window, wrong_prior};
}

}  // namespace gridloc
