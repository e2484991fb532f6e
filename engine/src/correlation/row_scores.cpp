#include "gridloc/engine/correlation/row_scores.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>

#include "gridloc/engine/correlation/fixed_point_kernel.hpp"
#include "gridloc/grids/error.hpp"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace gridloc {
namespace {

void row_scalar(const std::int8_t* grid, const std::int32_t* offset, const std::int32_t* fixed,
                std::size_t n, int run, std::int64_t* out) {
  for (std::size_t k = 0; k < n; ++k) {
    const std::int8_t* cells = grid + offset[k];
    for (int j = 0; j < run; ++j) out[j] += std::int64_t{fixed[k]} * cells[j];
  }
}

#if defined(__x86_64__)
// GCC 12's AVX-512 headers trip -Wmaybe-uninitialized on their own temporaries.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
__attribute__((target("avx512f,avx512bw,avx512vl"))) void row_avx512(const std::int8_t* grid,
                                                                     const std::int32_t* offset,
                                                                     const std::int32_t* fixed,
                                                                     std::size_t n, int run,
                                                                     std::int64_t* out) {
  // Lane j sums pose j's products; as in the per-pose kernel a product is below 2^22 in
  // magnitude, so int32 lanes are flushed to int64 every 256 cells.
  constexpr std::size_t kFlushSteps = 256;
  const auto mask = static_cast<__mmask16>((1u << run) - 1u);
  __m512i low = _mm512_setzero_si512(), high = _mm512_setzero_si512();
  std::size_t k = 0;
  while (k < n) {
    const std::size_t end = std::min(n, k + kFlushSteps);
    __m512i acc = _mm512_setzero_si512();
    for (; k < end; ++k) {
      const __m128i bytes = _mm_maskz_loadu_epi8(mask, grid + offset[k]);
      const __m512i cells = _mm512_cvtepi8_epi32(bytes);
      acc = _mm512_add_epi32(acc, _mm512_mullo_epi32(cells, _mm512_set1_epi32(fixed[k])));
    }
    low = _mm512_add_epi64(low, _mm512_cvtepi32_epi64(_mm512_castsi512_si256(acc)));
    high = _mm512_add_epi64(high, _mm512_cvtepi32_epi64(_mm512_extracti64x4_epi64(acc, 1)));
  }
  alignas(64) std::int64_t lanes[kRowRun];
  _mm512_store_si512(lanes, low);
  _mm512_store_si512(lanes + 8, high);
  for (int j = 0; j < run; ++j) out[j] += lanes[j];
}
#pragma GCC diagnostic pop
#endif

using RowSum = void (*)(const std::int8_t*, const std::int32_t*, const std::int32_t*, std::size_t,
                        int, std::int64_t*);

/// Both groups of cells (arc cells read `arc`, the others `all`) into out, zeroed first.
/// A run outside [1, kRowRun] is an error (the lanes and `out` hold kRowRun).
void both_groups(RowSum sum, const std::int8_t* arc, const std::int8_t* all,
                 const std::int32_t* offset, const std::int32_t* fixed, std::size_t arc_count,
                 std::size_t count, int run, std::int64_t* out) {
  if (run < 1 || run > kRowRun) {
    throw Error("row scores: a run of " + std::to_string(run) + " translations must lie in [1, " +
                std::to_string(kRowRun) + "]");
  }
  std::fill(out, out + run, std::int64_t{0});
  sum(arc, offset, fixed, arc_count, run, out);
  sum(all, offset + arc_count, fixed + arc_count, count - arc_count, run, out);
}

/// correlate_scalar for `run` translations at once: each pose's two sums take the same
/// terms in the same order, so each result is correlate_scalar's bit for bit; the grid's
/// values for the run are contiguous.
template <typename T>
void scalar_row(const T* arc, const T* all, const PlacedLocalGrid& local, int run, double* out) {
  double positive[kRowRun] = {}, negative[kRowRun] = {};
  const std::size_t n = local.value.size();
  for (std::size_t k = 0; k < local.arc_count; ++k) {
    const float v = local.value[k];
    const T* cells = arc + local.offset[k];
    for (int j = 0; j < run; ++j)
      positive[j] += static_cast<double>(v * static_cast<float>(cells[j]));
  }
  for (std::size_t k = local.arc_count; k < n; ++k) {
    const float v = local.value[k];
    const T* cells = all + local.offset[k];
    for (int j = 0; j < run; ++j)
      negative[j] += static_cast<double>(v * static_cast<float>(cells[j]));
  }
  for (int j = 0; j < run; ++j) out[j] = positive[j] + negative[j];
}

/// score_row's float sums, kRowRun at a time from `origin` (the row's first cell): the
/// float grid when kept, else its exact int8 copy; false for a decoded int8 grid.
bool float_row(const PaddedGrid& global, const PlacedLocalGrid& local, std::ptrdiff_t origin,
               int run, double* out) {
  for (int first = 0; first < run; first += kRowRun) {
    const int part = std::min(kRowRun, run - first);
    const std::ptrdiff_t at = origin + first;
    if (global.has_floats()) {
      scalar_row(global.arc_view().data() + at, global.grid.cells.data() + at, local, part,
                 out + first);
    } else if (global.int8_scale == 1.0f) {
      scalar_row(global.arc_view8().data() + at, global.grid8.data() + at, local, part,
                 out + first);
    } else {
      return false;
    }
  }
  return true;
}

bool use_avx512_rows() {
  static const bool use =
      avx512_row_available() && std::string_view(fixed_kernel_name()) == "avx512";
  return use;
}

}  // namespace

void correlate_fixed_row_scalar(const std::int8_t* arc, const std::int8_t* all,
                                const std::int32_t* offset, const std::int32_t* fixed,
                                std::size_t arc_count, std::size_t count, int run,
                                std::int64_t* out) {
  both_groups(&row_scalar, arc, all, offset, fixed, arc_count, count, run, out);
}

void correlate_fixed_row_avx512(const std::int8_t* arc, const std::int8_t* all,
                                const std::int32_t* offset, const std::int32_t* fixed,
                                std::size_t arc_count, std::size_t count, int run,
                                std::int64_t* out) {
#if defined(__x86_64__)
  both_groups(&row_avx512, arc, all, offset, fixed, arc_count, count, run, out);
#else
  correlate_fixed_row_scalar(arc, all, offset, fixed, arc_count, count, run, out);
#endif
}

bool avx512_row_available() {
#if defined(__x86_64__)
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512vl");
#else
  return false;
#endif
}

void correlate_fixed_row(const std::int8_t* arc, const std::int8_t* all, const std::int32_t* offset,
                         const std::int32_t* fixed, std::size_t arc_count, std::size_t count,
                         int run, std::int64_t* out) {
  if (use_avx512_rows()) {
    correlate_fixed_row_avx512(arc, all, offset, fixed, arc_count, count, run, out);
  } else {
    correlate_fixed_row_scalar(arc, all, offset, fixed, arc_count, count, run, out);
  }
}

void score_row(const PaddedGrid& global, const PlacedLocalGrid& local, int cx, int cy, int run,
               double* out) {
  const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(cy + global.pad) * global.grid.width();
  if (!(global.has_int8() && local.fixed_shift >= 0)) {
    if (float_row(global, local, row + cx + global.pad, run, out)) return;
    for (int j = 0; j < run; ++j) out[j] = score(global, local, cx + j, cy);
    return;
  }
  std::int64_t sums[kRowRun];
  for (int first = 0; first < run; first += kRowRun) {
    const int part = std::min(kRowRun, run - first);
    const std::ptrdiff_t origin = row + (cx + first + global.pad);
    correlate_fixed_row(global.arc_view8().data() + origin, global.grid8.data() + origin,
                        local.offset.data(), local.fixed.data(), local.arc_count,
                        local.offset.size(), part, sums);
    // As score(): the exact sum scaled by 2^-shift, then divided by the int8 scale.
    for (int j = 0; j < part; ++j) {
      out[first + j] = static_cast<double>(sums[j]) * fixed_point_unit(local.fixed_shift) /
                       static_cast<double>(global.int8_scale);
    }
  }
}

}  // namespace gridloc
