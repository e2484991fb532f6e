// Tests of engine/src/evaluation/office_environments.cpp: seed 002 §V's random offices.
#include "gridloc/engine/evaluation/office_environments.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "gridloc/sensors/rng.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using Step = std::pair<long, long>;

/// The ring's edges as integer steps (the coordinates are integers).
std::vector<Step> edge_steps(const Polygon& ring) {
  std::vector<Step> steps;
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const Eigen::Vector2d d = ring[(k + 1) % ring.size()] - ring[k];
    steps.emplace_back(std::lround(d.x()), std::lround(d.y()));
  }
  return steps;
}

/// The number of windows of `length` consecutive edges that the ring repeats elsewhere, not
/// overlapping the first occurrence: pieces of wall congruent under translation.
int repeated_windows(const Polygon& ring, std::size_t length) {
  const std::vector<Step> steps = edge_steps(ring);
  const std::size_t n = steps.size();
  std::map<std::vector<Step>, std::size_t> first;
  int repeats = 0;
  for (std::size_t k = 0; k < n; ++k) {
    std::vector<Step> window;
    for (std::size_t j = 0; j < length; ++j) window.push_back(steps[(k + j) % n]);
    const auto [it, inserted] = first.emplace(window, k);
    if (!inserted && k - it->second >= length && it->second + n - k >= length) ++repeats;
  }
  return repeats;
}

/// The ring is rectilinear with integer vertices, turning at every vertex.
void expect_rectilinear_integer(const Polygon& ring) {
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const Eigen::Vector2d& v = ring[k];
    ASSERT_EQ(v.x(), std::round(v.x()));
    ASSERT_EQ(v.y(), std::round(v.y()));
    const Eigen::Vector2d in = v - ring[(k + ring.size() - 1) % ring.size()];
    const Eigen::Vector2d out = ring[(k + 1) % ring.size()] - v;
    ASSERT_TRUE((in.x() == 0.0) != (in.y() == 0.0)) << "edge into vertex " << k;
    ASSERT_EQ(in.dot(out), 0.0) << "no turn at vertex " << k;
  }
}

TEST(OfficeEnvironments, TwentySeedsAreLegalSimpleRectilinearMaps) {
  // seed 002 §V: twenty offices of about 400 vertices each.
  std::vector<double> counts;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const PolygonMap office = random_office(seed);
    EXPECT_TRUE(office.obstacles.empty()) << "seed " << seed;
    EXPECT_EQ(office.resolution, 0.05);
    EXPECT_NO_THROW(make_polygon_map(office.boundary, {}, office.resolution));
    EXPECT_GT(signed_area2(office.boundary), 0.0);  // counter-clockwise
    expect_rectilinear_integer(office.boundary);
    double lowest_x = 1e9, lowest_y = 1e9;
    for (const auto& v : office.boundary) {
      lowest_x = std::min(lowest_x, v.x());
      lowest_y = std::min(lowest_y, v.y());
    }
    EXPECT_EQ(lowest_x, 0.0);
    EXPECT_EQ(lowest_y, 0.0);
    const double n = static_cast<double>(office.boundary.size());
    EXPECT_GE(n, 0.75 * 400) << "seed " << seed;
    EXPECT_LE(n, 1.25 * 400) << "seed " << seed;
    counts.push_back(n);
  }
  double sum = 0.0;
  for (double n : counts) sum += n;
  RecordProperty("mean_vertices", std::to_string(sum / 20.0));
  RecordProperty("min_vertices", std::to_string(*std::min_element(counts.begin(), counts.end())));
  RecordProperty("max_vertices", std::to_string(*std::max_element(counts.begin(), counts.end())));
}

TEST(OfficeEnvironments, SameSeedSameMapOtherSeedsDiffer) {
  std::vector<Polygon> offices;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    offices.push_back(random_office(seed).boundary);
    EXPECT_EQ(random_office(seed).boundary, offices.back()) << "seed " << seed;
  }
  for (std::size_t a = 0; a < offices.size(); ++a) {
    for (std::size_t b = a + 1; b < offices.size(); ++b) {
      EXPECT_NE(offices[a], offices[b]) << "seeds " << a + 1 << " and " << b + 1;
    }
  }
}

TEST(OfficeEnvironments, RoomsRepeat) {
  // A room with its door is about 8 edges; a repeated room repeats them (self-similarity).
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    EXPECT_GE(repeated_windows(random_office(seed).boundary, 8), 2) << "seed " << seed;
  }
  // Without repetition the rooms still come from few sizes, but the long windows rarely match.
  OfficeOptions unique;
  unique.repeat_probability = 0.0;
  int with = 0, without = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    with += repeated_windows(random_office(seed).boundary, 12);
    without += repeated_windows(random_office(seed, unique).boundary, 12);
  }
  EXPECT_GT(with, 2 * without);
}

TEST(OfficeEnvironments, AreaIsTheCellsInside) {
  // Brute force: the ring encloses whole cells only, so its area is the number of cell centres
  // inside it.
  OfficeOptions small;
  small.target_vertices = 80;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const Polygon ring = random_office(seed, small).boundary;
    double width = 0.0, height = 0.0;
    for (const auto& v : ring) {
      width = std::max(width, v.x());
      height = std::max(height, v.y());
    }
    int inside_cells = 0;
    for (int x = 0; x < static_cast<int>(width); ++x) {
      for (int y = 0; y < static_cast<int>(height); ++y) {
        inside_cells += inside(ring, {x + 0.5, y + 0.5}) ? 1 : 0;
      }
    }
    EXPECT_EQ(signed_area2(ring), 2.0 * inside_cells) << "seed " << seed;
  }
}

TEST(OfficeEnvironments, RandomOptionsGiveLegalMapsNearTheTarget) {
  Rng rng(7);
  for (int trial = 0; trial < 12; ++trial) {
    OfficeOptions o;
    o.target_vertices = 40 + static_cast<int>(rng.next() % 200);
    o.min_room_width = 2 + static_cast<int>(rng.next() % 3);
    o.max_room_width = o.min_room_width + static_cast<int>(rng.next() % 4);
    o.min_room_depth = 1 + static_cast<int>(rng.next() % 3);
    o.max_room_depth = o.min_room_depth + static_cast<int>(rng.next() % 4);
    o.corridor_width = 1 + static_cast<int>(rng.next() % 2);
    o.door_width = 1 + static_cast<int>(rng.next() % 2);
    o.repeat_probability = rng.uniform();
    o.notch_probability = rng.uniform();
    const PolygonMap office = random_office(100 + trial, o);  // checked by make_polygon_map
    expect_rectilinear_integer(office.boundary);
    const int n = static_cast<int>(office.boundary.size());
    EXPECT_GE(n, o.target_vertices) << "trial " << trial;
    EXPECT_LE(n, o.target_vertices + 24) << "trial " << trial;  // one piece's worth
  }
}

TEST(OfficeEnvironments, BundledMapIsSeedOne) {
  // maps/polygons/office_rooms.yaml is save_polygon_map(random_office(1)): the same vertices
  // here show the generator gives the same office on this platform (and has not changed).
  const PolygonMap bundled = load_polygon_map(test::maps_dir() + "/polygons/office_rooms.yaml");
  const PolygonMap office = random_office(1);
  EXPECT_EQ(bundled.boundary, office.boundary)
      << "regenerate the file with save_polygon_map(random_office(1), path, comment)";
  EXPECT_EQ(bundled.resolution, office.resolution);
  EXPECT_TRUE(bundled.obstacles.empty());
}

TEST(OfficeEnvironments, BadOptionsAreNamed) {
  const auto expect_bad = [](auto change, const std::string& name) {
    OfficeOptions o;
    change(o);
    test::expect_error([&] { random_office(1, o); }, {"random_office", name});
  };
  expect_bad([](OfficeOptions& o) { o.target_vertices = 3; }, "target_vertices");
  expect_bad([](OfficeOptions& o) { o.target_vertices = 20'000; }, "vertex limit");
  expect_bad([](OfficeOptions& o) { o.min_room_width = 7; }, "room width");
  expect_bad([](OfficeOptions& o) { o.min_room_depth = 0; }, "room depth");
  expect_bad([](OfficeOptions& o) { o.max_corridor_length = 5; }, "corridor length");
  expect_bad([](OfficeOptions& o) { o.corridor_width = 0; }, "corridor_width");
  expect_bad([](OfficeOptions& o) { o.corridor_width = 31; }, "max_corridor_length");
  expect_bad([](OfficeOptions& o) { o.door_width = 4; },
             "door_width must be in [1, min_room_width = 3]");
  expect_bad([](OfficeOptions& o) { o.repeat_probability = 1.5; }, "repeat_probability");
  expect_bad([](OfficeOptions& o) { o.notch_probability = -0.1; }, "notch_probability");
  expect_bad([](OfficeOptions& o) { o.branch_probability = 2.0; }, "branch_probability");
  expect_bad([](OfficeOptions& o) { o.resolution = 0.0; }, "resolution");
  expect_bad([](OfficeOptions& o) { o.max_attempts = 3; }, "max_attempts");
}

}  // namespace
}  // namespace gridloc
