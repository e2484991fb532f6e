// The map side of team localization: walls and corners of polygon maps (their rings as
// they are) and of occupancy maps (the free space's traced outline, simplified).
#include "gridloc/engine/team/map_features.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "free_outline.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/option_checks.hpp"
#include "outline_walls.hpp"

namespace gridloc {
namespace {

/// Free regions smaller than this many cells are no room of the map (specks of noise).
constexpr int kMinFreeRegionCells = 9;
/// Floors of the outline's simplification tolerance and shortest wall, in cells: a traced
/// outline zigzags by up to a cell along a slanted wall, and a rasterized wall's cut corners
/// run up to about 3 cells.
constexpr double kMinSimplifyCells = 1.5;
constexpr double kMinWallCells = 3.0;

void check_positive(double value, const char* field) {
  require_positive(value, "MapFeatureOptions", field);
}

/// The signed angle (rad, left positive) from direction `in` to direction `out`; 0 when
/// either has no length.
double turn_angle(const Eigen::Vector2d& in, const Eigen::Vector2d& out) {
  return std::atan2(in.x() * out.y() - in.y() * out.x(), in.dot(out));
}

/// Appends the ring's walls (vertex k to k + 1) and its corners (vertices turning by at
/// least min_turn) to `features`.
void add_ring(const Polygon& ring, const MapFeatureOptions& options, MapFeatures& features) {
  const int first = static_cast<int>(features.walls.size());
  const int n = static_cast<int>(ring.size());
  for (int k = 0; k < n; ++k) features.walls.push_back({ring[k], ring[(k + 1) % n]});
  for (int k = 0; k < n; ++k) {
    const int in = first + (k + n - 1) % n, out = first + k;
    const MapWall &arriving = features.walls[in], &leaving = features.walls[out];
    const double turn = turn_angle(arriving.b - arriving.a, leaving.b - leaving.a);
    if (std::abs(turn) >= options.min_turn) {
      features.corners.push_back({ring[k], in, out, std::numbers::pi - turn});
    }
  }
}

}  // namespace

bool MapCorner::convex() const {
  return free_angle > std::numbers::pi;
}

void validate(const MapFeatureOptions& options) {
  if (!(options.min_turn > 0.0 && options.min_turn < std::numbers::pi)) {
    throw Error("MapFeatureOptions: min_turn must lie in (0, pi) rad, got " +
                std::to_string(options.min_turn));
  }
  check_positive(options.simplify_m, "simplify_m");
  check_positive(options.min_wall_m, "min_wall_m");
}

MapFeatures polygon_features(const PolygonMap& map, const MapFeatureOptions& options) {
  validate(options);
  std::vector<const Polygon*> rings{&map.boundary};
  for (const Polygon& obstacle : map.obstacles) rings.push_back(&obstacle);
  MapFeatures features;
  for (std::size_t r = 0; r < rings.size(); ++r) {
    if (rings[r]->size() < 3) {
      throw Error("polygon_features: " +
                  (r == 0 ? std::string("the boundary") : "obstacle " + std::to_string(r - 1)) +
                  " has " + std::to_string(rings[r]->size()) + " vertices, needs at least 3");
    }
    add_ring(*rings[r], options, features);
  }
  return features;
}

MapFeatures occupancy_features(const OccupancyMap& map, const MapFeatureOptions& options) {
  validate(options);
  bool any_free = false;
  for (CellState cell : map.cells) any_free = any_free || cell == CellState::Free;
  if (!any_free) throw Error("occupancy map has no free cells");
  MapFeatures features;
  features.exact = false;
  const double cell = map.geometry.resolution;
  const double tolerance = std::max(options.simplify_m, kMinSimplifyCells * cell);
  const double min_wall = std::max(options.min_wall_m, kMinWallCells * cell);
  for (const Polygon& traced : detail::free_outline(map, kMinFreeRegionCells)) {
    const Polygon ring = detail::fit_walls(traced, tolerance, min_wall);
    if (!ring.empty()) add_ring(ring, options, features);
  }
  return features;
}

}  // namespace gridloc
