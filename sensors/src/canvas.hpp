#pragma once
// A dense scratch canvas for building one sparse local grid, centred on the robot's cell
// (internal to gridloc::sensors). Each thread reuses one canvas across calls: a call clears
// only the cells it wrote, so it costs what it draws, not the canvas area. Two layers: arc
// (occupied evidence) and free; a cell with arc > 0 is occupied, else it holds its free
// value ("arc beats free").
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/radix_sort.hpp"
#include "gridloc/sensors/local_grid.hpp"

namespace gridloc::detail {

class Canvas {
 public:
  /// Widest canvas (cells): its cell indices, side * side of them, stay ints.
  static constexpr int kMaxSide = 46339;

  /// The calling thread's canvas, ready for cells within +-(ceil(`reach_cells`) + `margin`)
  /// (at least) of the robot's cell at `resolution` (m), the robot centre lying `centre` (m)
  /// from that cell's centre; it holds no cell from a previous call. Where a local grid's
  /// centre enters: gridloc::Error if it is not finite, or if the canvas would be wider than
  /// kMaxSide cells.
  static Canvas& for_this_thread(double reach_cells, int margin, const Eigen::Vector2d& centre,
                                 double resolution) {
    thread_local Canvas canvas;
    canvas.prepare(half_width(reach_cells, margin, centre, resolution), resolution);
    return canvas;
  }

  /// Index of the cell holding robot-centred point (x, y) in metres; the robot centre is the
  /// centre of cell (0, 0), hence the +0.5. Shifted by half_ so the value is positive on the
  /// canvas: truncation is then floor, without a call to std::floor.
  int cell_index(double x, double y) const {
    const int ix = static_cast<int>(x * inv_res_ + 0.5 + half_);
    const int iy = static_cast<int>(y * inv_res_ + 0.5 + half_);
    return iy * side_ + ix;
  }
  int index_of_cell(int cx, int cy) const { return (cy + half_) * side_ + (cx + half_); }
  int cx(int idx) const { return idx % side_ - half_; }
  int cy(int idx) const { return idx / side_ - half_; }
  bool adjacent8(int a, int b) const {
    return std::abs(cx(a) - cx(b)) <= 1 && std::abs(cy(a) - cy(b)) <= 1;
  }
  double resolution() const { return res_; }

  /// A fresh mark pass: mark(idx, pass) is true the first time a cell is marked in it.
  std::uint32_t new_pass() { return ++pass_; }
  bool mark(int idx, std::uint32_t pass) {
    if (stamp_[idx] == pass) return false;
    stamp_[idx] = pass;
    return true;
  }
  bool marked(int idx, std::uint32_t pass) const { return stamp_[idx] == pass; }

  void add_arc(int idx, float v) { arc_[touch(idx)] += v; }
  void add_free(int idx, float v) { free_[touch(idx)] += v; }
  /// Overwrites both layers of a cell (footprint, turned grids).
  void set(int idx, float arc, float free) {
    arc_[touch(idx)] = arc;
    free_[idx] = free;
  }

  /// The non-zero cells in row-major order, sorted by (dy, dx); clears what was written.
  SparseLocalGrid collect(double theta) {
    SparseLocalGrid g;
    g.resolution = res_;
    g.theta = theta;
    g.dx.reserve(touched_.size());
    g.dy.reserve(touched_.size());
    g.value.reserve(touched_.size());
    // Cells come in increasing index order: the row only ever advances (no division).
    int row = 0, row_start = 0;
    auto emit = [&](int idx) {
      while (idx >= row_start + side_) ++row, row_start += side_;
      const float v = arc_[idx] > 0.0f ? arc_[idx] : free_[idx];
      if (v != 0.0f) {
        g.dx.push_back(idx - row_start - half_);
        g.dy.push_back(row - half_);
        g.value.push_back(v);
      }
      arc_[idx] = free_[idx] = 0.0f;
      written_[idx] = 0;
    };
    if (touched_.size() * 8 < static_cast<std::size_t>(side_) * side_) {
      // Sparse (scan points, sonar cones): radix-sorting the written cells beats walking
      // their bounding box; measured, not derived (ray scans stay dense).
      radix_sort(touched_);
      if (!touched_.empty()) row = touched_.front() / side_, row_start = row * side_;
      for (int idx : touched_) emit(idx);
    } else {
      for (int idx : touched_) {
        const int r = idx / side_, col = idx - r * side_;
        x_min_ = std::min(x_min_, col), x_max_ = std::max(x_max_, col);
        y_min_ = std::min(y_min_, r), y_max_ = std::max(y_max_, r);
      }
      row = y_min_, row_start = y_min_ * side_;
      for (int r = y_min_; r <= y_max_; ++r) {
        const int begin = r * side_;
        for (int idx = begin + x_min_; idx <= begin + x_max_; ++idx) {
          if (written_[idx]) emit(idx);
        }
      }
    }
    touched_.clear();
    reset_bounds();
    return g;
  }

 private:
  /// ceil(reach_cells) + margin, checked (see for_this_thread).
  static int half_width(double reach_cells, int margin, const Eigen::Vector2d& centre,
                        double resolution) {
    if (!centre.allFinite()) {
      throw Error("local grid centre must be finite, got (" + std::to_string(centre.x()) + ", " +
                  std::to_string(centre.y()) + ")");
    }
    const double half = std::ceil(reach_cells) + margin;
    constexpr int kMaxHalfSide = (kMaxSide - 1) / 2;  // exact: kMaxSide is odd
    if (!(half <= kMaxHalfSide)) {                    // NaN fails too
      throw Error("local grid reaching " + std::to_string(reach_cells * resolution) +
                  " m at resolution " + std::to_string(resolution) +
                  " m needs a canvas wider than the " + std::to_string(kMaxSide) +
                  " cells allowed");
    }
    return static_cast<int>(half);
  }

  void prepare(int half, double resolution) {
    if (!touched_.empty()) collect(0.0);  // a previous call that threw left cells behind
    res_ = resolution;
    inv_res_ = 1.0 / resolution;
    if (half > half_) {  // grow only: levels of different resolutions share one canvas
      half_ = half;
      side_ = 2 * half + 1;
      const auto n = static_cast<std::size_t>(side_) * side_;
      arc_.assign(n, 0.0f);
      free_.assign(n, 0.0f);
      written_.assign(n, 0);
      stamp_.assign(n, 0);
      pass_ = 0;
    }
    if (pass_ > 0xF0000000u) {  // keep pass ids unique: restart before they wrap
      std::fill(stamp_.begin(), stamp_.end(), 0u);
      pass_ = 0;
    }
    reset_bounds();
  }
  void reset_bounds() {
    x_min_ = y_min_ = side_;
    x_max_ = y_max_ = -1;
  }
  int touch(int idx) {
    if (!written_[idx]) {
      written_[idx] = 1;
      touched_.push_back(idx);
    }
    return idx;
  }

  /// Sorts the (non-negative) cell indices.
  void radix_sort(std::vector<int>& v) {
    const auto area = static_cast<std::uint64_t>(side_) * static_cast<std::uint64_t>(side_);
    gridloc::radix_sort(v, scratch_, 0, bits_below(area));
  }

  double res_ = 0.1;
  double inv_res_ = 10.0;
  int half_ = -1;
  int side_ = 0;
  int x_min_ = 0, x_max_ = -1, y_min_ = 0, y_max_ = -1;
  std::uint32_t pass_ = 0;
  std::vector<float> arc_;
  std::vector<float> free_;
  std::vector<unsigned char> written_;
  std::vector<int> touched_;  ///< cells written since the last collect, in write order
  std::vector<int> scratch_;
  std::vector<std::uint32_t> stamp_;
};

}  // namespace gridloc::detail
