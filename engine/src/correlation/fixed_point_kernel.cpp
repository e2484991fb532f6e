#include "gridloc/engine/correlation/fixed_point_kernel.hpp"

#include <cstdlib>
#include <string_view>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace gridloc {
namespace {

std::int64_t sum_scalar(const std::int8_t* grid, const std::int32_t* offset,
                        const std::int32_t* fixed, std::size_t n) {
  std::int64_t sum = 0;
  for (std::size_t k = 0; k < n; ++k) sum += std::int64_t{fixed[k]} * grid[offset[k]];
  return sum;
}

#if defined(__x86_64__)
// The function carries the target attribute itself: intrinsics inline only into AVX2 code.
__attribute__((target("avx2"))) std::int64_t sum_avx2(const std::int8_t* grid,
                                                      const std::int32_t* offset,
                                                      const std::int32_t* fixed, std::size_t n) {
  // A product is at most 2^15 * 127 < 2^22 in magnitude: 256 of them per int32 lane stay
  // below 2^30, so lanes are flushed to int64 every 256 steps.
  constexpr std::size_t kFlushSteps = 256;
  std::int64_t sum = 0;
  std::size_t k = 0;
  while (k + 8 <= n) {
    __m256i acc = _mm256_setzero_si256();
    for (std::size_t step = 0; step < kFlushSteps && k + 8 <= n; ++step, k += 8) {
      const __m256i idx = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(offset + k));
      // Four bytes from each cell (kGatherSlack), the first kept and sign-extended.
      __m256i g = _mm256_i32gather_epi32(reinterpret_cast<const int*>(grid), idx, 1);
      g = _mm256_srai_epi32(_mm256_slli_epi32(g, 24), 24);
      const __m256i f = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(fixed + k));
      acc = _mm256_add_epi32(acc, _mm256_mullo_epi32(g, f));
    }
    alignas(32) std::int32_t lanes[8];
    _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), acc);
    for (std::int32_t v : lanes) sum += v;
  }
  return sum + sum_scalar(grid, offset + k, fixed + k, n - k);
}

// GCC 12's AVX-512 headers trip -Wmaybe-uninitialized on their own temporaries.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
__attribute__((target("avx512f"))) std::int64_t sum_avx512(const std::int8_t* grid,
                                                           const std::int32_t* offset,
                                                           const std::int32_t* fixed,
                                                           std::size_t n) {
  constexpr std::size_t kFlushSteps = 256;  // as sum_avx2: lanes stay below 2^30
  std::int64_t sum = 0;
  std::size_t k = 0;
  while (k + 16 <= n) {
    __m512i acc = _mm512_setzero_si512();
    for (std::size_t step = 0; step < kFlushSteps && k + 16 <= n; ++step, k += 16) {
      const __m512i idx = _mm512_loadu_si512(offset + k);
      __m512i g = _mm512_i32gather_epi32(idx, grid, 1);
      g = _mm512_srai_epi32(_mm512_slli_epi32(g, 24), 24);
      acc = _mm512_add_epi32(acc, _mm512_mullo_epi32(g, _mm512_loadu_si512(fixed + k)));
    }
    // 16 lanes of up to 2^30 overflow int32: widen before adding them.
    const __m512i low = _mm512_cvtepi32_epi64(_mm512_castsi512_si256(acc));
    const __m512i high = _mm512_cvtepi32_epi64(_mm512_extracti64x4_epi64(acc, 1));
    sum += _mm512_reduce_add_epi64(_mm512_add_epi64(low, high));
  }
  return sum + sum_scalar(grid, offset + k, fixed + k, n - k);
}
#pragma GCC diagnostic pop
#endif

using Kernel = std::int64_t (*)(const std::int8_t*, const std::int8_t*, const std::int32_t*,
                                const std::int32_t*, std::size_t, std::size_t);

struct Choice {
  Kernel kernel;
  const char* name;
};

/// The widest path the CPU has, or the one GRIDLOC_SIMD names (scalar, avx2, avx512) when
/// the CPU has it: to measure each path's gain in the full search.
Choice choose_kernel() {
  const char* env = std::getenv("GRIDLOC_SIMD");
  const std::string_view wanted = env != nullptr ? env : "";
  auto allowed = [&](std::string_view name) { return wanted.empty() || wanted == name; };
  if (avx512_available() && allowed("avx512")) return {&correlate_fixed_avx512, "avx512"};
  if (avx2_available() && allowed("avx2")) return {&correlate_fixed_avx2, "avx2"};
  return {&correlate_fixed_scalar, "scalar"};
}

const Choice& chosen() {
  static const Choice choice = choose_kernel();
  return choice;
}

}  // namespace

namespace {

using GroupSum = std::int64_t (*)(const std::int8_t*, const std::int32_t*, const std::int32_t*,
                                  std::size_t);

/// The arc cells read `arc`, the others `all`: one sum per group.
std::int64_t both_groups(GroupSum sum, const std::int8_t* arc, const std::int8_t* all,
                         const std::int32_t* offset, const std::int32_t* fixed,
                         std::size_t arc_count, std::size_t count) {
  return sum(arc, offset, fixed, arc_count) +
         sum(all, offset + arc_count, fixed + arc_count, count - arc_count);
}

}  // namespace

std::int64_t correlate_fixed_scalar(const std::int8_t* arc, const std::int8_t* all,
                                    const std::int32_t* offset, const std::int32_t* fixed,
                                    std::size_t arc_count, std::size_t count) {
  return both_groups(&sum_scalar, arc, all, offset, fixed, arc_count, count);
}

std::int64_t correlate_fixed_avx2(const std::int8_t* arc, const std::int8_t* all,
                                  const std::int32_t* offset, const std::int32_t* fixed,
                                  std::size_t arc_count, std::size_t count) {
#if defined(__x86_64__)
  return both_groups(&sum_avx2, arc, all, offset, fixed, arc_count, count);
#else
  return correlate_fixed_scalar(arc, all, offset, fixed, arc_count, count);
#endif
}

std::int64_t correlate_fixed_avx512(const std::int8_t* arc, const std::int8_t* all,
                                    const std::int32_t* offset, const std::int32_t* fixed,
                                    std::size_t arc_count, std::size_t count) {
#if defined(__x86_64__)
  return both_groups(&sum_avx512, arc, all, offset, fixed, arc_count, count);
#else
  return correlate_fixed_scalar(arc, all, offset, fixed, arc_count, count);
#endif
}

bool avx512_available() {
#if defined(__x86_64__)
  return __builtin_cpu_supports("avx512f");
#else
  return false;
#endif
}

bool avx2_available() {
#if defined(__x86_64__)
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

std::int64_t correlate_fixed(const std::int8_t* arc, const std::int8_t* all,
                             const std::int32_t* offset, const std::int32_t* fixed,
                             std::size_t arc_count, std::size_t count) {
  return chosen().kernel(arc, all, offset, fixed, arc_count, count);
}

const char* fixed_kernel_name() {
  return chosen().name;
}

}  // namespace gridloc
