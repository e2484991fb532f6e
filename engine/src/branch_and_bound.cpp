#include "gridloc/engine/branch_and_bound.hpp"

#include <algorithm>
#include <sstream>
#include <string>
#include <tuple>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/pooling.hpp"

// Exactness rests on IEEE rounding being monotone and on the bound being summed exactly as
// score() sums (see block_bound); reassociating compilers would break both.
#if defined(__FAST_MATH__)
#error "branch_and_bound.cpp needs IEEE floating point: build without -ffast-math"
#endif

namespace gridloc {
namespace {

constexpr int kMaxDepth = 30;  // 2^h must fit an int

/// A block of 2^h x 2^h translations starting at (ix, iy), for heading it. Its first pose in
/// lattice order is (it, iy, ix): every other pose has a larger row, or the same row and a
/// larger column.
struct Node {
  double bound = 0.0;
  int it = 0, iy = 0, ix = 0, h = 0;
};

bool index_less(int it, int iy, int ix, const LatticePose& b) {
  return std::tie(it, iy, ix) < std::tie(b.it, b.iy, b.ix);
}

/// Better pose = higher score, then lower index (search_exhaustive's order).
bool better(const LatticePose& a, const LatticePose& b) {
  if (a.score != b.score) return a.score > b.score;
  return index_less(a.it, a.iy, a.ix, b);
}

/// Visit order: higher bound first, then lower first pose.
bool visit_before(const Node& a, const Node& b) {
  if (a.bound != b.bound) return a.bound > b.bound;
  return std::tie(a.it, a.iy, a.ix) < std::tie(b.it, b.iy, b.ix);
}

void validate(const Lattice& lattice, const PaddedGrid& g, const BoundPyramid& pyramid) {
  auto fail = [](const std::string& what) { throw Error("branch and bound: " + what); };
  if (lattice.headings < 1) {
    fail("lattice headings = " + std::to_string(lattice.headings) + " must be >= 1");
  }
  if (lattice.x0 < 0 || lattice.x0 > lattice.x1 || lattice.x1 >= g.width || lattice.y0 < 0 ||
      lattice.y0 > lattice.y1 || lattice.y1 >= g.height) {
    std::ostringstream m;
    m << "lattice x [" << lattice.x0 << ", " << lattice.x1 << "] y [" << lattice.y0 << ", "
      << lattice.y1 << "] must be non-empty and inside the " << g.width << " x " << g.height
      << " map";
    fail(m.str());
  }
  if (pyramid.depth() < 0 || pyramid.grid_min.size() != pyramid.arc_max.size() ||
      pyramid.pad != g.pad || pyramid.width != g.width || pyramid.height != g.height) {
    std::ostringstream m;
    m << "the bound pyramid (pad " << pyramid.pad << ", map " << pyramid.width << " x "
      << pyramid.height << ") was not built from the searched grid (pad " << g.pad << ", map "
      << g.width << " x " << g.height << ")";
    fail(m.str());
  }
}

}  // namespace

BoundPyramid make_bound_pyramid(const PaddedGrid& global, int depth) {
  if (depth < 0 || depth > kMaxDepth) {
    throw Error("bound pyramid: depth = " + std::to_string(depth) + " must lie in [0, " +
                std::to_string(kMaxDepth) + "]");
  }
  if (global.arc_view.size() != global.grid.cells.size()) {
    throw Error("bound pyramid: the padded grid's arc_view does not match its grid");
  }
  BoundPyramid p;
  p.pad = global.pad;
  p.width = global.width;
  p.height = global.height;
  p.arc_max.resize(static_cast<std::size_t>(depth) + 1);
  p.grid_min.resize(static_cast<std::size_t>(depth) + 1);
  EvidenceGrid arc = global.grid;  // arc_view with the padded geometry
  arc.cells = global.arc_view;
  for (int h = 1; h <= depth; ++h) {
    p.arc_max[static_cast<std::size_t>(h)] = max_pool(arc, 1 << h);
    p.grid_min[static_cast<std::size_t>(h)] = min_pool(global.grid, 1 << h);
  }
  return p;
}

int bound_depth_for(const Lattice& lattice) {
  const int n = std::max(lattice.x1 - lattice.x0 + 1, lattice.y1 - lattice.y0 + 1);
  int depth = 0;
  while (depth < kMaxDepth && (1 << depth) < n) ++depth;
  return depth;
}

std::vector<PlacedLocalGrid> place_headings(const Lattice& lattice, const SearchLevel& finest) {
  if (finest.global == nullptr) throw Error("branch and bound: the search level has no grid");
  const PaddedGrid& g = *finest.global;
  // Each heading's local grid, made and placed once (in parallel as finest.threads asks:
  // each heading is independent, so the result does not depend on it).
  const auto headings = static_cast<std::size_t>(std::max(lattice.headings, 0));
  std::vector<PlacedLocalGrid> placed(headings);
  std::vector<int> extents(headings, 0);
#pragma omp parallel for schedule(dynamic) num_threads(finest.threads) if (finest.threads > 1)
  for (int it = 0; it < lattice.headings; ++it) {
    const SparseLocalGrid local = finest.make_local(lattice.theta(it), Eigen::Vector2d::Zero());
    extents[static_cast<std::size_t>(it)] = local.size() > 0 ? local.extent() : 0;
    placed[static_cast<std::size_t>(it)] = place(local, g);
  }
  for (std::size_t it = 0; it < headings; ++it) {
    if (extents[it] > g.pad) {
      throw Error("branch and bound: local grid extent " + std::to_string(extents[it]) +
                  " cells (heading " + std::to_string(it) + ") exceeds the padding " +
                  std::to_string(g.pad));
    }
  }
  return placed;
}

SearchResult search_branch_and_bound(const Lattice& lattice, const SearchLevel& finest,
                                     const BoundPyramid& pyramid,
                                     const std::optional<Exclusion>& exclude) {
  if (finest.global == nullptr) throw Error("branch and bound: the search level has no grid");
  validate(lattice, *finest.global, pyramid);
  return search_branch_and_bound(lattice, *finest.global, place_headings(lattice, finest), pyramid,
                                 exclude);
}

SearchResult search_branch_and_bound(const Lattice& lattice, const PaddedGrid& g,
                                     const std::vector<PlacedLocalGrid>& placed,
                                     const BoundPyramid& pyramid,
                                     const std::optional<Exclusion>& exclude) {
  validate(lattice, g, pyramid);
  if (placed.size() != static_cast<std::size_t>(lattice.headings)) {
    throw Error("branch and bound: " + std::to_string(placed.size()) + " placed local grids for " +
                std::to_string(lattice.headings) + " headings");
  }
  SearchResult result;
  bool found = false;
  LatticePose& best = result.best;
  auto score_leaf = [&](int it, int iy, int ix) {
    if (exclude && exclude->contains(ix, iy, it)) return;
    const PlacedLocalGrid& local = placed[static_cast<std::size_t>(it)];
    const LatticePose c{ix, iy, it, score(g, local, ix, iy)};
    ++result.poses_scored;
    result.cells_scored += static_cast<long long>(local.value.size());
    result.scored.push_back(c);
    if (!found || better(c, best)) {
      best = c;
      found = true;
    }
  };
  auto make_node = [&](int it, int iy, int ix, int h) {
    const PlacedLocalGrid& local = placed[static_cast<std::size_t>(it)];
    result.cells_scored += static_cast<long long>(local.value.size());
    return Node{block_bound(pyramid, local, h, ix, iy), it, iy, ix, h};
  };
  // Could the block hold a pose better than `best`? Its poses score <= bound; an equal score
  // wins only at a lower index, and the block's lowest index is its first pose.
  auto promising = [&](const Node& n) {
    if (!found) return true;
    if (n.bound != best.score) return n.bound > best.score;
    return index_less(n.it, n.iy, n.ix, best);
  };

  // A deeper pyramid than the lattice needs only loosens the top bounds: start where one
  // block per heading covers the lattice.
  const int top = std::min(pyramid.depth(), bound_depth_for(lattice));
  if (top == 0) {  // no bound levels: the exhaustive search
    for (int it = 0; it < lattice.headings; ++it) {
      for (int iy = lattice.y0; iy <= lattice.y1; ++iy) {
        for (int ix = lattice.x0; ix <= lattice.x1; ++ix) score_leaf(it, iy, ix);
      }
    }
    return result;
  }

  // Top-level blocks of every heading, tiling the lattice from (x0, y0). Blocks and their
  // children start inside the lattice (children past x1 or y1 are dropped), so every bound
  // reads inside the padded grid and every leaf scored is a lattice pose.
  // Best first: `open` is a heap whose front is the block to open next (highest bound, then
  // lowest first pose: the order promising() tests in), so once the front cannot win, no
  // block can: stop.
  std::vector<Node> open;
  const int side = 1 << top;
  for (int it = 0; it < lattice.headings; ++it) {
    for (int iy = lattice.y0; iy <= lattice.y1; iy += side) {
      for (int ix = lattice.x0; ix <= lattice.x1; ix += side) {
        open.push_back(make_node(it, iy, ix, top));
      }
    }
  }
  auto heap_less = [](const Node& a, const Node& b) { return visit_before(b, a); };
  std::make_heap(open.begin(), open.end(), heap_less);

  while (!open.empty() && promising(open.front())) {
    std::pop_heap(open.begin(), open.end(), heap_less);
    const Node n = open.back();
    open.pop_back();
    const int half = 1 << (n.h - 1);
    const int ix_end = std::min(n.ix + 2 * half - 1, lattice.x1);
    const int iy_end = std::min(n.iy + 2 * half - 1, lattice.y1);
    for (int iy = n.iy; iy <= iy_end; iy += half) {
      for (int ix = n.ix; ix <= ix_end; ix += half) {
        if (n.h == 1) {  // children are leaves: score them exactly
          score_leaf(n.it, iy, ix);
          continue;
        }
        const int child_side = half;  // the child block's side
        if (exclude &&
            exclude->contains_block(n.it, ix, iy, std::min(ix + child_side - 1, lattice.x1),
                                    std::min(iy + child_side - 1, lattice.y1))) {
          continue;
        }
        const Node c = make_node(n.it, iy, ix, n.h - 1);
        if (!promising(c)) continue;
        open.push_back(c);
        std::push_heap(open.begin(), open.end(), heap_less);
      }
    }
  }
  return result;
}

}  // namespace gridloc
