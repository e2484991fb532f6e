#include "gridloc/grids/pooling.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

// `packed` is written as the x86 MAXPS / MINPS semantics (first operand when it wins,
// else the second) so that loops of it vectorize without -ffast-math; for the grids' values
// (no NaN) it equals apply.
struct Max {
  static float apply(float a, float b) { return std::max(a, b); }
  template <typename T>
  static T packed(T a, T b) {
    return a > b ? a : b;
  }
};
struct Min {
  static float apply(float a, float b) { return std::min(a, b); }
  template <typename T>
  static T packed(T a, T b) {
    return a < b ? a : b;
  }
};

/// out[i] = Op(a[i], b[i]) for i < n, where b's run never overlaps out's (a may be out).
template <class Op, typename T>
void combine(T* out, const T* a, const T* __restrict b, int n) {
  for (int i = 0; i < n; ++i) out[i] = Op::packed(a[i], b[i]);
}

void check_size(int size, const char* what) {
  if (size < 1)
    throw Error(std::string(what) + ": block size must be >= 1, got " + std::to_string(size));
}

/// `nonzero` clipped to the grid (an empty rectangle stays empty).
CellRect checked(CellRect nonzero, int width, int height) {
  nonzero.x0 = std::clamp(nonzero.x0, 0, width);
  nonzero.y0 = std::clamp(nonzero.y0, 0, height);
  nonzero.x1 = std::clamp(nonzero.x1, nonzero.x0, width);
  nonzero.y1 = std::clamp(nonzero.y1, nonzero.y0, height);
  return nonzero;
}

// van Herk / Gil-Werman along one axis: split the axis into blocks [jk, jk + k); `pre` holds
// the running Op from each block's start, `suf` the running Op to each block's end. A window
// [i, i + k) that fits in the axis meets at most two blocks, so its Op is
// Op(suf[i], pre[i + k - 1]); a window clipped by the axis end is a plain suffix Op. Three
// Op per cell whatever k. The column pass works on whole rows so both passes stream memory.

/// Pools every row of `in` (w x h) into `out` over [x, x + k).
template <class Op>
void pool_rows(const float* in, float* out, int w, int h, int k, std::vector<float>& pre,
               std::vector<float>& suf) {
  pre.resize(static_cast<std::size_t>(w));
  suf.resize(static_cast<std::size_t>(w));
  const int full = std::max(0, w - k + 1);  // windows [x, x + k) that fit in the row
  for (int y = 0; y < h; ++y) {
    const float* a = in + static_cast<std::ptrdiff_t>(y) * w;
    float* o = out + static_cast<std::ptrdiff_t>(y) * w;
    for (int x = 0, r = 0; x < w; ++x, r = (r + 1 == k ? 0 : r + 1)) {
      pre[x] = r == 0 ? a[x] : Op::apply(pre[x - 1], a[x]);
    }
    for (int x = w - 1; x >= 0; --x) {
      const bool block_end = (x + 1) % k == 0 || x == w - 1;
      suf[x] = block_end ? a[x] : Op::apply(a[x], suf[x + 1]);
    }
    for (int x = 0; x < full; ++x) o[x] = Op::apply(suf[x], pre[x + k - 1]);
    for (int x = w - 1; x >= full; --x) o[x] = x == w - 1 ? a[x] : Op::apply(a[x], o[x + 1]);
  }
}

/// Pools every column of `in` (w x h) into `out` over [y, y + k), whole rows at a time.
template <class Op>
void pool_columns(const float* in, float* out, int w, int h, int k, std::vector<float>& pre,
                  std::vector<float>& suf) {
  const auto n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  pre.resize(n);
  suf.resize(n);
  auto row = [w](auto* base, int y) { return base + static_cast<std::ptrdiff_t>(y) * w; };
  for (int y = 0, r = 0; y < h; ++y, r = (r + 1 == k ? 0 : r + 1)) {
    const float* a = row(in, y);
    float* p = row(pre.data(), y);
    if (r == 0) {
      std::copy(a, a + w, p);
    } else {
      const float* q = row(pre.data(), y - 1);
      for (int x = 0; x < w; ++x) p[x] = Op::apply(q[x], a[x]);
    }
  }
  for (int y = h - 1; y >= 0; --y) {
    const float* a = row(in, y);
    float* s = row(suf.data(), y);
    if ((y + 1) % k == 0 || y == h - 1) {
      std::copy(a, a + w, s);
    } else {
      const float* q = row(suf.data(), y + 1);
      for (int x = 0; x < w; ++x) s[x] = Op::apply(a[x], q[x]);
    }
  }
  const int full = std::max(0, h - k + 1);
  for (int y = 0; y < full; ++y) {
    const float* s = row(suf.data(), y);
    const float* p = row(pre.data(), y + k - 1);
    float* o = row(out, y);
    for (int x = 0; x < w; ++x) o[x] = Op::apply(s[x], p[x]);
  }
  for (int y = h - 1; y >= full; --y) {
    const float* a = row(in, y);
    float* o = row(out, y);
    if (y == h - 1) {
      std::copy(a, a + w, o);
    } else {
      const float* q = row(out, y + 1);
      for (int x = 0; x < w; ++x) o[x] = Op::apply(a[x], q[x]);
    }
  }
}

template <class Op>
Grid<float> pool(const Grid<float>& g, int size) {
  Grid<float> rows(g.geometry, 0.0f), out(g.geometry, 0.0f);
  if (g.cells.empty()) return out;
  std::vector<float> pre, suf;
  pool_rows<Op>(g.cells.data(), rows.cells.data(), g.width(), g.height(), size, pre, suf);
  pool_columns<Op>(rows.cells.data(), out.cells.data(), g.width(), g.height(), size, pre, suf);
  return out;
}

template <class Op>
Grid<float> pool_reference(const Grid<float>& g, int size) {
  Grid<float> out(g.geometry, 0.0f);
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      float v = g.at(x, y);
      for (int yy = y; yy < std::min(y + size, g.height()); ++yy) {
        for (int xx = x; xx < std::min(x + size, g.width()); ++xx) v = Op::apply(v, g.at(xx, yy));
      }
      out.at(x, y) = v;
    }
  }
  return out;
}

/// The pool of blocks 2s from the pool of blocks s: a 2s block is four s blocks, at offsets
/// 0 and s on each axis (those starting past the grid's edge are empty and skipped), so this
/// is exact. Each pass is an elementwise Op of two contiguous runs that do not overlap, which
/// the compiler turns into packed min/max instructions (see pool_doubled's test). Only the
/// rectangle `nonzero` (cells outside it are zero) grown by s on its low sides can change:
/// any other cell reads zeros alone, and the pool of zeros is zero.
template <class Op, typename T>
CellRect pool_doubled_in_place(T* cells, int w, int h, int s, CellRect nonzero) {
  const CellRect out{std::max(nonzero.x0 - s, 0), std::max(nonzero.y0 - s, 0), nonzero.x1,
                     nonzero.y1};
  const auto row = [&](int y) { return cells + static_cast<std::ptrdiff_t>(y) * w; };
  // Along x: each row's run [x0, x1) against the run s ahead, through a copy of both (the
  // runs overlap when s is shorter than the row).
  const int x_end = std::min(out.x1, w - s);  // the cells with a block s ahead
  std::vector<T> copy(static_cast<std::size_t>(std::max(x_end + s - out.x0, 0)));
  for (int y = out.y0; y < out.y1 && x_end > out.x0; ++y) {
    T* o = row(y) + out.x0;
    std::copy(o, o + copy.size(), copy.begin());
    combine<Op>(o, copy.data(), copy.data() + s, x_end - out.x0);
  }
  // Along y: row y against row y + s, a different run of the grid.
  for (int y = out.y0; y < out.y1 && y + s < h; ++y) {
    T* o = row(y) + out.x0;
    combine<Op>(o, o, row(y + s) + out.x0, out.x1 - out.x0);
  }
  return out;
}

template <class Op, typename T>
void pool_doubled_in_place(T* cells, int w, int h, int s) {
  pool_doubled_in_place<Op>(cells, w, h, s, CellRect{0, 0, w, h});
}

template <class Op>
void pool_doubled_in_place(Grid<float>& grid, int s) {
  pool_doubled_in_place<Op>(grid.cells.data(), grid.width(), grid.height(), s);
}

template <class Op>
Grid<float> pool_doubled(const Grid<float>& pooled, int s) {
  Grid<float> out = pooled;
  pool_doubled_in_place<Op>(out, s);
  return out;
}

}  // namespace

Grid<float> max_pool_doubled(const Grid<float>& pooled, int size) {
  check_size(size, "max_pool_doubled");
  return pool_doubled<Max>(pooled, size);
}

Grid<float> min_pool_doubled(const Grid<float>& pooled, int size) {
  check_size(size, "min_pool_doubled");
  return pool_doubled<Min>(pooled, size);
}

void max_pool_doubled_in_place(Grid<float>& pooled, int size) {
  check_size(size, "max_pool_doubled_in_place");
  pool_doubled_in_place<Max>(pooled, size);
}

void min_pool_doubled_in_place(Grid<float>& pooled, int size) {
  check_size(size, "min_pool_doubled_in_place");
  pool_doubled_in_place<Min>(pooled, size);
}

void max_pool_doubled_in_place(std::int8_t* cells, int width, int height, int size) {
  check_size(size, "max_pool_doubled_in_place");
  pool_doubled_in_place<Max>(cells, width, height, size);
}

void min_pool_doubled_in_place(std::int8_t* cells, int width, int height, int size) {
  check_size(size, "min_pool_doubled_in_place");
  pool_doubled_in_place<Min>(cells, width, height, size);
}

CellRect max_pool_doubled_in_place(std::int8_t* cells, int width, int height, int size,
                                   CellRect nonzero) {
  check_size(size, "max_pool_doubled_in_place");
  return pool_doubled_in_place<Max>(cells, width, height, size, checked(nonzero, width, height));
}

CellRect min_pool_doubled_in_place(std::int8_t* cells, int width, int height, int size,
                                   CellRect nonzero) {
  check_size(size, "min_pool_doubled_in_place");
  return pool_doubled_in_place<Min>(cells, width, height, size, checked(nonzero, width, height));
}

Grid<float> max_pool(const Grid<float>& g, int size) {
  check_size(size, "max_pool");
  return pool<Max>(g, size);
}

Grid<float> min_pool(const Grid<float>& g, int size) {
  check_size(size, "min_pool");
  return pool<Min>(g, size);
}

Grid<float> max_pool_reference(const Grid<float>& g, int size) {
  check_size(size, "max_pool_reference");
  return pool_reference<Max>(g, size);
}

Grid<float> min_pool_reference(const Grid<float>& g, int size) {
  check_size(size, "min_pool_reference");
  return pool_reference<Min>(g, size);
}

}  // namespace gridloc
