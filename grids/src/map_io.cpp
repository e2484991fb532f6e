#include "gridloc/grids/map_io.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <set>
#include <utility>

#include "gridloc/grids/error.hpp"
#include "map_image.hpp"

namespace gridloc {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& file, const std::string& what) {
  throw Error(file + ": " + what);
}

template <typename T>
T read_scalar(const YAML::Node& node, const std::string& key, const std::string& file) {
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    fail(file, "key '" + key + "' has a value of the wrong type: '" + YAML::Dump(node) + "'");
  }
}

MapMode parse_mode(const std::string& s, const std::string& file) {
  if (s == "trinary") return MapMode::Trinary;
  if (s == "scale") return MapMode::Scale;
  if (s == "raw") return MapMode::Raw;
  fail(file, "key 'mode' must be trinary, scale or raw, not '" + s + "'");
}

/// A coordinate of the map (its resolution, origin or a corner) within max_coordinate_m.
void check_coordinate(double value, const std::string& what, const std::string& file,
                      const ResourceLimits& limits) {
  check_limit(std::abs(value), limits.max_coordinate_m, file + ": " + what, "m",
              LimitNames::coordinate_m);
}

/// The map's four corners (the image's extent at its resolution, turned by the origin's yaw)
/// within max_coordinate_m, so that every cell centre is a well-conditioned coordinate.
void check_extent(const MapMetadata& meta, int width, int height, const std::string& file,
                  const ResourceLimits& limits) {
  const double w = width * meta.resolution, h = height * meta.resolution;
  const double c = std::cos(meta.origin.theta), s = std::sin(meta.origin.theta);
  for (const auto& [dx, dy] : {std::pair{w, 0.0}, {0.0, h}, {w, h}}) {
    check_coordinate(meta.origin.x + c * dx - s * dy, "a corner of the map (x)", file, limits);
    check_coordinate(meta.origin.y + s * dx + c * dy, "a corner of the map (y)", file, limits);
  }
}

/// The map as a binary PGM (P5), north up, in map_server's greys: 0 occupied, 254 free,
/// 205 unknown. The header is the one OpenCV's imwrite wrote ("P5\n<w> <h>\n255\n").
void write_pgm(const OccupancyMap& map, const std::string& pgm_path) {
  if (map.width() < 1 || map.height() < 1) {
    fail(pgm_path, "cannot write the image: the map has no cells");  // unreadable as a PGM
  }
  const auto width = static_cast<std::size_t>(map.width());
  std::string bytes =
      "P5\n" + std::to_string(map.width()) + " " + std::to_string(map.height()) + "\n255\n";
  const std::size_t header_bytes = bytes.size();
  bytes.resize(header_bytes + width * static_cast<std::size_t>(map.height()));
  for (int iy = 0; iy < map.height(); ++iy) {
    const auto image_row = static_cast<std::size_t>(map.height() - 1 - iy);
    char* px = bytes.data() + header_bytes + image_row * width;
    for (int ix = 0; ix < map.width(); ++ix) {
      const CellState s = map.at(ix, iy);
      px[ix] = static_cast<char>(s == CellState::Occupied ? 0 : s == CellState::Free ? 254 : 205);
    }
  }
  std::ofstream out(pgm_path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) fail(pgm_path, "cannot write the image");
}

}  // namespace

[[noreturn]] static void fail_too_large(const std::string& yaml_path) {
  fail(yaml_path, "too large for a map_server YAML (it holds a few keys; at most " +
                      std::to_string(kMaxMapYamlBytes) + " bytes are read)");
}

/// The map_server keys of `text`, the YAML that `yaml_path` names in messages.
static MapMetadata parse_map_metadata(const std::string& text, const std::string& yaml_path,
                                      const ResourceLimits& limits) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    fail(yaml_path, std::string("malformed YAML: ") + e.what());
  }
  if (!root.IsMap()) fail(yaml_path, "expected a YAML mapping of map_server keys");

  static const std::set<std::string> known = {"image", "resolution",      "origin",     "negate",
                                              "mode",  "occupied_thresh", "free_thresh"};
  for (const auto& kv : root) {
    if (!kv.first.IsScalar())
      fail(yaml_path, "every key must be a plain name, found a non-scalar key");
    const auto key = kv.first.as<std::string>();
    if (!known.count(key)) fail(yaml_path, "unknown key '" + key + "'");
  }
  for (const char* required : {"image", "resolution", "origin"}) {
    if (!root[required]) fail(yaml_path, std::string("missing key '") + required + "'");
  }

  MapMetadata m;
  m.image = read_scalar<std::string>(root["image"], "image", yaml_path);
  m.resolution = read_scalar<double>(root["resolution"], "resolution", yaml_path);
  if (!(m.resolution > 0.0) || !std::isfinite(m.resolution)) {
    fail(yaml_path, "key 'resolution' must be positive, got " + std::to_string(m.resolution));
  }
  check_coordinate(m.resolution, "key 'resolution'", yaml_path, limits);
  const auto origin = root["origin"];
  if (!origin.IsSequence() || origin.size() != 3) {
    fail(yaml_path, "key 'origin' must be a list [x, y, yaw]");
  }
  m.origin = {read_scalar<double>(origin[0], "origin", yaml_path),
              read_scalar<double>(origin[1], "origin", yaml_path),
              read_scalar<double>(origin[2], "origin", yaml_path)};
  if (!std::isfinite(m.origin.x) || !std::isfinite(m.origin.y) || !std::isfinite(m.origin.theta)) {
    fail(yaml_path, "key 'origin' must hold finite numbers");
  }
  check_coordinate(m.origin.x, "key 'origin' x", yaml_path, limits);
  check_coordinate(m.origin.y, "key 'origin' y", yaml_path, limits);
  if (root["negate"]) {
    // map_server accepts 0/1 as well as true/false.
    const auto s = read_scalar<std::string>(root["negate"], "negate", yaml_path);
    if (s == "1" || s == "true" || s == "True") {
      m.negate = true;
    } else if (s == "0" || s == "false" || s == "False") {
      m.negate = false;
    } else {
      fail(yaml_path, "key 'negate' must be 0, 1, true or false, not '" + s + "'");
    }
  }
  if (root["occupied_thresh"]) {
    m.occupied_thresh = read_scalar<double>(root["occupied_thresh"], "occupied_thresh", yaml_path);
  }
  if (root["free_thresh"]) {
    m.free_thresh = read_scalar<double>(root["free_thresh"], "free_thresh", yaml_path);
  }
  if (!(m.free_thresh >= 0.0 && m.free_thresh < m.occupied_thresh && m.occupied_thresh <= 1.0)) {
    fail(yaml_path, "thresholds must satisfy 0 <= free_thresh < occupied_thresh <= 1 (got " +
                        std::to_string(m.free_thresh) + ", " + std::to_string(m.occupied_thresh) +
                        ")");
  }
  if (root["mode"])
    m.mode = parse_mode(read_scalar<std::string>(root["mode"], "mode", yaml_path), yaml_path);
  return m;
}

/// parse_map_metadata, with the conversions not caught field by field (e.g. a non-scalar
/// key) naming the file too.
static MapMetadata map_metadata_of(const std::string& text, const std::string& yaml_path,
                                   const ResourceLimits& limits) {
  try {
    return parse_map_metadata(text, yaml_path, limits);
  } catch (const YAML::Exception& e) {
    fail(yaml_path, std::string("invalid map YAML: ") + e.what());
  }
}

MapMetadata load_map_metadata(const std::string& yaml_path, const ResourceLimits& limits) {
  if (check_input_file(yaml_path, "map YAML", limits) > kMaxMapYamlBytes) {
    fail_too_large(yaml_path);
  }
  return map_metadata_of(read_input_file(yaml_path, "map YAML", limits), yaml_path, limits);
}

/// The map of `meta`, whose relative image path is relative to `image_folder`; `yaml_path`
/// names the YAML in messages.
static OccupancyMap map_of(const MapMetadata& meta, const std::string& yaml_path,
                           const fs::path& image_folder, const ResourceLimits& limits) {
  fs::path image_path = meta.image;
  if (image_path.is_relative()) image_path = image_folder / image_path;
  if (!fs::exists(image_path)) {
    fail(yaml_path, "image file '" + image_path.string() + "' not found");
  }
  const Image img = read_map_image(image_path.string(), limits);
  check_extent(meta, img.width, img.height, yaml_path, limits);

  const int channels = img.channels;
  const bool has_alpha = channels == 2 || channels == 4;
  // map_server averages the colour channels; alpha only marks unknown (not in trinary mode).
  const int colour_channels =
      (meta.mode == MapMode::Trinary || !has_alpha) ? channels : channels - 1;

  GridGeometry g;
  g.resolution = meta.resolution;
  g.origin = {meta.origin.x, meta.origin.y};
  g.yaw = meta.origin.theta;
  g.width = img.width;
  g.height = img.height;
  OccupancyMap map(g, CellState::Unknown);

  for (int r = 0; r < img.height; ++r) {
    const std::uint8_t* px = img.row(r);
    const int iy = img.height - 1 - r;  // image row 0 is the top: flip so iy grows with y
    for (int c = 0; c < img.width; ++c) {
      const std::uint8_t* p = px + static_cast<std::ptrdiff_t>(c) * channels;
      int sum = 0;
      for (int k = 0; k < colour_channels; ++k) sum += p[k];
      double v = static_cast<double>(sum) / colour_channels;
      if (meta.negate) v = 255.0 - v;
      CellState s = CellState::Unknown;
      if (meta.mode == MapMode::Raw) {
        const double occ = v / 100.0;
        if (v <= 100.0) {
          s = occ > meta.occupied_thresh ? CellState::Occupied
              : occ < meta.free_thresh   ? CellState::Free
                                         : CellState::Unknown;
        }
      } else {
        const double occ = (255.0 - v) / 255.0;
        const bool transparent = has_alpha && meta.mode == MapMode::Scale && p[channels - 1] == 0;
        if (occ > meta.occupied_thresh) {
          s = CellState::Occupied;
        } else if (occ < meta.free_thresh) {
          s = CellState::Free;
        }
        if (transparent) s = CellState::Unknown;
      }
      map.at(c, iy) = s;
    }
  }
  return map;
}

OccupancyMap load_ros_map(const std::string& yaml_path, const ResourceLimits& limits) {
  return map_of(load_map_metadata(yaml_path, limits), yaml_path, fs::path(yaml_path).parent_path(),
                limits);
}

OccupancyMap load_ros_map_text(const std::string& yaml_text, const std::string& name,
                               const std::string& image_folder, const ResourceLimits& limits) {
  check_limit(static_cast<double>(yaml_text.size()) / (1024.0 * 1024.0), limits.max_file_mb, name,
              "MB", LimitNames::file_mb);
  if (yaml_text.size() > kMaxMapYamlBytes) fail_too_large(name);
  return map_of(map_metadata_of(yaml_text, name, limits), name, image_folder, limits);
}

void save_ros_map(const OccupancyMap& map, const std::string& yaml_path) {
  const fs::path yaml(yaml_path);
  const fs::path pgm = fs::path(yaml).replace_extension(".pgm");
  write_pgm(map, pgm.string());
  std::ofstream out(yaml);
  if (!out) fail(yaml_path, "cannot write the map YAML");
  out << std::setprecision(17);  // round-trip exact doubles
  out << "image: " << pgm.filename().string() << "\n"
      << "resolution: " << map.geometry.resolution << "\n"
      << "origin: [" << map.geometry.origin.x() << ", " << map.geometry.origin.y() << ", "
      << map.geometry.yaw << "]\n"
      << "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
}

}  // namespace gridloc
