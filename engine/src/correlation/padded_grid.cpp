// The padded global grid: the grid with a margin the placed local grids never leave, its
// int8 cells for the fixed-point kernel and the arc view (internal to the search).
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "gridloc/engine/correlation/search.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

/// A cell v * scale as int8: the cells are whole multiples of 1 / scale (int8_scale_for),
/// rounded half away from zero inline, as std::round does, but without a call per cell.
std::int8_t to_int8(float v, float scale) {
  const float x = v * scale;
  return static_cast<std::int8_t>(x >= 0.0f ? x + 0.5f : x - 0.5f);
}

/// `grid`'s cells converted by `convert` into a zero grid of geometry `padded` at (pad,
/// pad), followed by `slack` zeros.
template <typename Cells, typename Convert>
Cells padded_cells(const EvidenceGrid& grid, const GridGeometry& padded, int pad, std::size_t slack,
                   Convert convert) {
  using T = typename Cells::value_type;
  Cells out(padded.size() + slack, T{0});
  for (int iy = 0; iy < grid.height(); ++iy) {
    const float* row = grid.row(iy);
    T* to = out.data() + padded.index(pad, iy + pad);
    for (int ix = 0; ix < grid.width(); ++ix) to[ix] = convert(row[ix]);
  }
  return out;
}

}  // namespace

PaddedGrid pad_grid(const EvidenceGrid& grid, int pad, ArcRule rule, PaddedCells cells) {
  PaddedGrid p;
  p.pad = pad;
  p.width = grid.width();
  p.height = grid.height();
  if (pad < 0) throw Error("padded grid: pad = " + std::to_string(pad) + " must be >= 0");
  // Sizes in double first: a huge pad must be an error, not an int overflow.
  const double w = grid.width() + 2.0 * pad, h = grid.height() + 2.0 * pad;
  if (w * h >= 2147483648.0) {
    std::ostringstream m;
    m << "padded grid of " << w << " x " << h << " cells is too large (2^31 cells or more)";
    throw Error(m.str());
  }
  p.grid.geometry = grid.geometry;
  p.grid.geometry.width = static_cast<int>(w);
  p.grid.geometry.height = static_cast<int>(h);
  const bool negatives =
      std::any_of(grid.cells.begin(), grid.cells.end(), [](float v) { return v < 0.0f; });
  p.arc_is_grid = rule == ArcRule::Signed || !negatives;
  const auto arc = [](float v) { return std::max(v, 0.0f); };
  // The padding's zeros are whole at any scale, and the arc view takes its values from the
  // grid: one scale serves both.
  const float scale = int8_scale_for(grid.cells);
  if (scale > 0.0f) {
    p.int8_scale = scale;
    p.grid8 = padded_cells<Int8Cells>(grid, p.grid.geometry, pad, kGatherSlack,
                                      [scale](float v) { return to_int8(v, scale); });
    if (!p.arc_is_grid) {
      p.arc_cells8 = padded_cells<Int8Cells>(grid, p.grid.geometry, pad, kGatherSlack,
                                             [&](float v) { return to_int8(arc(v), scale); });
    }
    if (cells == PaddedCells::Int8WhereExact) return p;
  }
  p.grid.cells =
      padded_cells<std::vector<float>>(grid, p.grid.geometry, pad, 0, [](float v) { return v; });
  if (!p.arc_is_grid) {
    p.arc_cells = padded_cells<std::vector<float>>(grid, p.grid.geometry, pad, 0, arc);
  }
  return p;
}

std::vector<float> PaddedGrid::float_cells() const {
  if (has_floats()) return grid.cells;
  std::vector<float> out(cell_count());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = decode(grid8[i]);
  return out;
}

std::vector<float> PaddedGrid::arc_float_cells() const {
  if (has_floats()) return arc_view();
  std::vector<float> out(cell_count());
  const Int8Cells& arc = arc_view8();
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = decode(arc[i]);
  return out;
}

float int8_scale_for(const std::vector<float>& cells) {
  for (const float scale : {1.0f, static_cast<float>(kFieldLevels)}) {
    const bool whole = std::all_of(cells.begin(), cells.end(), [scale](float v) {
      const float q = std::round(v * scale);
      return std::abs(q) <= 127.0f && q / scale == v;
    });
    if (whole) return scale;
  }
  return 0.0f;
}

Int8Cells to_int8_with_slack(const std::vector<float>& cells, float scale) {
  Int8Cells out(cells.size() + kGatherSlack, 0);
  std::transform(cells.begin(), cells.end(), out.begin(),
                 [scale](float v) { return to_int8(v, scale); });
  return out;
}

}  // namespace gridloc
