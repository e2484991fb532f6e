#pragma once
/// The model of scan-to-map ICP: the map's contour cells (the cells of the contour-thinned
/// global grid, seed 001 §5) as points in the world frame, each with the normal of the wall
/// it lies on, indexed for nearest-neighbour queries.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "gridloc/grids/grid.hpp"

namespace gridloc {

namespace detail {
class PointBuckets;
}

struct MapContourOptions {
  /// A contour cell's normal is that of the total-least-squares line through the contour
  /// cells within this radius (m; at least 1.5 cells is used); cells with fewer than 3 such
  /// neighbours (themselves included) are left out: a lone post has no tangent.
  double normal_radius_m = 0.15;
  /// Bucket size of the nearest-neighbour index (m).
  double bucket_m = 0.5;
};

class MapContour {
 public:
  /// Throws gridloc::Error for an empty map or non-positive options.
  explicit MapContour(const OccupancyMap& map, const MapContourOptions& options = {});

  /// Contour points with a normal (world frame, m), and their unit normals.
  const std::vector<Eigen::Vector2d>& points() const { return *points_; }
  const std::vector<Eigen::Vector2d>& normals() const { return normals_; }
  std::size_t size() const { return normals_.size(); }
  /// The index of points(): internal to the engine's ICP.
  const detail::PointBuckets& buckets() const { return *buckets_; }

 private:
  // Shared so copies of the contour stay valid (the buckets point into the points).
  std::shared_ptr<const std::vector<Eigen::Vector2d>> points_;
  std::vector<Eigen::Vector2d> normals_;
  std::shared_ptr<const detail::PointBuckets> buckets_;
};

}  // namespace gridloc
