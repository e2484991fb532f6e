// Tests of concurrent use (issue 14): one estimator shared by four threads (correlation on
// sonar and laser, ICP, sectors) gives the answers one thread gets, bit for bit; four threads
// loading maps at once (ROS maps, polygon maps, OctoMap trees) get the maps one thread loads.
// cmake/sanitize.sh also runs this file under ThreadSanitizer, which reports any data race.
#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <exception>
#include <functional>
#include <latch>
#include <limits>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/icp/estimator.hpp"
#include "gridloc/engine/localizer/localizer.hpp"
#include "gridloc/engine/sectors/estimator.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/grids/octomap_io.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "gridloc/sensors/sonar_ring.hpp"
#include "gridloc/sensors/sonar_sim.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr int kThreads = 4;

/// job(k) for every k in [0, n) on each of kThreads threads started together, thread t
/// beginning at job t * n / kThreads (so different jobs also run at the same time): each
/// thread's results in job order. An exception in a thread is rethrown here.
template <class Result>
std::vector<std::vector<Result>> on_threads(int n, const std::function<Result(int)>& job) {
  std::vector<std::vector<Result>> results(kThreads, std::vector<Result>(n));
  std::vector<std::exception_ptr> errors(kThreads);
  std::latch start(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      start.arrive_and_wait();
      try {
        for (int i = 0; i < n; ++i) {
          const int k = (i + t * n / kThreads) % n;
          results[t][k] = job(k);
        }
      } catch (...) {
        errors[t] = std::current_exception();
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  return results;
}

/// The same double, bit for bit (NaN equals NaN).
bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

bool same_pose(const Pose2& a, const Pose2& b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.theta, b.theta);
}

/// Exact equality of what an estimate tells the caller (not its timing).
void expect_same_estimate(const Estimate& a, const Estimate& b, const std::string& what) {
  EXPECT_TRUE(same_pose(a.pose, b.pose)) << what;
  EXPECT_TRUE(same_pose(a.lattice_pose, b.lattice_pose)) << what;
  EXPECT_TRUE(same_bits(a.score, b.score)) << what;
  EXPECT_TRUE(same_bits(a.second_score, b.second_score)) << what;
  EXPECT_TRUE(same_bits(a.confidence, b.confidence)) << what;
  EXPECT_EQ(a.verdict, b.verdict) << what;
  EXPECT_EQ(a.on_window_edge, b.on_window_edge) << what;
  ASSERT_EQ(a.alternatives.size(), b.alternatives.size()) << what;
  for (std::size_t i = 0; i < a.alternatives.size(); ++i) {
    EXPECT_TRUE(same_pose(a.alternatives[i].pose, b.alternatives[i].pose)) << what << " alt " << i;
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(same_bits(a.covariance(r, c), b.covariance(r, c)));
  }
}

/// An observation and the window it is localized in.
struct Query {
  Observation observation;
  SearchWindow window;
};

/// Every query estimated by one thread, then by kThreads threads sharing `estimator`: the
/// same estimates.
void expect_threads_agree(const Estimator& estimator, const std::vector<Query>& queries) {
  std::vector<Estimate> reference;
  for (const Query& q : queries) reference.push_back(estimator.estimate(q.observation, q.window));
  const auto results = on_threads<Estimate>(static_cast<int>(queries.size()), [&](int k) {
    return estimator.estimate(queries[k].observation, queries[k].window);
  });
  for (int t = 0; t < kThreads; ++t) {
    for (std::size_t k = 0; k < queries.size(); ++k) {
      expect_same_estimate(
          results[t][k], reference[k],
          estimator.name() + " thread " + std::to_string(t) + " query " + std::to_string(k));
    }
  }
}

/// A window around `truth`, the prior off by (0.3 m, -0.2 m, 10 deg).
SearchWindow window_near(const Pose2& truth) {
  SearchWindow w;
  w.center = {truth.x + 0.3, truth.y - 0.2, truth.theta + deg2rad(10.0)};
  return w;
}

const std::vector<Pose2>& room_poses() {
  static const std::vector<Pose2> poses{
      {2.4, 2.3, -0.35}, {1.5, 1.5, 1.0}, {3.2, 2.0, 2.5}, {2.0, 3.0, -2.0}};
  return poses;
}

TEST(ConcurrentEstimates, CorrelationOnSonarRings) {
  const OccupancyMap map = load_ros_map(test::map_path("room_furnished"));
  const SonarRing ring = load_sonar_ring(test::ring_path());
  std::vector<Query> queries;
  for (const Pose2& truth : room_poses()) {
    queries.push_back({Observation{simulate_sonar(map, ring, truth)}, window_near(truth)});
  }
  for (int threads : {1, 2}) {  // each call's own search threads, as well
    CorrelationOptions options;
    options.threads = threads;
    options.poses_per_thread = 0.0;  // two threads even on these small windows
    const CorrelationEstimator estimator(map, ring, options);
    expect_threads_agree(estimator, queries);
  }
}

TEST(ConcurrentEstimates, CorrelationOnLaserScans) {
  const OccupancyMap map = load_ros_map(test::map_path("apartment_small"));
  CorrelationOptions options;
  options.reach_m = 8.0;
  const CorrelationEstimator estimator(map, options);
  std::vector<Query> queries;
  std::uint64_t seed = 1;
  for (const Pose2 truth : {Pose2{2.0, 2.0, 0.3}, Pose2{6.5, 4.5, -2.0}, Pose2{8.0, 1.5, 1.2}}) {
    Observation obs;
    obs.scan = simulate_scan(map, truth, 180, 8.0, 0.01, seed++);
    queries.push_back({obs, window_near(truth)});
  }
  expect_threads_agree(estimator, queries);
}

TEST(ConcurrentEstimates, IcpOnLaserScans) {
  const OccupancyMap map = load_ros_map(test::map_path("apartment_small"));
  const IcpEstimator icp(map);
  std::vector<Query> queries;
  std::uint64_t seed = 7;
  for (const Pose2 truth : {Pose2{2.0, 2.0, 0.3}, Pose2{6.5, 4.5, -2.0}, Pose2{8.0, 1.5, 1.2}}) {
    Observation obs;
    obs.scan = simulate_scan(map, truth, 360, 8.0, 0.01, seed++);
    SearchWindow w;
    w.center = {truth.x + 0.15, truth.y - 0.12, truth.theta + 0.1};
    queries.push_back({obs, w});
  }
  expect_threads_agree(icp, queries);
}

TEST(ConcurrentEstimates, SectorsOnAnLShapedRoom) {
  const PolygonMap room = make_polygon_map({{0, 0}, {7, 0}, {7, 3}, {3, 3}, {3, 6}, {0, 6}}, {});
  const SectorEstimator sectors(room);
  SearchWindow everywhere;
  everywhere.center = {3.5, 3.0, 0.0};
  everywhere.half_xy = 4.0;
  everywhere.half_theta = std::numbers::pi;
  std::vector<Query> queries;
  for (const Pose2 truth : {Pose2{1.5, 1.5, 0.3}, Pose2{5.5, 1.2, -1.0}, Pose2{1.2, 4.8, 2.2}}) {
    queries.push_back({Observation{{}, polygon_scan(room, truth, 360, 20.0)}, everywhere});
  }
  expect_threads_agree(sectors, queries);
}

/// A drive through room_l from a prior, odometry without error, one firing per step: what
/// the writer hands a Localizer.
struct Drive {
  std::vector<Pose2> odometry;
  std::vector<std::vector<double>> firings;  ///< the driver's view: no echo is +inf
};

Drive drive_through(const OccupancyMap& map, const SonarRing& ring) {
  Drive d;
  const Pose2 start{1.5, 1.5, 0.3};
  for (int k = 0; k <= 4; ++k) {
    const Pose2 step{0.25 * k, 0.0, 0.05 * k};
    d.odometry.push_back(step);
    std::vector<double> ranges = simulate_sonar(map, ring, compose(start, step));
    for (std::size_t i = 0; i < ranges.size(); ++i) {
      if (ranges[i] >= ring.sonars[i].max_range) {
        ranges[i] = std::numeric_limits<double>::infinity();
      }
    }
    d.firings.push_back(ranges);
  }
  return d;
}

/// The writer's side of the drive on `localizer`: the estimate after each firing.
std::vector<Estimate> write_drive(Localizer& localizer, const Drive& d) {
  localizer.set_prior({1.6, 1.4, 0.4}, Eigen::Vector3d(0.04, 0.04, 0.03).asDiagonal());
  std::vector<Estimate> after;
  for (std::size_t k = 0; k < d.firings.size(); ++k) {
    localizer.add_odometry(d.odometry[k]);
    localizer.add_observation(0.5 * static_cast<double>(k), d.firings[k]);
    after.push_back(localizer.estimate());
  }
  return after;
}

// The Localizer's contract: one writer and any number of readers at the same time. The
// writer gets the estimates a lone writer gets; each read is one of them.
TEST(ConcurrentLocalizer, OneWriterAndThreeReaders) {
  const OccupancyMap map = load_ros_map(test::map_path("room_l"));
  const SonarRing ring = load_sonar_ring(test::ring_path());
  const Drive drive = drive_through(map, ring);
  Localizer alone(map, ring);
  const std::vector<Estimate> reference = write_drive(alone, drive);

  Localizer shared(map, ring);
  std::atomic<bool> writing{true};
  std::vector<Estimate> written;
  std::vector<std::vector<Estimate>> read(kThreads - 1);
  std::vector<std::thread> readers;
  for (int t = 0; t + 1 < kThreads; ++t) {
    readers.emplace_back([&, t] {
      while (writing.load()) {
        try {
          const Estimate e = shared.estimate();
          if (read[t].empty() || !same_pose(read[t].back().pose, e.pose)) read[t].push_back(e);
        } catch (const Error&) {  // no estimate yet
        }
        // A pause between reads: glibc's rwlock prefers readers, spinning ones starve the writer.
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
    });
  }
  written = write_drive(shared, drive);
  writing.store(false);
  for (std::thread& reader : readers) reader.join();

  ASSERT_EQ(written.size(), reference.size());
  for (std::size_t k = 0; k < written.size(); ++k) {
    expect_same_estimate(written[k], reference[k], "firing " + std::to_string(k));
  }
  for (int t = 0; t + 1 < kThreads; ++t) {
    for (const Estimate& e : read[t]) {
      bool known = false;
      for (const Estimate& w : written) known = known || same_pose(e.pose, w.pose);
      EXPECT_TRUE(known) << "reader " << t << " read a pose the writer never published";
    }
  }
}

/// Exact equality of two occupancy maps: geometry and every cell.
void expect_same_map(const OccupancyMap& a, const OccupancyMap& b, const std::string& what) {
  EXPECT_EQ(a.geometry.width, b.geometry.width) << what;
  EXPECT_EQ(a.geometry.height, b.geometry.height) << what;
  EXPECT_TRUE(same_bits(a.geometry.resolution, b.geometry.resolution)) << what;
  EXPECT_TRUE(same_bits(a.geometry.origin.x(), b.geometry.origin.x())) << what;
  EXPECT_TRUE(same_bits(a.geometry.origin.y(), b.geometry.origin.y())) << what;
  EXPECT_TRUE(same_bits(a.geometry.yaw, b.geometry.yaw)) << what;
  EXPECT_TRUE(a.cells == b.cells) << what;
}

/// kThreads threads each loading every file `rounds` times get what one thread loads.
void expect_concurrent_loads_agree(const std::vector<std::string>& paths, int rounds,
                                   const std::function<OccupancyMap(const std::string&)>& load) {
  std::vector<OccupancyMap> reference;
  for (const std::string& path : paths) reference.push_back(load(path));
  const int n = static_cast<int>(paths.size()) * rounds;
  const auto results =
      on_threads<OccupancyMap>(n, [&](int k) { return load(paths[k % paths.size()]); });
  for (int t = 0; t < kThreads; ++t) {
    for (int k = 0; k < n; ++k) {
      expect_same_map(results[t][k], reference[k % paths.size()],
                      paths[k % paths.size()] + " thread " + std::to_string(t));
    }
  }
}

TEST(ConcurrentMapLoads, RosMapsAndPolygonMaps) {
  std::vector<std::string> ros;
  for (const char* name :
       {"room_rect", "room_l", "room_furnished", "room_symmetric", "apartment_small"}) {
    ros.push_back(test::map_path(name));
  }
  expect_concurrent_loads_agree(ros, 4, [](const std::string& path) { return load_ros_map(path); });
  std::vector<std::string> polygons;
  for (const char* name : {"room_rect", "room_l", "room_furnished", "office"}) {
    polygons.push_back(test::maps_dir() + "/polygons/" + name + ".yaml");
  }
  expect_concurrent_loads_agree(polygons, 4, [](const std::string& path) {
    return rasterize_polygon_map(load_polygon_map(path), 0.1);
  });
}

/// A small tree (0.1 m leaves): a 1 m x 1 m room of free space walled on two sides, one
/// update per leaf, written with octomap's API as .bt and .ot.
void write_trees(const std::string& bt, const std::string& ot) {
  octomap::OcTree tree(0.1);
  for (int x = -2; x < 12; ++x) {
    for (int y = -2; y < 12; ++y) {
      for (int z = 1; z < 6; ++z) {
        const bool wall = x == 10 || y == 10;
        tree.updateNode(octomap::point3d(static_cast<float>((x + 0.5) * 0.1),
                                         static_cast<float>((y + 0.5) * 0.1),
                                         static_cast<float>((z + 0.5) * 0.1)),
                        wall);
      }
    }
  }
  ASSERT_TRUE(tree.writeBinary(bt));
  ASSERT_TRUE(tree.write(ot));
}

// load_octomap captured octomap's messages by swapping the process-wide std::cerr buffer,
// which crashed concurrent loads (issue 14, item 1): kept apart so its result shows alone.
TEST(ConcurrentOctomapLoads, BinaryAndFullTrees) {
  const test::TempDir dir;
  const std::string bt = (dir.path() / "room.bt").string();
  const std::string ot = (dir.path() / "room.ot").string();
  write_trees(bt, ot);
  expect_concurrent_loads_agree({bt, ot}, 25,
                                [](const std::string& path) { return load_octomap(path); });
}

}  // namespace
}  // namespace gridloc
