#pragma once
/// Importing OctoMap trees (`.bt`, `.ot`) as 2-D occupancy maps: the slice of the 3-D map at
/// the sonars' height, so that a 3-D map serves the same engine as a map_server map.
#include <string>

#include "gridloc/grids/grid.hpp"

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
/// 2-D map. `.bt` files are read with OcTree::readBinary, `.ot` files with
/// AbstractOcTree::read (the tree must be an OcTree; ColorOcTree and others are refused).
///
/// A cell is Occupied if an occupied leaf voxel overlapping the band covers part of it; Free if
/// it is not Occupied and a free leaf voxel overlapping the band covers part of it; Unknown
/// otherwise. Occupied/free is the tree's own classification (isNodeOccupied). A voxel merely
/// touching the band at a face does not overlap it. Pruned (larger) leaves cover every cell
/// under them. The map spans the x-y bounding box of all the tree's known voxels (in the band
/// or not), with its origin at the box's lower-left corner and yaw 0; with the tree's
/// resolution its cells are exactly the voxel columns.
///
/// Throws gridloc::Error naming the file for a missing or unreadable file, an extension other
/// than .bt/.ot, a tree that is not an OcTree, an empty tree, a bad band (z_min >= z_max, NaN),
/// a given resolution <= 0 or NaN, a band that holds no known voxel, or a map too large.
OccupancyMap load_octomap(const std::string& path, const OctomapSlice& slice = {});

/// True if `path` names an OctoMap file by its extension (.bt or .ot, any case).
bool is_octomap_path(const std::string& path);

}  // namespace gridloc
