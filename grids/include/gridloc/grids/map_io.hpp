#pragma once
/// Loading ROS map_server maps (YAML + PGM/PNG image).
#include <string>

#include "gridloc/grids/grid.hpp"

namespace gridloc {

enum class MapMode { Trinary, Scale, Raw };

/// The keys of a map_server YAML file, with map_server's defaults.
struct MapMetadata {
  std::string image;        ///< path of the image, relative to the YAML file's folder
  double resolution = 0.0;  ///< metres per pixel
  Pose2 origin;             ///< world pose of the lower-left pixel's corner (x, y, yaw)
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  MapMode mode = MapMode::Trinary;
};

/// Reads and validates a map_server YAML file; throws gridloc::Error naming the file and key.
MapMetadata load_map_metadata(const std::string& yaml_path);

/// Loads a map_server map. The image's rows are flipped so that row index grows with world y.
/// Pixels are classified as map_server does: occupancy p = (255 - v) / 255 (v averaged over
/// colour channels, negated if asked); p > occupied_thresh is Occupied, p < free_thresh Free,
/// otherwise Unknown; a transparent pixel is Unknown. In raw mode v itself is the occupancy in
/// percent (0..100, anything above 100 Unknown), compared with the thresholds.
OccupancyMap load_ros_map(const std::string& yaml_path);

/// Writes a map as map_server YAML + PGM (trinary: 0 occupied, 254 free, 205 unknown).
void save_ros_map(const OccupancyMap& map, const std::string& yaml_path);

}  // namespace gridloc
