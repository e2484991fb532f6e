#pragma once
/// Loading ROS map_server maps (YAML + PGM/PNG image).
#include <cstdint>
#include <string>

#include "gridloc/grids/grid.hpp"
#include "gridloc/grids/limits.hpp"

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

/// The largest map_server YAML file read (bytes): it holds a few keys, and YAML parsing takes
/// about 65 bytes of memory per byte of the file, so a larger one is refused before parsing.
inline constexpr std::uintmax_t kMaxMapYamlBytes = 1 << 20;

/// Reads and validates a map_server YAML file; throws gridloc::Error naming the file and key.
/// The file is checked first (check_input_file: missing, a directory, over max_file_mb, over
/// kMaxMapYamlBytes); the
/// resolution and each origin coordinate must not exceed limits.max_coordinate_m.
MapMetadata load_map_metadata(const std::string& yaml_path, const ResourceLimits& limits = {});

/// Loads a map_server map. The image's rows are flipped so that row index grows with world y.
/// Pixels are classified as map_server does: occupancy p = (255 - v) / 255 (v averaged over
/// colour channels, negated if asked); p > occupied_thresh is Occupied, p < free_thresh Free,
/// otherwise Unknown; a transparent pixel is Unknown. In raw mode v itself is the occupancy in
/// percent (0..100, anything above 100 Unknown), compared with the thresholds.
///
/// The image is a PGM/PPM (P2, P3, P5, P6; a maxval below 255 is scaled to 0..255 as
/// map_server does, 16-bit images are rejected) or a PNG of 8 or fewer bits per sample. Its
/// declared size is checked against `limits` (max_cells, and max_memory_mb for the file, the
/// decoded image and the map) before it is decoded, and the map's corners against
/// max_coordinate_m. A damaged, truncated or oversized image is a gridloc::Error naming the
/// file; nothing is printed.
OccupancyMap load_ros_map(const std::string& yaml_path, const ResourceLimits& limits = {});

/// load_ros_map for a map_server YAML that is not a file of its own (the gridloc CLI's
/// standard input): `yaml_text` is the YAML, `name` stands for it in messages, and a relative
/// `image:` is resolved against `image_folder`. The text is held to kMaxMapYamlBytes and
/// max_file_mb; everything else is checked as load_ros_map checks it.
OccupancyMap load_ros_map_text(const std::string& yaml_text, const std::string& name,
                               const std::string& image_folder, const ResourceLimits& limits = {});

/// Writes a map as map_server YAML + PGM (trinary: 0 occupied, 254 free, 205 unknown).
void save_ros_map(const OccupancyMap& map, const std::string& yaml_path);

}  // namespace gridloc
