#pragma once
/// Scores of neighbouring translations on one map row at once, for the poses a search scores
/// in blocks (the covariance around the winner). On the integer path each local cell's grid
/// bytes for the whole run come from one contiguous load instead of one gather per pose; the
/// sums are exact integers, so every score equals score()'s bit for bit (tested).
#include <cstddef>
#include <cstdint>

#include "gridloc/engine/correlation/search.hpp"

namespace gridloc {

/// The most translations one row call scores.
inline constexpr int kRowRun = 16;

/// out[j] = correlate_fixed_scalar(arc + j, all + j, ...) for j in [0, run), run in
/// [1, kRowRun] (gridloc::Error otherwise, for every row function): the plain loop, the
/// reference.
void correlate_fixed_row_scalar(const std::int8_t* arc, const std::int8_t* all,
                                const std::int32_t* offset, const std::int32_t* fixed,
                                std::size_t arc_count, std::size_t count, int run,
                                std::int64_t* out);

/// The same sums from masked 16-byte loads (AVX-512F/BW/VL): reads only the bytes the run's
/// poses read. Call only when avx512_row_available().
void correlate_fixed_row_avx512(const std::int8_t* arc, const std::int8_t* all,
                                const std::int32_t* offset, const std::int32_t* fixed,
                                std::size_t arc_count, std::size_t count, int run,
                                std::int64_t* out);

/// Whether this CPU runs correlate_fixed_row_avx512.
bool avx512_row_available();

/// The AVX-512 path when correlate_fixed runs AVX-512 (fixed_kernel_name(), so GRIDLOC_SIMD
/// picks both) and the CPU has its byte loads; the scalar loop otherwise.
void correlate_fixed_row(const std::int8_t* arc, const std::int8_t* all, const std::int32_t* offset,
                         const std::int32_t* fixed, std::size_t arc_count, std::size_t count,
                         int run, std::int64_t* out);

/// out[j] = score(global, local, cx + j, cy) for j in [0, run), run >= 1; every cell must
/// lie in the map (as for score()). Integer path: correlate_fixed_row, kRowRun at a time;
/// float values (a sonar cone's) on floats or an exact int8 copy: correlate_scalar's sums
/// for kRowRun poses at once; a decoded int8 grid: score() per pose.
void score_row(const PaddedGrid& global, const PlacedLocalGrid& local, int cx, int cy, int run,
               double* out);

}  // namespace gridloc
