#pragma once
// Uniform-grid buckets of 2-D points for nearest-neighbour and radius queries (ICP's
// correspondences and the map contour's normals). Internal to the engine.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace gridloc::detail {

class PointBuckets {
 public:
  PointBuckets() = default;
  /// Buckets `usable` indices of `points` in square cells of about `cell` metres (grown so a
  /// side has at most 1024 cells). `points` must outlive the buckets.
  PointBuckets(const std::vector<Eigen::Vector2d>& points, const std::vector<int>& usable,
               double cell)
      : points_(&points), cell_(cell) {
    lo_ = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector2d hi = -lo_;
    for (int i : usable) {
      lo_ = lo_.cwiseMin(points[i]);
      hi = hi.cwiseMax(points[i]);
    }
    if (usable.empty()) lo_ = hi = Eigen::Vector2d::Zero();
    cell_ = std::max(cell_, (hi - lo_).maxCoeff() / 1024.0);
    nx_ = static_cast<int>((hi.x() - lo_.x()) / cell_) + 1;
    ny_ = static_cast<int>((hi.y() - lo_.y()) / cell_) + 1;
    start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    for (int i : usable) ++start_[cell_index(points[i]) + 1];
    for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
    index_.resize(usable.size());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (int i : usable) index_[fill[cell_index(points[i])]++] = i;  // ascending within a cell
  }

  /// Calls f(i) for every bucketed point i within the cells that can hold points within
  /// `radius` of q (a superset of the disc).
  template <typename F>
  void for_each_near(const Eigen::Vector2d& q, double radius, F&& f) const {
    // Clamped in double: a radius beyond the grid covers it all, and cannot overflow the cast.
    const int reach =
        static_cast<int>(std::min(std::ceil(radius / cell_), static_cast<double>(nx_ + ny_)));
    // Clamped in double first, so a query far outside the grid cannot overflow the cast.
    const int cx = static_cast<int>(std::clamp(std::floor((q.x() - lo_.x()) / cell_), -1.0 - reach,
                                               static_cast<double>(nx_ + reach)));
    const int cy = static_cast<int>(std::clamp(std::floor((q.y() - lo_.y()) / cell_), -1.0 - reach,
                                               static_cast<double>(ny_ + reach)));
    for (int y = std::max(cy - reach, 0); y <= std::min(cy + reach, ny_ - 1); ++y) {
      for (int x = std::max(cx - reach, 0); x <= std::min(cx + reach, nx_ - 1); ++x) {
        const std::size_t c = static_cast<std::size_t>(y) * nx_ + x;
        for (int k = start_[c]; k < start_[c + 1]; ++k) f(index_[k]);
      }
    }
  }

  /// Index of the nearest bucketed point within `max_dist`, or -1; ties go to the lowest index.
  int nearest(const Eigen::Vector2d& q, double max_dist) const {
    int best = -1;
    double best_d2 = max_dist * max_dist;
    for_each_near(q, max_dist, [&](int i) {
      const double d2 = ((*points_)[i] - q).squaredNorm();
      if (d2 < best_d2 || (d2 == best_d2 && best >= 0 && i < best)) {
        best_d2 = d2;
        best = i;
      }
    });
    return best;
  }

 private:
  std::size_t cell_index(const Eigen::Vector2d& p) const {
    const int x = std::min(static_cast<int>((p.x() - lo_.x()) / cell_), nx_ - 1);
    const int y = std::min(static_cast<int>((p.y() - lo_.y()) / cell_), ny_ - 1);
    return static_cast<std::size_t>(y) * nx_ + x;
  }

  const std::vector<Eigen::Vector2d>* points_ = nullptr;
  double cell_ = 1.0;
  Eigen::Vector2d lo_ = Eigen::Vector2d::Zero();
  int nx_ = 1, ny_ = 1;
  std::vector<int> start_ = {0, 0};
  std::vector<int> index_;
};

}  // namespace gridloc::detail
