#include "gridloc/engine/icp/map_contour.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/evidence.hpp"
#include "point_buckets.hpp"

namespace gridloc {

MapContour::MapContour(const OccupancyMap& map, const MapContourOptions& options) {
  if (map.geometry.size() == 0) throw Error("MapContour: the map is empty");
  if (!(options.normal_radius_m > 0.0) || !(options.bucket_m > 0.0) ||
      !std::isfinite(options.normal_radius_m) || !std::isfinite(options.bucket_m)) {
    throw Error(
        "MapContourOptions: normal_radius_m and bucket_m must be positive and finite, got " +
        std::to_string(options.normal_radius_m) + " and " + std::to_string(options.bucket_m));
  }
  const GridGeometry& g = map.geometry;
  const EvidenceGrid thinned = make_thinned_evidence(map);
  std::vector<Eigen::Vector2d> cells;
  std::vector<Cell> cells_of;
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      if (thinned.at(ix, iy) <= 0.0f) continue;
      const Eigen::Vector2d c = g.cell_center(ix, iy);
      const Pose2 w = g.to_world_frame({c.x(), c.y(), 0.0});
      cells.emplace_back(w.x, w.y);
      cells_of.push_back({ix, iy});
    }
  }
  std::vector<int> all(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) all[i] = static_cast<int>(i);
  const double radius = std::max(options.normal_radius_m, 1.5 * g.resolution);
  const detail::PointBuckets near(cells, all, radius);

  // Each cell's normal: the smaller eigenvector of the scatter of its neighbours.
  auto points = std::make_shared<std::vector<Eigen::Vector2d>>();
  for (const Eigen::Vector2d& p : cells) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    int n = 0;
    near.for_each_near(p, radius, [&](int j) {
      if ((cells[j] - p).squaredNorm() <= radius * radius) mean += cells[j], ++n;
    });
    if (n < 3) continue;
    mean /= n;
    Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
    near.for_each_near(p, radius, [&](int j) {
      if ((cells[j] - p).squaredNorm() <= radius * radius) {
        scatter += (cells[j] - mean) * (cells[j] - mean).transpose();
      }
    });
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
    Eigen::Vector2d normal = eig.eigenvectors().col(0).normalized();
    // A contour cell's centre lies half a cell inside the obstacle; a range sensor sees its
    // face. The point moves to that face: half a cell along the normal, turned to the side
    // of the cell's free neighbours (their mean direction).
    const Cell& cell = cells_of[&p - cells.data()];
    Eigen::Vector2d to_free = Eigen::Vector2d::Zero();
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if (g.contains(cell.ix + dx, cell.iy + dy) &&
            map.at(cell.ix + dx, cell.iy + dy) == CellState::Free) {
          to_free += Eigen::Vector2d(dx, dy).normalized();
        }
      }
    }
    const Eigen::Vector2d to_free_world = Eigen::Rotation2Dd(g.yaw) * to_free;
    if (normal.dot(to_free_world) < 0.0) normal = -normal;
    const double shift = to_free.squaredNorm() > 0.0 ? 0.5 * g.resolution : 0.0;
    points->push_back(p + shift * normal);
    normals_.push_back(normal);
  }
  std::vector<int> usable(points->size());
  for (std::size_t i = 0; i < usable.size(); ++i) usable[i] = static_cast<int>(i);
  buckets_ = std::make_shared<const detail::PointBuckets>(*points, usable, options.bucket_m);
  points_ = std::move(points);
}

}  // namespace gridloc
