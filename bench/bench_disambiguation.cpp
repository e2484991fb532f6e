/// Seed 002's overlay arrangement and distance_OI, timed on a synthetic office floor: a
/// corridor [0, 250] x [0, 2] with 50 rooms 4 x 4 above it (room i: [5i + 0.5, 5i + 4.5] x
/// [2.5, 6.5], 1 apart, its door [5i + 2, 5i + 3] through the corridor's wall 0.5 thick):
/// 404 vertices, self-similar under shifts by 5.
/// - BM_MakeOverlay/<k>: make_overlay() with the robot in the middle of rooms 0 .. k-1.
/// - BM_GeodesicBuild/<k>: GeodesicDistance on that overlay's OI from the start (Dijkstra).
/// - BM_GeodesicQueries/<k>: distance_to() for 500 points of that OI (uniform, seed 1), one
///   iteration = 500 queries.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>
#include <vector>

#include "gridloc/engine/disambiguation/geodesic.hpp"
#include "gridloc/engine/disambiguation/overlay.hpp"

namespace gridloc::bench {
namespace {

constexpr int kRooms = 50;
constexpr double kPitch = 5.0;

Area office_floor() {
  Polygon ring{{0, 0}, {kPitch * kRooms, 0}, {kPitch * kRooms, 2}};
  for (int i = kRooms - 1; i >= 0; --i) {  // the top wall, right to left (counter-clockwise)
    const double x = kPitch * i;
    ring.insert(ring.end(), {{x + 3, 2},
                             {x + 3, 2.5},
                             {x + 4.5, 2.5},
                             {x + 4.5, 6.5},
                             {x + 0.5, 6.5},
                             {x + 0.5, 2.5},
                             {x + 2, 2.5},
                             {x + 2, 2}});
  }
  ring.push_back({0, 2});
  return Area{ring, {}};
}

std::vector<Pose2> room_starts(int k) {
  std::vector<Pose2> starts;
  for (int i = 0; i < k; ++i) starts.push_back({kPitch * i + 2.5, 4.5, 0.0});
  return starts;
}

std::vector<Eigen::Vector2d> points_in(const Area& area, int count) {
  std::mt19937 rng(1);
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (const Eigen::Vector2d& v : area.outer) {
    x0 = std::min(x0, v.x()), x1 = std::max(x1, v.x());
    y0 = std::min(y0, v.y()), y1 = std::max(y1, v.y());
  }
  std::uniform_real_distribution<double> ux(x0, x1), uy(y0, y1);
  std::vector<Eigen::Vector2d> points;
  while (static_cast<int>(points.size()) < count) {
    const Eigen::Vector2d p(ux(rng), uy(rng));
    if (covers(area, p)) points.push_back(p);
  }
  return points;
}

void BM_MakeOverlay(benchmark::State& state) {
  const Area floor = office_floor();
  const std::vector<Pose2> starts = room_starts(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(make_overlay(floor, starts));
}
BENCHMARK(BM_MakeOverlay)->Arg(2)->Arg(10)->Arg(50)->Unit(benchmark::kMillisecond);

void BM_GeodesicBuild(benchmark::State& state) {
  const Overlay overlay =
      make_overlay(office_floor(), room_starts(static_cast<int>(state.range(0))));
  for (auto _ : state) {
    benchmark::DoNotOptimize(GeodesicDistance(overlay.oi, Eigen::Vector2d::Zero()));
  }
}
BENCHMARK(BM_GeodesicBuild)->Arg(2)->Arg(10)->Arg(50)->Unit(benchmark::kMillisecond);

void BM_GeodesicQueries(benchmark::State& state) {
  const Overlay overlay =
      make_overlay(office_floor(), room_starts(static_cast<int>(state.range(0))));
  const GeodesicDistance geodesic(overlay.oi, Eigen::Vector2d::Zero());
  const std::vector<Eigen::Vector2d> targets = points_in(overlay.oi, 500);
  for (auto _ : state) {
    double sum = 0.0;
    for (const Eigen::Vector2d& target : targets) sum += geodesic.distance_to(target);
    benchmark::DoNotOptimize(sum);
  }
}
BENCHMARK(BM_GeodesicQueries)->Arg(2)->Arg(10)->Arg(50)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace gridloc::bench
