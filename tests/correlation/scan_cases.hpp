#pragma once
// Search problems over rigid scan points shared by the branch-and-bound tests (rooms, scans
// seen from a pose, random ScanCases), and checks of a search result against the exhaustive
// one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "correlation/search_cases.hpp"
#include "gridloc/sensors/range_scan.hpp"
#include "random_cases.hpp"

namespace gridloc::test {

/// Rooms like a thinned map: +1 one-cell contours around -1 interiors, unknown elsewhere.
inline EvidenceGrid make_rooms(std::mt19937& rng, int w, int h) {
  GridGeometry geo;
  geo.width = w;
  geo.height = h;
  EvidenceGrid g(geo, 0.0f);
  const int rooms = 1 + w * h / 150;
  for (int r = 0; r < rooms; ++r) {
    const int x0 = uniform_int(rng, 0, w - 1), y0 = uniform_int(rng, 0, h - 1);
    const int x1 = std::min(w - 1, x0 + uniform_int(rng, 2, 18));
    const int y1 = std::min(h - 1, y0 + uniform_int(rng, 2, 18));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        if (x == x0 || x == x1 || y == y0 || y == y1) {
          g.at(x, y) = 1.0f;
        } else if (g.at(x, y) == 0.0f) {
          g.at(x, y) = -1.0f;
        }
      }
    }
  }
  return g;
}

/// The scan a robot at cell (tx, ty) + a sub-cell offset with heading theta sees on g (cells
/// of `res` m): each beam ends in the first cell > 0 it meets (a little noise), or has no
/// return when it meets none within the max range or leaves the map.
inline RangeScan scan_from(std::mt19937& rng, const EvidenceGrid& g, double res, int tx, int ty,
                           double theta, int beams, double max_range) {
  RangeScan scan;
  scan.max_range = max_range;
  const double x0 = tx + uniform_real(rng, -0.5, 0.5), y0 = ty + uniform_real(rng, -0.5, 0.5);
  const double a0 = uniform_real(rng, -std::numbers::pi, std::numbers::pi);
  for (int k = 0; k < beams; ++k) {
    const double a = a0 + 2.0 * std::numbers::pi * k / beams;
    double range = max_range;
    for (double d = 0.0; d * res < max_range; d += 0.25) {
      const int x = static_cast<int>(std::floor(x0 + d * std::cos(theta + a) + 0.5));
      const int y = static_cast<int>(std::floor(y0 + d * std::sin(theta + a) + 0.5));
      if (!g.geometry.contains(x, y)) break;
      if (g.at(x, y) > 0.0f) {
        range = std::max(0.0, d * res + uniform_real(rng, -0.3, 0.3) * res);
        break;
      }
    }
    scan.angles.push_back(a);
    scan.ranges.push_back(range);
  }
  if (std::none_of(scan.ranges.begin(), scan.ranges.end(),
                   [&](double r) { return r < max_range; })) {
    scan.ranges[0] = 0.5 * max_range;
  }
  return scan;
}

/// A level whose local grids are the rigid points rasterized, as the estimator makes it.
inline SearchLevel points_level(const PaddedGrid& padded, const ScanPoints& points) {
  const double res = padded.grid.geometry.resolution;
  SearchLevel level{&padded, [&points, res](double theta, const Eigen::Vector2d& centre) {
                      return rasterize_points(points, theta, res, centre);
                    }};
  level.points = &points;
  return level;
}

/// One random search problem over rigid scan points.
struct ScanCase {
  EvidenceGrid grid;
  RangeScan scan;
  ScanPoints points;
  Lattice lat;
  int depth = 0;
  int pad = 0;
  ArcRule rule = ArcRule::Neutral;
  std::string what;
};

inline ScanCase make_scan_case(std::mt19937& rng, int c) {
  ScanCase s;
  const double res = c % 2 == 0 ? 0.05 : 0.1;
  const int w = uniform_int(rng, 1, c % 8 == 0 ? 48 : 28);
  const int h = uniform_int(rng, 1, c % 8 == 0 ? 48 : 28);
  const int kind = c % 8;
  switch (kind) {
    case 0:
    case 1:
      s.grid = make_grid(rng, w, h, GridKind::Sparse);
      break;
    case 2:
    case 3:
      s.grid = make_rooms(rng, w, h);
      break;
    case 4:
      s.grid = make_grid(rng, w, h, c % 3 == 0 ? GridKind::Zero : GridKind::Ternary);
      break;
    case 5:
      s.grid = make_grid(rng, w, h, GridKind::Periodic);
      break;
    case 6:  // not ternary: the float bound levels, or a field's int8 ones
      s.grid = make_grid(rng, w, h, c % 16 == 6 ? GridKind::Floats : GridKind::Field);
      break;
    default: {  // needles: a few occupied cells in unknown space. With few points, a bound
                // is tight: one that misses where a point can land prunes the winner.
      GridGeometry geo;
      geo.width = w;
      geo.height = h;
      s.grid = EvidenceGrid(geo, 0.0f);
      for (int k = uniform_int(rng, 1, 3); k > 0; --k) {
        s.grid.at(uniform_int(rng, 0, w - 1), uniform_int(rng, 0, h - 1)) = 1.0f;
      }
      break;
    }
  }
  s.grid.geometry.resolution = res;
  const int beams = uniform_int(rng, 1, kind == 7 ? 3 : 40);
  const double max_range = uniform_real(rng, 0.15, c % 5 == 0 || kind == 7 ? 2.5 : 1.2);
  if (kind == 3) {  // seen from a pose of the map: one clear peak, deep pruning
    s.scan = scan_from(rng, s.grid, res, uniform_int(rng, 0, w - 1), uniform_int(rng, 0, h - 1),
                       uniform_real(rng, -3.0, 3.0), beams, max_range);
  } else {
    s.scan = random_scan(rng, beams, max_range);
  }
  const ScanModelOptions model = c % 3 == 2
                                     ? ScanModelOptions{ScanModel::Hits, 1}
                                     : ScanModelOptions{ScanModel::Samples, uniform_int(rng, 1, 5)};
  s.points = scan_points(s.scan, model);
  const int headings = c % 10 == 0 ? 1 : uniform_int(rng, 2, 40);
  s.lat = make_lattice(rng, w, h, headings);
  s.lat.theta0 = uniform_real(rng, -std::numbers::pi, std::numbers::pi);
  s.lat.step_theta = std::exp(uniform_real(rng, std::log(0.01), std::log(0.5)));
  if (c % 9 == 4) s.lat.step_theta = -s.lat.step_theta;
  s.depth = uniform_int(rng, 0, 8);
  s.pad = static_cast<int>(std::ceil(s.points.max_norm / res)) + uniform_int(rng, 3, 5);
  s.rule = (c / 2) % 2 == 0 ? ArcRule::Neutral : ArcRule::Signed;
  std::ostringstream what;
  what << "case " << c << ": map " << w << " x " << h << " res " << res << " kind " << kind << ", "
       << beams << " beams (" << s.points.hit_count << " ends, " << s.points.size()
       << " points, max_norm " << s.points.max_norm << "), lattice x [" << s.lat.x0 << ", "
       << s.lat.x1 << "] y [" << s.lat.y0 << ", " << s.lat.y1 << "] " << headings
       << " headings step " << s.lat.step_theta << ", depth " << s.depth << ", pad " << s.pad
       << ", rule " << static_cast<int>(s.rule);
  s.what = what.str();
  return s;
}

/// Index of a lattice pose in search_exhaustive's `scored` (heading, row, column order).
inline std::size_t lattice_index(const Lattice& lat, int ix, int iy, int it) {
  const auto nx = static_cast<std::size_t>(lat.x1 - lat.x0 + 1);
  const auto ny = static_cast<std::size_t>(lat.y1 - lat.y0 + 1);
  return (static_cast<std::size_t>(it) * ny + static_cast<std::size_t>(iy - lat.y0)) * nx +
         static_cast<std::size_t>(ix - lat.x0);
}

inline bool in_lattice(const Lattice& lat, const LatticePose& p) {
  return p.ix >= lat.x0 && p.ix <= lat.x1 && p.iy >= lat.y0 && p.iy <= lat.y1 && p.it >= 0 &&
         p.it < lat.headings;
}

inline void expect_pose(const LatticePose& got, const LatticePose& want, const std::string& what) {
  EXPECT_EQ(got.ix, want.ix) << what;
  EXPECT_EQ(got.iy, want.iy) << what;
  EXPECT_EQ(got.it, want.it) << what;
  EXPECT_EQ(got.score, want.score) << what;
}

/// The leaves a search scored are lattice poses with their exhaustive scores, each once.
inline void expect_leaves_exact(const SearchResult& r, const SearchResult& exhaustive,
                                const Lattice& lat, const std::string& what) {
  EXPECT_EQ(r.poses_scored, static_cast<long long>(r.scored.size())) << what;
  std::vector<char> seen(exhaustive.scored.size(), 0);
  for (const auto& p : r.scored) {
    ASSERT_TRUE(in_lattice(lat, p)) << what;
    const std::size_t k = lattice_index(lat, p.ix, p.iy, p.it);
    ASSERT_LT(k, exhaustive.scored.size()) << what;
    EXPECT_EQ(p.score, exhaustive.scored[k].score) << what;
    EXPECT_FALSE(seen[k]) << what << ": pose scored twice";
    seen[k] = 1;
  }
}

/// Checks an unbudgeted search result against the exhaustive best.
inline void expect_exact(const SearchResult& r, const SearchResult& e, const Lattice& lat,
                         const std::string& what) {
  expect_pose(r.best, e.best, what);
  EXPECT_TRUE(r.proven_optimal) << what;
  EXPECT_EQ(r.upper_bound, r.best.score) << what;
  expect_leaves_exact(r, e, lat, what);
}

}  // namespace gridloc::test
