#include "scan_sim.hpp"

#include <algorithm>
#include <cmath>

#include "gridloc/sensors/rng.hpp"

namespace gridloc::bench {
namespace {

// synthetic_rooms() layout, in 0.05 m pixels.
constexpr double kRes = 0.05;
constexpr int kMargin = 10;  // unknown border
constexpr int kWall = 3;
constexpr int kPitchX = 100, kPitchY = 80;  // 5 m x 4 m rooms, one wall included
constexpr int kDoor = 18;
constexpr int kInset = 8;  // blocks keep 0.4 m from the walls, so doors stay open
const Pose2 kTruth{1.6, 2.3, 0.6};

/// Independent streams per room or wall: Rng is splitmix64, any distinct seeds will do.
Rng stream(std::uint64_t seed, int tag, int i, int j) {
  return Rng(seed * 1000003ull + static_cast<std::uint64_t>(tag) * 15485863ull +
             static_cast<std::uint64_t>(i) * 7919ull + static_cast<std::uint64_t>(j) * 104729ull);
}

int uniform_int(Rng& rng, int lo, int hi) {  // in [lo, hi]
  return lo + static_cast<int>(rng.uniform() * (hi - lo + 1));
}

void fill(OccupancyMap& m, int x0, int y0, int x1, int y1, CellState s) {  // inclusive
  for (int y = std::max(0, y0); y <= std::min(m.height() - 1, y1); ++y) {
    for (int x = std::max(0, x0); x <= std::min(m.width() - 1, x1); ++x) m.at(x, y) = s;
  }
}

}  // namespace

OccupancyMap synthetic_rooms(int rooms_x, int rooms_y, std::uint64_t seed) {
  GridGeometry geo;
  geo.resolution = kRes;
  geo.origin = {-kMargin * kRes, -kMargin * kRes};
  geo.width = 2 * kMargin + rooms_x * kPitchX + kWall;
  geo.height = 2 * kMargin + rooms_y * kPitchY + kWall;
  OccupancyMap m(geo, CellState::Unknown);
  const int x_end = kMargin + rooms_x * kPitchX + kWall - 1;
  const int y_end = kMargin + rooms_y * kPitchY + kWall - 1;
  fill(m, kMargin, kMargin, x_end, y_end, CellState::Free);
  // Wall lines, then a door in each wall segment between two rooms.
  for (int i = 0; i <= rooms_x; ++i) {
    const int x = kMargin + i * kPitchX;
    fill(m, x, kMargin, x + kWall - 1, y_end, CellState::Occupied);
  }
  for (int j = 0; j <= rooms_y; ++j) {
    const int y = kMargin + j * kPitchY;
    fill(m, kMargin, y, x_end, y + kWall - 1, CellState::Occupied);
  }
  const int inner_x = kPitchX - kWall, inner_y = kPitchY - kWall;
  for (int i = 0; i < rooms_x; ++i) {
    for (int j = 0; j < rooms_y; ++j) {
      const int x0 = kMargin + i * kPitchX + kWall, y0 = kMargin + j * kPitchY + kWall;
      if (i + 1 < rooms_x) {  // east wall
        Rng rng = stream(seed, 1, i, j);
        const int o = uniform_int(rng, kInset, inner_y - kDoor - kInset);
        fill(m, x0 + inner_x, y0 + o, x0 + inner_x + kWall - 1, y0 + o + kDoor - 1,
             CellState::Free);
      }
      if (j + 1 < rooms_y) {  // north wall
        Rng rng = stream(seed, 2, i, j);
        const int o = uniform_int(rng, kInset, inner_x - kDoor - kInset);
        fill(m, x0 + o, y0 + inner_y, x0 + o + kDoor - 1, y0 + inner_y + kWall - 1,
             CellState::Free);
      }
      Rng rng = stream(seed, 3, i, j);
      const Pose2 t = geo.to_grid_frame(kTruth);
      for (int b = 0; b < 3; ++b) {
        for (int attempt = 0; attempt < 100; ++attempt) {
          const int w = uniform_int(rng, 6, 20), h = uniform_int(rng, 6, 20);
          const int bx = uniform_int(rng, x0 + kInset, x0 + inner_x - kInset - w);
          const int by = uniform_int(rng, y0 + kInset, y0 + inner_y - kInset - h);
          // Keep 0.7 m around the truth pose free (it lies in room (0, 0)).
          const double cx =
              std::clamp(t.x / kRes, static_cast<double>(bx), static_cast<double>(bx + w));
          const double cy =
              std::clamp(t.y / kRes, static_cast<double>(by), static_cast<double>(by + h));
          if (std::hypot(cx - t.x / kRes, cy - t.y / kRes) < 0.7 / kRes) continue;
          fill(m, bx, by, bx + w - 1, by + h - 1, CellState::Occupied);
          break;
        }
      }
    }
  }
  return m;
}

Pose2 synthetic_rooms_truth() {
  return kTruth;
}

}  // namespace gridloc::bench
