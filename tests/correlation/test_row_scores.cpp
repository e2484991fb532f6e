// Scores of a row of translations at once (row_scores.hpp): the vector path equals the scalar
// reference exactly, and score_row equals score() pose by pose on every kind of grid.
#include "gridloc/engine/correlation/row_scores.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "correlation/search_cases.hpp"
#include "gridloc/engine/correlation/fixed_point_kernel.hpp"
#include "gridloc/grids/error.hpp"
#include "random_cases.hpp"

namespace gridloc {
namespace {

using namespace test;

TEST(RowScores, VectorPathEqualsScalarReference) {
  if (!avx512_row_available()) GTEST_SKIP() << "this CPU has no AVX-512 byte loads";
  std::mt19937 rng(31);
  for (int c = 0; c < 300; ++c) {
    const int cells = uniform_int(rng, 16, c % 2 == 0 ? 60 : 50000);
    const int lim = c % 3 == 0 ? 127 : 1;
    std::vector<std::int8_t> arc(static_cast<std::size_t>(cells)), all(arc.size());
    for (auto& v : arc) v = static_cast<std::int8_t>(uniform_int(rng, -lim, lim));
    for (auto& v : all) v = static_cast<std::int8_t>(uniform_int(rng, -lim, lim));
    const int run = uniform_int(rng, 1, kRowRun);
    // Offsets from cell 0 whose run of bytes stays inside the grid (no slack read).
    const int n = uniform_int(rng, 0, 3000);
    std::vector<std::int32_t> offset, fixed;
    const std::int32_t max_fixed = c % 4 == 0 ? 32768 : 5;
    for (int k = 0; k < n; ++k) {
      offset.push_back(uniform_int(rng, 0, cells - run));
      fixed.push_back(uniform_int(rng, -max_fixed, max_fixed));
    }
    const auto arc_count = static_cast<std::size_t>(uniform_int(rng, 0, n));
    std::int64_t reference[kRowRun], fast[kRowRun];
    correlate_fixed_row_scalar(arc.data(), all.data(), offset.data(), fixed.data(), arc_count,
                               offset.size(), run, reference);
    correlate_fixed_row_avx512(arc.data(), all.data(), offset.data(), fixed.data(), arc_count,
                               offset.size(), run, fast);
    for (int j = 0; j < run; ++j) {
      // Each lane is the per-pose kernel's sum at that translation.
      const std::int64_t one = correlate_fixed_scalar(arc.data() + j, all.data() + j, offset.data(),
                                                      fixed.data(), arc_count, offset.size());
      ASSERT_EQ(reference[j], one) << "case " << c << ", pose " << j;
      ASSERT_EQ(fast[j], reference[j]) << "case " << c << ", pose " << j << " of " << run;
    }
  }
}

TEST(RowScores, LanesDoNotOverflowAtTheLimits) {
  std::vector<std::int8_t> grid(kRowRun, 127);
  const std::vector<std::int32_t> offset(20000, 0), fixed(20000, 32768);
  const std::int64_t expected = std::int64_t{20000} * 32768 * 127;  // beyond int32
  std::int64_t out[kRowRun];
  correlate_fixed_row(grid.data(), grid.data(), offset.data(), fixed.data(), 7000, 20000, kRowRun,
                      out);
  for (int j = 0; j < kRowRun; ++j) EXPECT_EQ(out[j], expected) << "pose " << j;
}

TEST(RowScores, ARunOutsideTheLanesIsAnError) {
  std::vector<std::int8_t> grid(2 * kRowRun, 1);
  const std::vector<std::int32_t> offset(3, 0), fixed(3, 1);
  std::int64_t out[kRowRun];
  for (int run : {0, -1, kRowRun + 1}) {
    try {
      correlate_fixed_row(grid.data(), grid.data(), offset.data(), fixed.data(), 1, 3, run, out);
      ADD_FAILURE() << "run " << run << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("a run of " + std::to_string(run)), std::string::npos)
          << e.what();
    }
  }
}

// Every grid kind (int8 ternary grids, floats, a likelihood field's scaled int8 cells) and
// local values with and without a fixed-point form: the same doubles as score().
TEST(RowScores, ScoreRowEqualsScoreOnEveryGrid) {
  std::mt19937 rng(8);
  int integer_rows = 0, float_rows = 0;  // cases on correlate_fixed_row's path, on float sums
  for (int c = 0; c < 200; ++c) {
    const int w = uniform_int(rng, 1, 50), h = uniform_int(rng, 1, 30);
    const auto kind = static_cast<GridKind>(c % static_cast<int>(GridKind::Count));
    const int extent = uniform_int(rng, 0, 6);
    const PaddedGrid padded = pad_grid(make_grid(rng, w, h, kind), extent, kRules[c % 2]);
    const SparseLocalGrid local = make_local(rng, uniform_int(rng, 1, 60), extent, c % 3);
    const PlacedLocalGrid placed = place(local, padded);
    const int cy = uniform_int(rng, 0, h - 1), cx = uniform_int(rng, 0, w - 1);
    const int run = uniform_int(rng, 1, w - cx);  // may exceed kRowRun
    std::vector<double> row(static_cast<std::size_t>(run));
    integer_rows += padded.has_int8() && placed.fixed_shift >= 0 ? 1 : 0;
    float_rows += placed.fixed_shift < 0 && (padded.has_floats() || padded.ternary()) ? 1 : 0;
    score_row(padded, placed, cx, cy, run, row.data());
    for (int j = 0; j < run; ++j) {
      ASSERT_EQ(row[static_cast<std::size_t>(j)], score(padded, placed, cx + j, cy))
          << "case " << c << " (grid kind " << c % static_cast<int>(GridKind::Count)
          << ", fixed shift " << placed.fixed_shift << "), pose " << j << " of " << run;
    }
  }
  EXPECT_GE(integer_rows, 40);
  EXPECT_GE(float_rows, 40);
}

}  // namespace
}  // namespace gridloc
