#include "gridloc/engine/disambiguation/sampling.hpp"

#include <gtest/gtest.h>

#include "gridloc/engine/disambiguation/overlay.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

// Two areas: a 2 x 1 rectangle and, apart, a 1 x 1 square with a 0.5 x 0.5 hole.
Region two_areas() {
  return {Area{{{0, 0}, {2, 0}, {2, 1}, {0, 1}}, {}},
          Area{{{3, 0}, {4, 0}, {4, 1}, {3, 1}},
               {{{3.25, 0.25}, {3.25, 0.75}, {3.75, 0.75}, {3.75, 0.25}}}}};
}

TEST(SampleUniform, SpreadsPointsByAreaInsideTheRegion) {
  Rng rng(5);
  const Region region = two_areas();
  const std::vector<Eigen::Vector2d> points = sample_uniform(region, 8000, rng);
  ASSERT_EQ(points.size(), 8000u);
  int in_rectangle = 0;
  for (const Eigen::Vector2d& p : points) {
    EXPECT_TRUE(covers(region, p)) << p.transpose();
    EXPECT_FALSE(p.x() > 3.25 && p.x() < 3.75 && p.y() > 0.25 && p.y() < 0.75);  // the hole
    in_rectangle += p.x() < 2.5 ? 1 : 0;
  }
  EXPECT_NEAR(in_rectangle / 8000.0, 2.0 / 2.75, 0.02);  // areas 2 and 0.75
  Rng again(5);
  EXPECT_EQ(sample_uniform(region, 8000, again), points);
  EXPECT_TRUE(sample_uniform({}, 10, rng).empty());
}

TEST(SampleLattice, CoversTheRegionAtItsStepAndRefusesAHugeOne) {
  const std::vector<Eigen::Vector2d> lattice = sample_lattice(two_areas(), 0.05);
  EXPECT_NEAR(static_cast<double>(lattice.size()), 2.75 / (0.05 * 0.05), 20.0);
  for (const Eigen::Vector2d& p : lattice) EXPECT_TRUE(covers(two_areas(), p));
  EXPECT_THROW(sample_lattice(two_areas(), 0.0), Error);
  EXPECT_THROW(sample_lattice(two_areas(), 1e-5), Error);  // 2e10 points
}

}  // namespace
}  // namespace gridloc
