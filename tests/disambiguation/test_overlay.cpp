// The overlay arrangement of seed 002 §IV: maps in the start frame, their intersection, OI,
// and OI's boundary split into internal and silhouette edges (Fig. 5).
#include "gridloc/engine/disambiguation/overlay.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "test_support.hpp"

namespace gridloc {
namespace {

Polygon rectangle(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};  // counter-clockwise
}

Polygon clockwise(Polygon ring) {
  std::reverse(ring.begin(), ring.end());
  return ring;
}

double total_length(const std::vector<PlanarSegment>& pieces) {
  double length = 0.0;
  for (const PlanarSegment& piece : pieces) length += (piece.b - piece.a).norm();
  return length;
}

double distance_to_segment(const PlanarSegment& s, const Eigen::Vector2d& p) {
  const Eigen::Vector2d d = s.b - s.a;
  const double t = std::clamp((p - s.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (s.a + t * d - p).norm();
}

/// Whether some piece passes through p.
bool on_some_piece(const std::vector<PlanarSegment>& pieces, const Eigen::Vector2d& p) {
  for (const PlanarSegment& piece : pieces) {
    if (distance_to_segment(piece, p) < 1e-9) return true;
  }
  return false;
}

double oi_perimeter(const Area& oi) {
  return total_length(area_edges(oi));
}

/// Every piece agrees with a brute-force look just beyond its midpoint.
void expect_pieces_classified(const Overlay& overlay) {
  for (int internal = 0; internal < 2; ++internal) {
    for (const PlanarSegment& piece :
         internal ? overlay.internal_edges : overlay.silhouette_edges) {
      if ((piece.b - piece.a).norm() < 1e-6) continue;  // a sliver of Boost's rescaling
      const Eigen::Vector2d d = (piece.b - piece.a).normalized();
      const Eigen::Vector2d probe =
          0.5 * (piece.a + piece.b) + 1e-4 * Eigen::Vector2d(d.y(), -d.x());
      bool free_beyond = false;
      for (const Area& map : overlay.maps) free_beyond = free_beyond || covers(map, probe);
      EXPECT_EQ(free_beyond, internal == 1) << probe.transpose();
      EXPECT_FALSE(covers(overlay.oi, probe)) << "the probe should lie outside OI";
    }
  }
  EXPECT_NEAR(total_length(overlay.internal_edges) + total_length(overlay.silhouette_edges),
              oi_perimeter(overlay.oi), 1e-6);
}

TEST(Overlay, TheIssuesCaseStartsOneApartInAFourByThreeRoom) {
  // Starts (0, 0) and (1, 0) in the room [0,4]x[0,3]: the copies [0,4]x[0,3] and [-1,3]x[0,3]
  // overlap in [0,3]x[0,3]; the anchor (the start) is OI's corner.
  const Overlay overlay = make_overlay(Area{rectangle(0, 0, 4, 3), {}}, {{0, 0, 0}, {1, 0, 0}});
  ASSERT_EQ(overlay.oi.outer.size(), 4u);
  for (const Eigen::Vector2d& corner : rectangle(0, 0, 3, 3)) {
    EXPECT_NE(std::find(overlay.oi.outer.begin(), overlay.oi.outer.end(), corner),
              overlay.oi.outer.end())
        << corner.transpose();
  }
  EXPECT_GT(signed_area2(overlay.oi.outer), 0.0);  // counter-clockwise
  EXPECT_NEAR(area_size(overlay.oi), 9.0, 1e-12);
  EXPECT_TRUE(on_some_piece(overlay.internal_edges, {0, 1.5}));  // the second copy goes on
  EXPECT_TRUE(on_some_piece(overlay.internal_edges, {3, 1.5}));  // the first copy goes on
  EXPECT_NEAR(total_length(overlay.internal_edges), 6.0, 1e-12);
  EXPECT_NEAR(total_length(overlay.silhouette_edges), 6.0, 1e-12);
}

TEST(Overlay, TwoShiftedRectangularRoomsOverlapInASquare) {
  const Area room{rectangle(0, 0, 4, 3), {}};
  const Overlay overlay = make_overlay(room, {{1, 1, 0}, {2, 1, 0}});
  ASSERT_EQ(overlay.maps.size(), 2u);
  EXPECT_TRUE(covers(overlay.maps[0], {-1, -1}));  // the room seen from (1, 1)
  EXPECT_TRUE(covers(overlay.maps[1], {-2, -1}));
  ASSERT_EQ(overlay.intersection.size(), 1u);
  EXPECT_NEAR(region_size(overlay.intersection), 9.0, 1e-12);  // [-1, 2] x [-1, 2]
  EXPECT_NEAR(area_size(overlay.oi), 9.0, 1e-12);
  EXPECT_TRUE(covers(overlay.oi, {-1, -1}));
  EXPECT_TRUE(covers(overlay.oi, {2, 2}));
  EXPECT_FALSE(covers(overlay.oi, {2.01, 0}));
  EXPECT_FALSE(covers(overlay.oi, {-1.01, 0}));
  // The side walls each belong to one copy, the other copy's room goes on: internal.
  EXPECT_NEAR(total_length(overlay.internal_edges), 6.0, 1e-12);
  EXPECT_NEAR(total_length(overlay.silhouette_edges), 6.0, 1e-12);
  EXPECT_TRUE(on_some_piece(overlay.internal_edges, {-1, 0.5}));
  EXPECT_TRUE(on_some_piece(overlay.internal_edges, {2, 0.5}));
  EXPECT_TRUE(on_some_piece(overlay.silhouette_edges, {0.5, 2}));
  expect_pieces_classified(overlay);
}

TEST(Overlay, LShapedMapSplitsAWallWhereTheOtherCopyGoesOn) {
  // L: [0,4]x[0,2] and [0,2]x[2,4]; from (1,1) and (2,1) OI is the L with corners (-1,-1),
  // (2,-1), (2,1), (0,1), (0,3), (-1,3).
  const Area l_room{{{0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}}, {}};
  const Overlay overlay = make_overlay(l_room, {{1, 1, 0}, {2, 1, 0}});
  EXPECT_NEAR(area_size(overlay.oi), 8.0, 1e-12);
  EXPECT_NEAR(total_length(overlay.internal_edges), 9.0, 1e-12);
  EXPECT_NEAR(total_length(overlay.silhouette_edges), 5.0, 1e-12);
  // The wall y = 1 from x = 0 to 2 is split at x = 1, where the first copy's arm ends.
  EXPECT_TRUE(on_some_piece(overlay.internal_edges, {0.5, 1}));
  EXPECT_FALSE(on_some_piece(overlay.internal_edges, {1.5, 1}));
  EXPECT_TRUE(on_some_piece(overlay.silhouette_edges, {1.5, 1}));
  EXPECT_TRUE(on_some_piece(overlay.internal_edges, {0, 2}));     // the arm's inner wall
  EXPECT_TRUE(on_some_piece(overlay.internal_edges, {2, 0}));     // the second copy's end
  EXPECT_TRUE(on_some_piece(overlay.internal_edges, {-1, 2}));    // the first copy's end
  EXPECT_TRUE(on_some_piece(overlay.silhouette_edges, {0, -1}));  // both floors
  EXPECT_TRUE(on_some_piece(overlay.silhouette_edges, {-0.5, 3}));
  expect_pieces_classified(overlay);
}

TEST(Overlay, AnObstacleGivesOIBothCopiesHoles) {
  const Area room{rectangle(0, 0, 8, 4), {clockwise(rectangle(3, 1, 4, 2))}};
  const Overlay overlay = make_overlay(room, {{1, 1, 0}, {3, 1, 0}});
  ASSERT_EQ(overlay.oi.holes.size(), 2u);  // [2,3]x[0,1] and [0,1]x[0,1]
  for (const Polygon& hole : overlay.oi.holes) EXPECT_LT(signed_area2(hole), 0.0);  // clockwise
  EXPECT_NEAR(area_size(overlay.oi), 6.0 * 4.0 - 2.0, 1e-12);
  EXPECT_FALSE(covers(overlay.oi, {0.5, 0.5}));
  EXPECT_FALSE(covers(overlay.oi, {2.5, 0.5}));
  EXPECT_TRUE(covers(overlay.oi, {1.5, 0.5}));
  EXPECT_TRUE(covers(overlay.oi, {1, 0.5}));  // on a hole's wall (closed)
  // Each hole is one copy's obstacle, free in the other copy: its walls are internal.
  EXPECT_TRUE(on_some_piece(overlay.internal_edges, {0.5, 0}));
  EXPECT_TRUE(on_some_piece(overlay.internal_edges, {3, 0.5}));
  expect_pieces_classified(overlay);
}

TEST(Overlay, RotatedHypothesesSeeTheRoomTurned) {
  const Area room{rectangle(0, 0, 4, 2), {}};
  const double quarter = std::acos(0.0);
  const Overlay overlay = make_overlay(room, {{1, 1, quarter}, {1, 1, quarter}});
  // Facing +y from (1, 1): the room spans x' in [-1, 1] (from world y) and y' in [-3, 1].
  EXPECT_NEAR(area_size(overlay.oi), 8.0, 1e-9);
  EXPECT_TRUE(covers(overlay.oi, {0.5, -2.5}));
  EXPECT_FALSE(covers(overlay.oi, {2.5, 0.5}));
  EXPECT_TRUE(overlay.internal_edges.empty());
  expect_pieces_classified(overlay);
}

TEST(Overlay, AllHypothesesTurnedAlikeTurnTheOverlayOnly) {
  // The same pair of starts, the robot heading elsewhere: the overlay turns with it (rotated
  // coordinates are inexact: cos(pi / 2) != 0 in doubles; Boost 1.74's rescaling to an integer
  // grid moves crossings by about 1e-7 of the extent: boost_geometry.hpp).
  const Area l_room{{{0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}},
                    {clockwise(rectangle(0.5, 0.5, 1.5, 1.5))}};
  const Overlay plain = make_overlay(l_room, {{1, 1, 0}, {2, 1, 0}}, {0, 0.7});
  constexpr double kTurned = 1e-6;
  for (const double theta : {std::acos(0.0), 2 * std::acos(0.0), 0.3, -1.234}) {
    const Overlay turned =
        make_overlay(l_room, {{1, 1, theta}, {2, 1, theta}},
                     to_start_frame(Pose2{0, 0, theta}, Eigen::Vector2d(0, 0.7)));
    EXPECT_NEAR(region_size(turned.intersection), region_size(plain.intersection), kTurned);
    EXPECT_NEAR(area_size(turned.oi), area_size(plain.oi), kTurned) << theta;
    EXPECT_EQ(turned.oi.holes.size(), plain.oi.holes.size()) << theta;
    EXPECT_NEAR(total_length(turned.internal_edges), total_length(plain.internal_edges), kTurned)
        << theta;
    EXPECT_NEAR(total_length(turned.silhouette_edges), total_length(plain.silhouette_edges),
                kTurned)
        << theta;
    expect_pieces_classified(turned);
  }
}

TEST(Overlay, TheAnchorPicksItsComponent) {
  // A U (notch [1,2]x[1,3]) and its copy raised by 2: they overlap in two 1x1 squares.
  const Area u_room{{{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}}, {}};
  const std::vector<Pose2> hypotheses{{0, 0, 0}, {0, -2, 0}};
  const Overlay left = make_overlay(u_room, hypotheses, {0.5, 2.5});
  const Overlay right = make_overlay(u_room, hypotheses, {2.5, 2.5});
  ASSERT_EQ(left.intersection.size(), 2u);
  EXPECT_NEAR(region_size(left.intersection), 2.0, 1e-12);
  EXPECT_TRUE(covers(left.oi, {0.5, 2.5}));
  EXPECT_FALSE(covers(left.oi, {2.5, 2.5}));
  EXPECT_TRUE(covers(right.oi, {2.5, 2.5}));
  EXPECT_TRUE(covers(left.intersection, {2.5, 2.5}));
  EXPECT_FALSE(covers(left.intersection, {1.5, 2.5}));
}

TEST(Overlay, BadInputThrows) {
  const Area room{rectangle(0, 0, 4, 3), {}};
  test::expect_error(
      [&] {
        make_overlay(room, {{1, 1, 0}, {2, 1, 0}}, {10, 10});
      },
      {"anchor", "10.0", "make_overlay"});
  test::expect_error([&] { make_overlay(room, {}); }, {"no hypotheses"});
  test::expect_error(
      [&] {
        make_overlay(room, {{1, 1, 0}, {NAN, 1, 0}});
      },
      {"hypothesis 1", "not finite"});
  const Area bow_tie{{{0, 0}, {2, 2}, {2, 0}, {0, 2}}, {}};
  test::expect_error([&] { make_overlay(bow_tie, {{1, 1, 0}}); }, {"not a valid polygon"});
  test::expect_error(
      [&] {
        make_overlay(Area{{{0, 0}, {1, 0}}, {}}, {{0, 0, 0}});
      },
      {"fewer than 3"});
}

// ---- brute force: rooms of unit cells, hypotheses at cell centres ----

/// A room of unit columns: column c is [c, c+1] x [low_c, high_c], neighbours overlapping.
struct ColumnRoom {
  std::vector<int> low, high;
  bool free_cell(int c, int r) const {  // the cell [c, c+1] x [r, r+1]
    return c >= 0 && c < static_cast<int>(low.size()) && r >= low[c] && r < high[c];
  }
  Area area() const {
    Polygon ring;
    auto add = [&](double x, double y) {
      if (ring.empty() || ring.back() != Eigen::Vector2d(x, y)) ring.emplace_back(x, y);
    };
    for (std::size_t i = 0; i < low.size(); ++i) add(i, low[i]), add(i + 1.0, low[i]);
    for (std::size_t i = high.size(); i-- > 0;) add(i + 1.0, high[i]), add(i, high[i]);
    return Area{ring, {}};
  }
};

ColumnRoom random_column_room(std::mt19937& rng, int columns) {
  std::uniform_int_distribution<int> pick(0, 6);
  ColumnRoom room;
  while (static_cast<int>(room.low.size()) < columns) {
    int a = pick(rng), b = pick(rng);
    if (a == b) continue;
    if (a > b) std::swap(a, b);
    if (!room.low.empty() && (a >= room.high.back() || b <= room.low.back())) continue;
    room.low.push_back(a);
    room.high.push_back(b);
  }
  return room;
}

/// What the cells say: under hypothesis (c + 0.5, r + 0.5) the start-frame cell centred at
/// (x, y) is world cell (x + c, y + r). OI's cells flood from the origin's cell over shared
/// sides; a unit side of OI is internal when the cell beyond is free in some map.
struct CellOverlay {
  double intersection_size = 0, oi_size = 0, internal_length = 0, silhouette_length = 0;
};

CellOverlay cell_overlay(const ColumnRoom& room, const std::vector<Cell>& starts) {
  auto in_map = [&](const Cell& start, int x, int y) {
    return room.free_cell(x + start.ix, y + start.iy);
  };
  auto in_all = [&](int x, int y) {
    return std::all_of(starts.begin(), starts.end(),
                       [&](const Cell& s) { return in_map(s, x, y); });
  };
  auto in_some = [&](int x, int y) {
    return std::any_of(starts.begin(), starts.end(),
                       [&](const Cell& s) { return in_map(s, x, y); });
  };
  CellOverlay result;
  const int span = 12;
  for (int x = -span; x <= span; ++x) {
    for (int y = -span; y <= span; ++y) result.intersection_size += in_all(x, y) ? 1 : 0;
  }
  std::set<std::pair<int, int>> oi{{0, 0}};
  std::vector<std::pair<int, int>> stack{{0, 0}};
  const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
  while (!stack.empty()) {
    const auto [x, y] = stack.back();
    stack.pop_back();
    for (int d = 0; d < 4; ++d) {
      const std::pair<int, int> next{x + dx[d], y + dy[d]};
      if (in_all(next.first, next.second) && oi.insert(next).second) stack.push_back(next);
    }
  }
  result.oi_size = static_cast<double>(oi.size());
  for (const auto& [x, y] : oi) {
    for (int d = 0; d < 4; ++d) {
      if (oi.count({x + dx[d], y + dy[d]})) continue;
      (in_some(x + dx[d], y + dy[d]) ? result.internal_length : result.silhouette_length) += 1;
    }
  }
  return result;
}

TEST(Overlay, MatchesTheCellsOnRandomRooms) {
  std::mt19937 rng(2002);
  for (int trial = 0; trial < 30; ++trial) {
    const ColumnRoom room = random_column_room(rng, 6);
    std::vector<Cell> free_cells;
    for (int c = 0; c < 6; ++c) {
      for (int r = 0; r < 6; ++r) {
        if (room.free_cell(c, r)) free_cells.push_back({c, r});
      }
    }
    std::vector<Cell> starts;
    std::vector<Pose2> hypotheses;
    const int k = 2 + trial % 4;
    for (int i = 0; i < k; ++i) {
      starts.push_back(free_cells[rng() % free_cells.size()]);
      hypotheses.push_back({starts.back().ix + 0.5, starts.back().iy + 0.5, 0.0});
    }
    const Overlay overlay = make_overlay(room.area(), hypotheses);
    const CellOverlay expected = cell_overlay(room, starts);
    EXPECT_NEAR(region_size(overlay.intersection), expected.intersection_size, 1e-9) << trial;
    EXPECT_NEAR(area_size(overlay.oi), expected.oi_size, 1e-9) << trial;
    EXPECT_NEAR(total_length(overlay.internal_edges), expected.internal_length, 1e-9) << trial;
    EXPECT_NEAR(total_length(overlay.silhouette_edges), expected.silhouette_length, 1e-9) << trial;
    expect_pieces_classified(overlay);
  }
}

/// Points well clear of every map edge: in the intersection exactly when in every map.
/// Returns how many sampled points were in every map.
int expect_intersection_by_sampling(const Overlay& overlay, std::mt19937& rng) {
  std::vector<PlanarSegment> edges;
  for (const Area& map : overlay.maps) {
    for (const PlanarSegment& edge : area_edges(map)) edges.push_back(edge);
  }
  std::uniform_real_distribution<double> coordinate(-8, 8);  // any start sees the room here
  int checked = 0;
  for (int n = 0; n < 400; ++n) {
    const Eigen::Vector2d p(coordinate(rng), coordinate(rng));
    double clearance = 1e9;
    for (const PlanarSegment& edge : edges)
      clearance = std::min(clearance, distance_to_segment(edge, p));
    if (clearance < 1e-6) continue;
    bool in_all = true;
    for (const Area& map : overlay.maps) in_all = in_all && covers(map, p);
    EXPECT_EQ(covers(overlay.intersection, p), in_all) << p.transpose();
    checked += in_all ? 1 : 0;
  }
  EXPECT_TRUE(covers(overlay.oi, Eigen::Vector2d::Zero()));
  return checked;
}

TEST(Overlay, TurnedHypothesesOnRandomRooms) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> heading(-3.14159, 3.14159);
  int inside_all = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const ColumnRoom room = random_column_room(rng, 6);
    const Area map = room.area();
    std::vector<Pose2> hypotheses;
    const int k = 2 + trial % 3;
    for (int i = 0; i < k; ++i) {
      const int c = static_cast<int>(rng() % 6);
      const double y = room.low[c] + 0.5;  // a cell centre inside column c
      hypotheses.push_back({c + 0.5, y, heading(rng)});
    }
    const Overlay overlay = make_overlay(map, hypotheses);
    inside_all += expect_intersection_by_sampling(overlay, rng);
    expect_pieces_classified(overlay);
  }
  EXPECT_GT(inside_all, 40);  // the samples do reach the intersections (79 of 8000)
}

/// A comb: a corridor [0, 2 teeth] x [0, 1] with `teeth` rooms [2i, 2i + 1] x [1, 3] above
/// it: 4 teeth + 2 vertices, self-similar under shifts by 2.
Area comb(int teeth) {
  Polygon ring{{0, 0}, {2.0 * teeth, 0}, {2.0 * teeth, 1}};
  for (int i = teeth - 1; i >= 0; --i) {
    const double x = 2.0 * i;
    ring.insert(ring.end(), {{x + 1, 1}, {x + 1, 3}, {x, 3}});
    if (i > 0) ring.push_back({x, 1});  // (0, 1) would sit on the straight wall x = 0
  }
  return Area{ring, {}};
}

/// k hypotheses 2 apart along a comb of about 400 vertices.
void expect_comb_overlay(int k) {
  const Area map = comb(100);
  std::vector<Pose2> hypotheses;
  for (int i = 0; i < k; ++i) hypotheses.push_back({2.0 * i + 0.5, 2.0, 0.0});
  const Overlay overlay = make_overlay(map, hypotheses);
  // Under every hypothesis the robot stands in a tooth; the copies agree on all but k - 1
  // teeth (2 each) and k - 1 corridor stretches (2 each).
  ASSERT_EQ(map.outer.size(), 402u);
  EXPECT_TRUE(covers(overlay.oi, {-0.5, -1.5}));
  EXPECT_FALSE(covers(overlay.oi, {-0.6, -1.5}));
  EXPECT_NEAR(region_size(overlay.intersection), area_size(map) - 4.0 * (k - 1), 1e-9);
  EXPECT_NEAR(area_size(overlay.oi), area_size(map) - 4.0 * (k - 1), 1e-9);
  expect_pieces_classified(overlay);
}

TEST(Overlay, CombOfFourHundredVerticesTwoHypotheses) {
  expect_comb_overlay(2);
}
TEST(Overlay, CombOfFourHundredVerticesTenHypotheses) {
  expect_comb_overlay(10);
}
TEST(Overlay, CombOfFourHundredVerticesFiftyHypotheses) {
  expect_comb_overlay(50);
}

}  // namespace
}  // namespace gridloc
