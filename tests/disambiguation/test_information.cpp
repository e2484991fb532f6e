#include "gridloc/engine/disambiguation/information.hpp"

#include <gtest/gtest.h>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

RangeView view_of(std::initializer_list<PlanarSegment> segments) {
  RangeView view;
  for (const PlanarSegment& segment : segments) view.pieces.push_back({segment, true, false});
  return view;
}

TEST(ExpectedEliminations, FollowsSeed002OnHandMadeClasses) {
  EXPECT_DOUBLE_EQ(expected_eliminations({3}), 0.0);           // nothing tells them apart
  EXPECT_DOUBLE_EQ(expected_eliminations({1, 1}), 1.0);        // one of two goes
  EXPECT_DOUBLE_EQ(expected_eliminations({2, 1}), 4.0 / 3.0);  // (2/3)(1) + (1/3)(2)
  EXPECT_DOUBLE_EQ(expected_eliminations({1, 1, 1, 1}), 3.0);  // k - 1: every one alone
  EXPECT_DOUBLE_EQ(expected_eliminations({2, 2}), 2.0);        // (1/2)(2) + (1/2)(2)
}

TEST(ExpectedEliminations, RefusesAnEmptyClass) {
  EXPECT_THROW(expected_eliminations({2, 0}), Error);
}

TEST(EquivalenceClasses, GroupsViewsEqualWithinTolerance) {
  const RangeView wall = view_of({{{1, -1}, {1, 1}}});
  const RangeView same_wall = view_of({{{1, -1 + 1e-9}, {1, 1}}});
  const RangeView nearer_wall = view_of({{{0.5, -1}, {0.5, 1}}});
  const RangeView two_walls = view_of({{{1, -1}, {1, 1}}, {{1, 1}, {-1, 1}}});
  const std::vector<int> classes =
      equivalence_classes({wall, nearer_wall, same_wall, two_walls, RangeView{}});
  EXPECT_EQ(classes, (std::vector<int>{0, 1, 0, 2, 3}));
  EXPECT_EQ(class_sizes(classes), (std::vector<int>{2, 1, 1, 1}));
}

TEST(EquivalenceClasses, TellsAVertexFromACut) {
  RangeView cut = view_of({{{1, -1}, {1, 1}}});
  cut.pieces.front().a_is_vertex = false;
  EXPECT_EQ(equivalence_classes({view_of({{{1, -1}, {1, 1}}}), cut}), (std::vector<int>{0, 1}));
}

}  // namespace
}  // namespace gridloc
