// The fixed-point correlation kernel: the vector path equals the scalar reference exactly,
// and both equal the float correlation they stand in for.
#include "gridloc/engine/correlation/fixed_point_kernel.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "gridloc/engine/correlation/search.hpp"
#include "random_cases.hpp"

namespace gridloc {
namespace {

using test::uniform_int;

/// A random int8 grid of `cells` cells (values in [-lim, lim]) plus the kernel's slack.
std::vector<std::int8_t> random_grid(std::mt19937& rng, int cells, int lim) {
  std::vector<std::int8_t> g(static_cast<std::size_t>(cells) + kGatherSlack, 0);
  for (int k = 0; k < cells; ++k)
    g[static_cast<std::size_t>(k)] = static_cast<std::int8_t>(uniform_int(rng, -lim, lim));
  return g;
}

struct Case {
  std::vector<std::int8_t> arc, all;
  PlacedLocalGrid local;
  std::ptrdiff_t origin = 0;
};

/// Offsets anywhere in the grid around a random origin (negative ones included), values
/// with fixed-point representations of up to `max_shift` fractional bits.
Case random_case(std::mt19937& rng, int max_cells, int lim, std::int32_t max_fixed) {
  Case c;
  const int cells = uniform_int(rng, 1, max_cells);
  c.arc = random_grid(rng, cells, lim);
  c.all = random_grid(rng, cells, lim);
  c.origin = uniform_int(rng, 0, cells - 1);
  const int n = uniform_int(rng, 0, 3000);
  const int shift = uniform_int(rng, 0, 4);
  for (int k = 0; k < n; ++k) {
    c.local.offset.push_back(uniform_int(rng, 0, cells - 1) - static_cast<int>(c.origin));
    const auto f = static_cast<std::int32_t>(uniform_int(rng, -max_fixed, max_fixed));
    c.local.value.push_back(static_cast<float>(std::ldexp(f, -shift)));
  }
  c.local.arc_count = static_cast<std::size_t>(uniform_int(rng, 0, n));
  set_fixed_point(c.local);
  return c;
}

std::int64_t run(decltype(&correlate_fixed_scalar) kernel, const Case& c) {
  return kernel(c.arc.data() + c.origin, c.all.data() + c.origin, c.local.offset.data(),
                c.local.fixed.data(), c.local.arc_count, c.local.offset.size());
}

/// The vector paths this CPU runs, with their names.
std::vector<std::pair<const char*, decltype(&correlate_fixed_scalar)>> vector_paths() {
  std::vector<std::pair<const char*, decltype(&correlate_fixed_scalar)>> paths;
  if (avx2_available()) paths.emplace_back("avx2", &correlate_fixed_avx2);
  if (avx512_available()) paths.emplace_back("avx512", &correlate_fixed_avx512);
  return paths;
}

TEST(FixedPointKernel, VectorPathsEqualScalarReference) {
  if (vector_paths().empty()) GTEST_SKIP() << "this CPU has no AVX2: only the scalar path runs";
  std::mt19937 rng(77);
  for (int k = 0; k < 400; ++k) {
    // Small grids (many repeated cells), large ones; the largest values stress the lanes.
    const Case c =
        random_case(rng, k % 2 == 0 ? 50 : 200000, k % 3 == 0 ? 127 : 1, k % 4 == 0 ? 32768 : 3);
    ASSERT_GE(c.local.fixed_shift, 0) << "case " << k;
    const std::int64_t reference = run(&correlate_fixed_scalar, c);
    for (const auto& [name, kernel] : vector_paths()) {
      EXPECT_EQ(run(kernel, c), reference) << name << ", case " << k;
    }
    EXPECT_EQ(run(&correlate_fixed, c), reference) << fixed_kernel_name() << ", case " << k;
  }
}

TEST(FixedPointKernel, LanesDoNotOverflowAtTheLimits) {
  // Every product at its largest, 2^15 * 127, over 20000 cells: 8.3e10, beyond int32.
  std::vector<std::int8_t> grid(1 + kGatherSlack, 0);
  grid[0] = 127;
  const std::vector<std::int32_t> offset(20000, 0), fixed(20000, 32768);
  const std::int64_t expected = std::int64_t{20000} * 32768 * 127;
  EXPECT_EQ(
      correlate_fixed_scalar(grid.data(), grid.data(), offset.data(), fixed.data(), 7000, 20000),
      expected);
  for (const auto& [name, kernel] : vector_paths()) {
    EXPECT_EQ(kernel(grid.data(), grid.data(), offset.data(), fixed.data(), 7000, 20000), expected)
        << name;
  }
}

// correlate() on int8 grids takes the integer path for fixed-point local grids: the same
// double as the float loop, bit for bit.
TEST(FixedPointKernel, IntegerPathEqualsFloatCorrelation) {
  std::mt19937 rng(5);
  for (int k = 0; k < 300; ++k) {
    const Case c = random_case(rng, 5000, 1, k % 2 == 0 ? 1 : 64);
    ASSERT_GE(c.local.fixed_shift, 0);
    const double fast = correlate(c.arc.data() + c.origin, c.all.data() + c.origin, c.local);
    const double reference =
        correlate_scalar(c.arc.data() + c.origin, c.all.data() + c.origin, c.local);
    EXPECT_EQ(fast, reference) << "case " << k;
  }
}

// A sonar cone's 1/n values have no fixed form but sum exactly in double on -1/0/1 cells:
// the four-sum loop gives correlate_scalar's result bit for bit.
TEST(FixedPointKernel, OrderFreeSumsEqualTheOrderedLoop) {
  std::mt19937 rng(12);
  int order_free = 0;
  for (int k = 0; k < 300; ++k) {
    Case c = random_case(rng, 5000, 1, 1);
    for (float& v : c.local.value) {  // +-1/n, and sums of two as overlapping cones make
      v = (uniform_int(rng, 0, 1) == 0 ? 1.0f : -1.0f) /
          static_cast<float>(uniform_int(rng, 1, 400));
      if (uniform_int(rng, 0, 3) == 0) v += 1.0f / static_cast<float>(uniform_int(rng, 1, 400));
    }
    set_fixed_point(c.local);
    if (!c.local.order_free) continue;
    ++order_free;
    const std::int8_t* arc = c.arc.data() + c.origin;
    const std::int8_t* all = c.all.data() + c.origin;
    EXPECT_EQ(correlate_scalar_unordered(arc, all, c.local), correlate_scalar(arc, all, c.local))
        << "case " << k;
    EXPECT_EQ(correlate(arc, all, c.local), correlate_scalar(arc, all, c.local)) << "case " << k;
  }
  EXPECT_GT(order_free, 200);
  // Values far apart in magnitude would need more than 53 bits: the ordered loop stays.
  PlacedLocalGrid wide_apart;
  wide_apart.value = {1.0e12f, 1.0f / 3.0f};  // 2^40 and a 2^-25 bit: 65 bits
  set_fixed_point(wide_apart);
  EXPECT_FALSE(wide_apart.order_free);
}

TEST(FixedPointKernel, ValuesWithoutAFixedPointFormKeepTheFloatPath) {
  PlacedLocalGrid p;
  p.value = {1.0f, -1.0f / 3.0f};  // a third has no binary fraction
  set_fixed_point(p);
  EXPECT_EQ(p.fixed_shift, -1);
  EXPECT_TRUE(p.fixed.empty());
  p.value = {65536.0f};  // beyond 2^15
  set_fixed_point(p);
  EXPECT_EQ(p.fixed_shift, -1);
  p.value = {1.0f, -0.25f, 0.75f};
  set_fixed_point(p);
  EXPECT_EQ(p.fixed_shift, 2);
  EXPECT_EQ(p.fixed, (std::vector<std::int32_t>{4, -1, 3}));
}

}  // namespace
}  // namespace gridloc
