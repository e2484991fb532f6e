#pragma once
// OctoMap files read into memory and checked before octomap sees them (internal to
// octomap_io.cpp): octomap's readers print to stderr and load truncated data silently, so
// every byte is accounted for here first and octomap is only handed data it reads cleanly.
#include <cstddef>
#include <cstdint>
#include <string>

#include "gridloc/grids/limits.hpp"

namespace gridloc::octomap_detail {

/// An OctoMap file whose header and node data have been checked.
struct OctomapFile {
  bool binary = false;          ///< a .bt (child codes only) rather than a .ot (full nodes)
  std::string id;               ///< the header's tree type ("OcTree" for a .ot)
  std::uint64_t size = 0;       ///< the header's node count (equal to the data's once checked)
  double resolution = 0.0;      ///< the header's leaf size (m), positive and finite
  std::size_t data_offset = 0;  ///< where the node data starts in the file (bytes)
  std::string data;             ///< the node data: everything after the header's `data` line
};

/// Octree depth of octomap's trees: the root is at depth 0, the leaves at depth 16 at most.
inline constexpr int kTreeDepth = 16;
/// Bytes octomap's OcTree takes per node, an upper estimate (measured: 43, for the 1.37 million
/// nodes of fr_078_tidyup.bt).
inline constexpr double kTreeBytesPerNode = 48.0;

/// Reads `path` (a regular file within limits.max_file_mb, `binary` = .bt) into memory and
/// parses its header: octomap's first line, then `id`, `size`, `res` and `data` (comment lines
/// starting with '#' allowed); a .ot must hold an OcTree; the tree of `size` nodes and the
/// file's bytes must fit limits.max_memory_mb. The data is not walked yet.
/// Throws gridloc::Error naming the file and the fault.
OctomapFile read_octomap_file(const std::string& path, bool binary, const ResourceLimits& limits);

/// Walks the node data to its end as octomap would read it (.bt: two bytes of 2-bit child codes
/// per inner node; .ot: a float log-odds and a child bit byte per node, depth first) and checks
/// that it is complete, holds exactly the header's `size` nodes, no node below the leaf level,
/// no inner .bt node without children, only finite .ot log-odds and no byte after the tree.
/// Throws gridloc::Error naming the file and the fault.
void check_octomap_data(const std::string& path, const OctomapFile& file);

}  // namespace gridloc::octomap_detail
