#pragma once
// Random search problems shared by the branch-and-bound tests: grids of several kinds (ternary,
// floats, ties), sparse local grids and lattices, drawn portably from fixed seeds.
#include "gridloc/engine/correlation/branch_and_bound.hpp"
#include "gridloc/grids/likelihood_field.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "random_cases.hpp"

namespace gridloc::test {

inline constexpr ArcRule kRules[] = {ArcRule::Neutral, ArcRule::Signed};

/// Field: a likelihood field's values, whole multiples of 1 / kFieldLevels near walls and
/// -1 or 0 on free cells (its pyramid's int8 levels use the scale kFieldLevels).
enum class GridKind { Ternary, Floats, Zero, Constant, Sparse, Periodic, Field, Count };

inline EvidenceGrid make_grid(std::mt19937& rng, int w, int h, GridKind kind) {
  GridGeometry geo;
  geo.width = w;
  geo.height = h;
  EvidenceGrid g(geo, 0.0f);
  switch (kind) {
    case GridKind::Ternary:
      for (float& v : g.cells) v = static_cast<float>(uniform_int(rng, -1, 1));
      break;
    case GridKind::Floats:
      for (float& v : g.cells) v = uniform_float(rng, -1.0f, 1.0f);
      break;
    case GridKind::Zero:
    case GridKind::Count:
      break;
    case GridKind::Constant: {
      const float c = std::array<float, 4>{1.0f, -1.0f, 0.5f, 0.3f}[rng() % 4];
      for (float& v : g.cells) v = c;
      break;
    }
    case GridKind::Sparse:  // like a thinned map: a few occupied cells, some free, mostly unknown
      for (float& v : g.cells) {
        const int r = uniform_int(rng, 0, 9);
        v = r == 0 ? 1.0f : (r <= 3 ? -1.0f : 0.0f);
      }
      break;
    case GridKind::Field:
      for (float& v : g.cells) {
        const int r = uniform_int(rng, 0, 3);
        v = r == 0 ? -1.0f
                   : (r == 1 ? 0.0f : uniform_int(rng, 1, kFieldLevels) / float(kFieldLevels));
      }
      break;
    case GridKind::Periodic: {  // a small tile repeated: equal scores at many translations
      const int px = uniform_int(rng, 1, 4), py = uniform_int(rng, 1, 4);
      std::vector<float> tile(static_cast<std::size_t>(px * py));
      for (float& v : tile) v = static_cast<float>(uniform_int(rng, -1, 1));
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x)
          g.at(x, y) = tile[static_cast<std::size_t>((y % py) * px + x % px)];
      }
      break;
    }
  }
  return g;
}

/// `n` distinct cells within `extent`, sorted by (dy, dx), mixed signs. Values: +-1 (many
/// ties), the sonar model's +-1/k, or arbitrary floats.
inline SparseLocalGrid make_local(std::mt19937& rng, int n, int extent, int value_kind) {
  const int side = 2 * extent + 1;
  n = std::min(n, side * side);
  std::set<std::pair<int, int>> cells;  // (dy, dx)
  while (static_cast<int>(cells.size()) < n) {
    cells.insert({uniform_int(rng, -extent, extent), uniform_int(rng, -extent, extent)});
  }
  SparseLocalGrid l;
  for (const auto& [dy, dx] : cells) {
    l.dx.push_back(dx);
    l.dy.push_back(dy);
    const float sign = uniform_int(rng, 0, 9) < 4 ? 1.0f : -1.0f;
    float v = sign;
    if (value_kind == 1) v = sign / static_cast<float>(uniform_int(rng, 1, 23));
    if (value_kind == 2) v = sign * uniform_float(rng, 0.01f, 2.0f);
    l.value.push_back(v);
  }
  return l;
}

inline Lattice make_lattice(std::mt19937& rng, int w, int h, int headings) {
  Lattice lat;
  lat.headings = headings;
  lat.theta0 = 0.0;
  lat.step_theta = 1.0;  // heading index it has theta = it: make_local picks locals[it]
  switch (uniform_int(rng, 0, 4)) {
    case 0:  // the whole map
      lat.x0 = 0, lat.x1 = w - 1, lat.y0 = 0, lat.y1 = h - 1;
      break;
    case 1:  // a single cell
      lat.x0 = lat.x1 = uniform_int(rng, 0, w - 1);
      lat.y0 = lat.y1 = uniform_int(rng, 0, h - 1);
      break;
    case 2: {  // a +-r window around a cell, clipped at the map's edge
      const int r = uniform_int(rng, 0, 12);
      const int cx = uniform_int(rng, 0, w - 1), cy = uniform_int(rng, 0, h - 1);
      lat.x0 = std::max(0, cx - r), lat.x1 = std::min(w - 1, cx + r);
      lat.y0 = std::max(0, cy - r), lat.y1 = std::min(h - 1, cy + r);
      break;
    }
    default:  // any sub-rectangle
      lat.x0 = uniform_int(rng, 0, w - 1), lat.x1 = uniform_int(rng, lat.x0, w - 1);
      lat.y0 = uniform_int(rng, 0, h - 1), lat.y1 = uniform_int(rng, lat.y0, h - 1);
      break;
  }
  return lat;
}

}  // namespace gridloc::test
