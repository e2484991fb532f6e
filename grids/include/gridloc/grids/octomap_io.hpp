#pragma once
/// Importing OctoMap trees (`.bt`, `.ot`) as 2-D occupancy maps: the slice of the 3-D map at
/// the sonars' height, so that a 3-D map serves the same engine as a map_server map.
#include <string>

#include "gridloc/grids/grid.hpp"
#include "gridloc/grids/limits.hpp"

namespace gridloc {

/// Which part of an OctoMap becomes the 2-D map. Heights in metres, in the tree's frame
/// (z up, 0 at the floor for a map made by the robot itself).
///
/// The default band suits the wheelchair's sonar ring, whose cones lie roughly between knee
/// and seat height: starting at 0.1 m leaves out the floor, door sills, rugs and the ground
/// noise of the 3-D sensor that made the tree, which the horizontal cones never see; ending at
/// 0.6 m leaves out what the cones pass under — table tops, window sills, shelves, a
/// bed's overhang — which would otherwise appear as walls the sonars cannot echo from.
struct OctomapSlice {
  double z_min = 0.1;       ///< lower edge of the band (m)
  double z_max = 0.6;       ///< upper edge of the band (m); must exceed z_min
  double resolution = 0.0;  ///< 2-D cell side (m); 0 = the tree's leaf size
};

/// Loads an OctoMap OcTree and projects the voxels overlapping the band [z_min, z_max] onto a
/// 2-D map. The file (a regular file) is read into memory and checked whole before octomap
/// reads it: the header octomap writes (its first line, then `id`, `size`, `res`, `data`;
/// comment lines starting with '#' allowed, any other keyword refused) and the node data walked
/// to its end: a `.bt` as octomap's readBinaryData reads it (two bytes of child codes per inner
/// node), a `.ot` as its readData does (a float log-odds and a child byte per node; the tree
/// must be an OcTree: ColorOcTree and others are refused). octomap's data readers then build
/// the tree from the checked bytes, so none of its messages reach stderr and the loader
/// touches no process-wide state: concurrent calls are safe.
///
/// A cell is Occupied if an occupied leaf voxel overlapping the band covers part of it; Free if
/// it is not Occupied and a free leaf voxel overlapping the band covers part of it; Unknown
/// otherwise. Occupied/free is the tree's own classification (isNodeOccupied). A voxel merely
/// touching the band at a face does not overlap it. Pruned (larger) leaves cover every cell
/// under them. The map spans the x-y bounding box of all the tree's known voxels (in the band
/// or not), with its origin at the box's lower-left corner and yaw 0; with the tree's
/// resolution its cells are exactly the voxel columns.
///
/// Within `limits`: the file's size (max_file_mb), the tree's memory, estimated from the
/// header's node count before octomap allocates it (max_memory_mb; octomap takes about 45
/// bytes per node: a room of 1.4 million nodes at 5 cm, 60 MB), the 2-D map's cells (max_cells).
///
/// Throws gridloc::Error naming the file for a missing file, a directory or other non-regular
/// file, a file, tree or map over its limit, an extension other than .bt/.ot, a header that is not
/// octomap's (a wrong first line; a missing, repeated or unknown keyword; a size that is not a
/// whole number; a res that is not a leaf size from 1e-6 to 1e6 m), data that ends before the tree
/// does, holds another number of nodes than the header's size, reaches below the leaf level, has a
/// .bt inner node without children or a .ot log-odds that is not finite, bytes after the end of the
/// tree (refused, as octomap's writers leave none), a tree that is not an OcTree, an empty tree, a
/// bad band (z_min >= z_max, NaN), a given resolution <= 0 or NaN, or a band that holds no known
/// voxel.
OccupancyMap load_octomap(const std::string& path, const OctomapSlice& slice = {},
                          const ResourceLimits& limits = {});

/// True if `path` names an OctoMap file by its extension (.bt or .ot, any case).
bool is_octomap_path(const std::string& path);

}  // namespace gridloc
