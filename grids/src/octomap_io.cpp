#include "gridloc/grids/octomap_io.hpp"

#include <octomap/OcTree.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <new>
#include <sstream>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/option_checks.hpp"
#include "octomap_file.hpp"

namespace gridloc {
namespace {

namespace fs = std::filesystem;

// Tolerance, in leaf or cell units, for comparing voxel faces with band edges and cell edges
// (voxel faces are integer multiples of the leaf size; band edges are decimal numbers).
constexpr double kEps = 1e-6;

[[noreturn]] void fail(const std::string& file, const std::string& what) {
  throw Error(file + ": " + what);
}

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

void check_slice(const std::string& path, const OctomapSlice& s) {
  if (std::isnan(s.z_min) || std::isnan(s.z_max)) {
    fail(path, "OctoMap band z_min/z_max must be numbers, got z_min " + message_number(s.z_min) +
                   ", z_max " + message_number(s.z_max));
  }
  if (!(s.z_min < s.z_max)) {
    fail(path, "OctoMap band: z_min (" + message_number(s.z_min) + " m) must be below z_max (" +
                   message_number(s.z_max) + " m)");
  }
  if (!(s.resolution >= 0.0) || !std::isfinite(s.resolution)) {
    fail(path, "OctoMap slice resolution must be positive when given (0 = the tree's), got " +
                   message_number(s.resolution));
  }
}

// octomap's own data readers on the checked bytes, as OcTree::readBinary and
// AbstractOcTree::read call them after the header (which is parsed in octomap_file.cpp, so
// that octomap's header warnings and errors, printed to stderr, are never reached).
std::unique_ptr<octomap::OcTree> tree_of(const std::string& path,
                                         octomap_detail::OctomapFile file) {
  auto tree = std::make_unique<octomap::OcTree>(file.resolution);
  std::istringstream in(std::move(file.data));
  try {
    if (file.binary) {
      tree->readBinaryData(in);
    } else {
      tree->readData(in);
    }
  } catch (const std::bad_alloc&) {
    fail(path, "not enough memory for the OctoMap tree of " + std::to_string(file.size) +
                   " nodes (--max-memory-mb limits the estimate)");
  }
  if (tree->size() != file.size) {
    fail(path, "octomap read " + std::to_string(tree->size()) + " nodes of the checked " +
                   std::to_string(file.size));
  }
  return tree;
}

// Reads the tree; its kind is told by the extension, and the file is checked whole before
// octomap reads it, so that a wrong file gets our message rather than octomap's console output
// or a tree silently cut short.
std::unique_ptr<octomap::OcTree> read_tree(const std::string& path, const ResourceLimits& limits) {
  const std::string ext = lower_extension(path);
  if (ext != ".bt" && ext != ".ot") {
    fail(path,
         "an OctoMap file must end in .bt (binary tree) or .ot (full tree), not '" + ext + "'");
  }
  const bool binary = ext == ".bt";
  octomap_detail::OctomapFile file = octomap_detail::read_octomap_file(path, binary, limits);
  octomap_detail::check_octomap_data(path, file);
  if (file.size == 0) fail(path, "the OctoMap tree is empty");
  return tree_of(path, std::move(file));
}

// A leaf voxel as a box of leaf-index units: [lo, hi) per axis, faces at index x resolution.
struct VoxelBox {
  std::array<std::int64_t, 3> lo{}, hi{};
};

template <typename LeafIterator>
VoxelBox box_of(const LeafIterator& it, double resolution) {
  // A pruned leaf of depth d spans 2^(16 - d) leaves; its centre is a float, so snap the
  // faces to the leaf lattice.
  const double half = 0.5 * static_cast<double>(std::llround(it.getSize() / resolution));
  const octomap::point3d c = it.getCoordinate();
  VoxelBox b;
  for (int i = 0; i < 3; ++i) {
    const double centre = static_cast<double>(c(i)) / resolution;
    b.lo[i] = std::llround(centre - half);
    b.hi[i] = std::llround(centre + half);
  }
  return b;
}

}  // namespace

bool is_octomap_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".bt" || ext == ".ot";
}

OccupancyMap load_octomap(const std::string& path, const OctomapSlice& slice,
                          const ResourceLimits& limits) {
  limits.validate();
  check_slice(path, slice);
  const std::unique_ptr<octomap::OcTree> tree = read_tree(path, limits);
  const double res = tree->getResolution();

  // Pass 1: the bounding box of every known voxel, and whether any overlaps the band.
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
  std::array<std::int64_t, 3> lo{kMax, kMax, kMax}, hi{-kMax, -kMax, -kMax};
  const double band_lo = slice.z_min / res, band_hi = slice.z_max / res;  // leaf units
  const auto in_band = [&](const VoxelBox& b) {
    return static_cast<double>(b.lo[2])<band_hi - kEps&& static_cast<double>(b.hi[2])> band_lo +
           kEps;
  };
  bool any_in_band = false;
  for (auto it = tree->begin_leafs(), end = tree->end_leafs(); it != end; ++it) {
    const VoxelBox b = box_of(it, res);
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], b.lo[i]);
      hi[i] = std::max(hi[i], b.hi[i]);
    }
    any_in_band = any_in_band || in_band(b);
  }
  if (!any_in_band) {
    fail(path, "no known voxel overlaps the band z in [" + message_number(slice.z_min) + ", " +
                   message_number(slice.z_max) + "] m (the tree's voxels span z in [" +
                   message_number(static_cast<double>(lo[2]) * res) + ", " +
                   message_number(static_cast<double>(hi[2]) * res) + "] m)");
  }

  // The 2-D geometry: the x-y box, cut into cells of the requested side.
  const double cell = slice.resolution > 0.0 ? slice.resolution : res;
  const double scale = res / cell;  // cells per leaf unit
  GridGeometry g;
  g.resolution = cell;
  g.origin = {static_cast<double>(lo[0]) * res, static_cast<double>(lo[1]) * res};
  g.yaw = 0.0;
  const double w = std::max(1.0, std::ceil(static_cast<double>(hi[0] - lo[0]) * scale - kEps));
  const double h = std::max(1.0, std::ceil(static_cast<double>(hi[1] - lo[1]) * scale - kEps));
  check_grid_cells(w, h, limits,
                   path + ": the OctoMap's 2-D map at " + message_number(cell) + " m");
  g.width = static_cast<int>(w);
  g.height = static_cast<int>(h);
  OccupancyMap map(g, CellState::Unknown);

  // Cells [first, last) covered by the leaf-unit interval [a, b) along one axis.
  const auto cells_of = [&](std::int64_t a, std::int64_t b, std::int64_t origin, int size) {
    int first = static_cast<int>(std::floor(static_cast<double>(a - origin) * scale + kEps));
    int last = static_cast<int>(std::ceil(static_cast<double>(b - origin) * scale - kEps));
    last = std::max(last, first + 1);
    return std::array<int, 2>{std::clamp(first, 0, size), std::clamp(last, 0, size)};
  };

  // Pass 2: paint the band's voxels; occupied wins over free, free over unknown.
  for (auto it = tree->begin_leafs(), end = tree->end_leafs(); it != end; ++it) {
    const VoxelBox b = box_of(it, res);
    if (!in_band(b)) continue;
    const bool occupied = tree->isNodeOccupied(*it);
    const auto xs = cells_of(b.lo[0], b.hi[0], lo[0], g.width);
    const auto ys = cells_of(b.lo[1], b.hi[1], lo[1], g.height);
    for (int iy = ys[0]; iy < ys[1]; ++iy) {
      CellState* row = map.row(iy);
      for (int ix = xs[0]; ix < xs[1]; ++ix) {
        if (occupied) {
          row[ix] = CellState::Occupied;
        } else if (row[ix] == CellState::Unknown) {
          row[ix] = CellState::Free;
        }
      }
    }
  }
  return map;
}

}  // namespace gridloc
