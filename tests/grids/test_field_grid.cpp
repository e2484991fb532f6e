// Tests of grids/src/likelihood_field.cpp: the exact distance transform, the field's values
// at known distances, free-space evidence, the options' checks and the global grid's level.
#include "gridloc/grids/likelihood_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "gridloc/grids/evidence.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr CellState F = CellState::Free;
constexpr CellState O = CellState::Occupied;
constexpr CellState U = CellState::Unknown;

OccupancyMap make_map(int w, int h, CellState fill, double res = 0.1) {
  return test::filled_map(w, h, fill, res);
}

/// The field's quantized value of `v` (what the grid stores).
float level(double v) {
  return static_cast<float>(std::round(v * kFieldLevels)) / static_cast<float>(kFieldLevels);
}

TEST(LikelihoodField, DistanceTransformEqualsBruteForceOnRandomMaps) {
  std::mt19937 rng(13);
  for (int trial = 0; trial < 30; ++trial) {
    const int w = 1 + static_cast<int>(rng() % 40), h = 1 + static_cast<int>(rng() % 40);
    const double density = (trial % 5) * 0.03;  // includes maps without an occupied cell
    OccupancyMap m = make_map(w, h, F);
    std::bernoulli_distribution occupied(density);
    for (auto& c : m.cells) c = occupied(rng) ? O : (rng() % 4 == 0 ? U : F);
    const std::vector<double> d2 = squared_cell_distances(m);
    for (int iy = 0; iy < h; ++iy) {
      for (int ix = 0; ix < w; ++ix) {
        double best = 1e30;
        for (int oy = 0; oy < h; ++oy) {
          for (int ox = 0; ox < w; ++ox) {
            if (m.at(ox, oy) != O) continue;
            best = std::min(best, double((ox - ix) * (ox - ix) + (oy - iy) * (oy - iy)));
          }
        }
        ASSERT_EQ(d2[m.geometry.index(ix, iy)], best)
            << "trial " << trial << " cell " << ix << "," << iy;
      }
    }
  }
}

TEST(LikelihoodField, ValuesAtKnownDistancesOfOneWallCell) {
  // One occupied cell at (3, 3) of a 7 x 7 free map at 10 cm; column 0 unknown.
  OccupancyMap m = make_map(7, 7, F);
  m.at(3, 3) = O;
  for (int iy = 0; iy < 7; ++iy) m.at(0, iy) = U;
  LikelihoodFieldOptions o;
  o.sigma_m = 0.1;
  o.cutoff_m = 0.2;
  o.free_value = -0.5;
  const EvidenceGrid f = make_likelihood_field(m, o);
  EXPECT_EQ(f.geometry.origin, m.geometry.origin);
  EXPECT_EQ(f.geometry.yaw, m.geometry.yaw);
  EXPECT_EQ(f.at(3, 3), 1.0f);                   // d = 0
  EXPECT_EQ(f.at(4, 3), level(std::exp(-0.5)));  // d = 1 cell = sigma
  EXPECT_EQ(f.at(2, 2), level(std::exp(-1.0)));  // d = sqrt(2) cells
  EXPECT_EQ(f.at(3, 5), level(std::exp(-2.0)));  // d = 2 cells = the cutoff, kept
  EXPECT_EQ(f.at(3, 6), level(-0.5));            // d = 3 cells, free: free-space value
  EXPECT_EQ(f.at(5, 5), level(-0.5));            // d = sqrt(8) cells > cutoff
  EXPECT_EQ(f.at(0, 0), 0.0f);                   // unknown beyond the cutoff
  EXPECT_EQ(f.at(4, 3), likelihood_field_value(0.1, F, o));
  EXPECT_EQ(level(std::exp(-0.5)), 77.0f / 127.0f);  // 127 levels: 0.6065 -> 77 / 127
}

TEST(LikelihoodField, UnknownCellsNearAWallGetTheField) {
  OccupancyMap m = make_map(3, 1, U);
  m.at(0, 0) = O;
  LikelihoodFieldOptions o;
  o.sigma_m = 0.1;
  o.cutoff_m = 0.1;
  const EvidenceGrid f = make_likelihood_field(m, o);
  EXPECT_EQ(f.cells, (std::vector<float>{1.0f, level(std::exp(-0.5)), 0.0f}));
}

TEST(LikelihoodField, AMapWithoutWallsIsFreeSpaceOnly) {
  OccupancyMap m = make_map(3, 1, F);
  m.at(1, 0) = U;
  const EvidenceGrid f = make_likelihood_field(m, {});
  EXPECT_EQ(f.cells, (std::vector<float>{-1.0f, 0.0f, -1.0f}));
}

TEST(LikelihoodField, EveryValueIsAWholeLevel) {
  std::mt19937 rng(5);
  OccupancyMap m = make_map(30, 20, F, 0.05);
  for (auto& c : m.cells) c = rng() % 10 == 0 ? O : rng() % 5 == 0 ? U : F;
  LikelihoodFieldOptions o;
  o.free_value = -0.3;
  for (float v : make_likelihood_field(m, o).cells) {
    const float q = v * kFieldLevels;
    EXPECT_EQ(std::round(q), q);
    EXPECT_EQ(static_cast<float>(std::round(q)) / static_cast<float>(kFieldLevels), v);
    EXPECT_LE(std::abs(v), 1.0f);
  }
}

TEST(LikelihoodField, GlobalGridIsTheFieldOfTheResampledLevel) {
  OccupancyMap m = make_map(40, 30, F, 0.05);
  for (int ix = 0; ix < 40; ++ix) m.at(ix, 10) = O;
  m.at(7, 21) = O;
  LikelihoodFieldOptions o;
  o.sigma_m = 0.15;
  o.cutoff_m = 0.4;
  for (double res : {0.05, 0.1, 0.2}) {
    EXPECT_EQ(make_global_grid(m, res, GlobalModel::LikelihoodField, o).cells,
              make_likelihood_field(resample(m, res), o).cells)
        << res;
  }
}

TEST(LikelihoodField, OptionsAreChecked) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto with = [](auto change) {
    LikelihoodFieldOptions o;
    change(o);
    return o;
  };
  EXPECT_NO_THROW(LikelihoodFieldOptions{}.validate());
  for (double s : {0.0, -0.1, 11.0, nan}) {
    test::expect_error([&] { with([&](auto& o) { o.sigma_m = s; }).validate(); }, {"sigma_m"});
  }
  for (double c : {-0.01, 101.0, nan}) {
    test::expect_error([&] { with([&](auto& o) { o.cutoff_m = c; }).validate(); }, {"cutoff_m"});
  }
  for (double v : {0.5, -1.5, nan}) {
    test::expect_error([&] { with([&](auto& o) { o.free_value = v; }).validate(); },
                       {"free_value"});
  }
  const OccupancyMap m = make_map(2, 2, F);
  test::expect_error([&] { make_likelihood_field(m, with([](auto& o) { o.sigma_m = 0.0; })); },
                     {"likelihood field", "sigma_m", "(0, 10]"});
}

}  // namespace
}  // namespace gridloc
