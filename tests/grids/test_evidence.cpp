// Tests of grids/src/evidence.cpp: evidence values, contour thinning (seed 001 §5) and
// direct resampling (seed 001 §2).
#include "gridloc/grids/evidence.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr CellState F = CellState::Free;
constexpr CellState O = CellState::Occupied;
constexpr CellState U = CellState::Unknown;

OccupancyMap make_map(int w, int h, CellState fill, double res = 0.05) {
  return test::filled_map(w, h, fill, res);
}

TEST(Evidence, ValuesArePlusMinusOneAndZero) {
  OccupancyMap m = make_map(3, 1, F);
  m.at(0, 0) = O;
  m.at(2, 0) = U;
  const EvidenceGrid e = make_evidence(m);
  EXPECT_EQ(e.cells, (std::vector<float>{1.0f, -1.0f, 0.0f}));
  EXPECT_EQ(e.geometry.width, 3);
  EXPECT_EQ(e.geometry.origin, m.geometry.origin);
  EXPECT_EQ(e.geometry.yaw, m.geometry.yaw);
}

TEST(Evidence, ThinningKeepsTheBorderOfASolidBlock) {
  // A solid 5x5 obstacle (cells 2..6) in a 9x9 free map.
  OccupancyMap m = make_map(9, 9, F);
  for (int iy = 2; iy <= 6; ++iy) {
    for (int ix = 2; ix <= 6; ++ix) m.at(ix, iy) = O;
  }
  const EvidenceGrid e = make_thinned_evidence(m);
  int border = 0, interior = 0, free_cells = 0;
  for (int iy = 0; iy < 9; ++iy) {
    for (int ix = 0; ix < 9; ++ix) {
      const bool in_block = ix >= 2 && ix <= 6 && iy >= 2 && iy <= 6;
      const bool in_interior = ix >= 3 && ix <= 5 && iy >= 3 && iy <= 5;
      const float v = e.at(ix, iy);
      if (in_interior) {
        EXPECT_EQ(v, 0.0f) << ix << "," << iy;
        interior += v == 0.0f;
      } else if (in_block) {
        EXPECT_EQ(v, 1.0f) << ix << "," << iy;
        border += v == 1.0f;
      } else {
        EXPECT_EQ(v, -1.0f) << ix << "," << iy;
        free_cells += v == -1.0f;
      }
    }
  }
  EXPECT_EQ(border, 16);
  EXPECT_EQ(interior, 9);
  EXPECT_EQ(free_cells, 81 - 25);
}

TEST(Evidence, ThinningKeepsAOneCellWall) {
  OccupancyMap m = make_map(7, 5, F);
  for (int iy = 0; iy < 5; ++iy) m.at(3, iy) = O;
  const EvidenceGrid e = make_thinned_evidence(m);
  EXPECT_EQ(e.cells, make_evidence(m).cells);
  for (int iy = 0; iy < 5; ++iy) EXPECT_EQ(e.at(3, iy), 1.0f);
}

TEST(Evidence, ThinningKeepsBothFacesOfATwoCellWall) {
  OccupancyMap m = make_map(6, 4, F);
  for (int iy = 0; iy < 4; ++iy) m.at(2, iy) = m.at(3, iy) = O;
  EXPECT_EQ(make_thinned_evidence(m).cells, make_evidence(m).cells);
}

TEST(Evidence, ThinningUsesTheEightNeighbourhood) {
  // All occupied but one free corner cell: its 3 neighbours (including the diagonal one)
  // stay +1, every other occupied cell becomes 0. Cells beyond the map edge do not count
  // as free.
  OccupancyMap m = make_map(4, 4, O);
  m.at(0, 0) = F;
  const EvidenceGrid e = make_thinned_evidence(m);
  for (int iy = 0; iy < 4; ++iy) {
    for (int ix = 0; ix < 4; ++ix) {
      const float want = (ix == 0 && iy == 0) ? -1.0f : (ix <= 1 && iy <= 1) ? 1.0f : 0.0f;
      EXPECT_EQ(e.at(ix, iy), want) << ix << "," << iy;
    }
  }
}

TEST(Evidence, ObstacleFacingOnlyUnknownVanishes) {
  OccupancyMap m = make_map(5, 5, U);
  m.at(2, 2) = O;
  m.at(2, 3) = O;
  const EvidenceGrid e = make_thinned_evidence(m);
  for (float v : e.cells) EXPECT_EQ(v, 0.0f);
}

TEST(Resample, CoarserCellsFromTheirFineCells) {
  // 4x4 at 0.05 -> 2x2 at 0.10; coarse cell (i, j) covers fine cells 2i..2i+1, 2j..2j+1.
  OccupancyMap m = make_map(4, 4, F);
  m.at(1, 0) = O;  // coarse (0, 0): one occupied among free -> occupied
  m.at(2, 0) = U;  // coarse (1, 0): free and unknown -> unknown
  m.at(3, 1) = U;
  // coarse (0, 1): all free -> free
  m.at(2, 2) = U;  // coarse (1, 1): occupied + unknown + free -> occupied
  m.at(3, 3) = O;
  const OccupancyMap c = resample(m, 0.10);
  ASSERT_EQ(c.width(), 2);
  ASSERT_EQ(c.height(), 2);
  EXPECT_EQ(c.geometry.resolution, 0.10);
  EXPECT_EQ(c.geometry.origin, m.geometry.origin);
  EXPECT_EQ(c.geometry.yaw, m.geometry.yaw);
  EXPECT_EQ(c.at(0, 0), O);
  EXPECT_EQ(c.at(1, 0), U);
  EXPECT_EQ(c.at(0, 1), F);
  EXPECT_EQ(c.at(1, 1), O);
}

TEST(Resample, AllUnknownStaysUnknownAndOddSizesRoundUp) {
  // 5x3 at 0.05 -> 3x2 at 0.10; the last column and row form partial coarse cells.
  OccupancyMap m = make_map(5, 3, F);
  m.at(4, 0) = U;
  m.at(4, 1) = U;
  m.at(0, 2) = U;
  m.at(1, 2) = U;
  const OccupancyMap c = resample(m, 0.10);
  ASSERT_EQ(c.width(), 3);
  ASSERT_EQ(c.height(), 2);
  EXPECT_EQ(c.at(2, 0), U);  // fine (4, 0..1): all unknown
  EXPECT_EQ(c.at(0, 1), U);  // fine (0..1, 2): all unknown
  EXPECT_EQ(c.at(1, 1), F);  // fine (2..3, 2): free
  EXPECT_EQ(c.at(0, 0), F);
  EXPECT_EQ(c.at(1, 0), F);
}

TEST(Resample, FinerCellsCopyTheCellHoldingTheirCentre) {
  OccupancyMap m = make_map(2, 2, F, 0.10);
  m.at(1, 0) = O;
  m.at(0, 1) = U;
  const OccupancyMap f = resample(m, 0.05);
  ASSERT_EQ(f.width(), 4);
  ASSERT_EQ(f.height(), 4);
  for (int iy = 0; iy < 4; ++iy) {
    for (int ix = 0; ix < 4; ++ix) EXPECT_EQ(f.at(ix, iy), m.at(ix / 2, iy / 2)) << ix << "," << iy;
  }
}

TEST(Resample, SameResolutionIsIdentity) {
  OccupancyMap m = make_map(7, 5, F);
  m.at(3, 2) = O;
  m.at(6, 4) = U;
  EXPECT_EQ(resample(m, 0.05).cells, m.cells);
}

TEST(Resample, NonPositiveResolutionThrows) {
  const OccupancyMap m = make_map(4, 4, F);
  for (double r : {0.0, -0.1, std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::infinity()}) {
    test::expect_error([&] { resample(m, r); }, {"resolution"});
    test::expect_error([&] { make_global_grid(m, r, GlobalModel::Thinned); }, {"resolution"});
  }
}

TEST(GlobalGrid, IsResampleThenRawOrThinned) {
  OccupancyMap m = make_map(20, 16, F);
  for (int iy = 4; iy < 12; ++iy) {
    for (int ix = 6; ix < 16; ++ix) m.at(ix, iy) = O;
  }
  m.at(0, 0) = U;
  const OccupancyMap coarse = resample(m, 0.10);
  EXPECT_EQ(make_global_grid(m, 0.10, GlobalModel::Raw).cells, make_evidence(coarse).cells);
  EXPECT_EQ(make_global_grid(m, 0.10, GlobalModel::Thinned).cells,
            make_thinned_evidence(coarse).cells);
  // The 5x4 coarse block keeps its 14 border cells.
  const EvidenceGrid t = make_global_grid(m, 0.10, GlobalModel::Thinned);
  int plus = 0;
  for (float v : t.cells) plus += v == 1.0f;
  EXPECT_EQ(plus, 14);
}

TEST(Evidence, ResampledSizeIsCheckedBeforeTheCast) {
  // A map of 1e300 m cells (resolution: 1e300 in a YAML) resampled at 10 cm: the size is
  // refused as doubles, not cast to a garbage int (the grid collapsed to one cell).
  const OccupancyMap huge = test::filled_map(2, 2, CellState::Free, 1e300);
  test::expect_error([&] { resample(huge, 0.1); }, {"resampled", "--max-cells"});
  ResourceLimits unlimited;
  unlimited.max_cells = 1e30;  // past the cell limit: the int range still holds
  const OccupancyMap wide = test::filled_map(2, 2, CellState::Free, 1e10);
  test::expect_error([&] { resample(wide, 0.1, unlimited); }, {"too long"});
  const OccupancyMap room = test::filled_map(100, 100, CellState::Free, 0.05);
  ResourceLimits small;
  small.max_cells = 1000;
  test::expect_error([&] { make_global_grid(room, 0.05, GlobalModel::Thinned, {}, small); },
                     {"100 x 100", "--max-cells"});
  EXPECT_EQ(make_global_grid(room, 0.5, GlobalModel::Thinned, {}, small).width(), 10);
}

}  // namespace
}  // namespace gridloc
