#pragma once
/// The correlation kernel on integer lanes: sum over k of fixed[k] * grid[offset[k]] for
/// int8 grids, the first `arc_count` cells reading `arc`, the rest `all`. Integer sums are
/// exact in any order, so the vector paths equal the scalar reference exactly (tested on
/// random inputs).
#include <cstddef>
#include <cstdint>

namespace gridloc {

/// Bytes that must stay readable after the last cell of an int8 grid the kernel reads: the
/// vector path loads 4 bytes per cell and keeps the first.
inline constexpr std::size_t kGatherSlack = 3;

/// Plain loop, the reference. |fixed[k]| <= 2^15 and |grid| <= 127 keep every partial sum
/// far inside int64.
std::int64_t correlate_fixed_scalar(const std::int8_t* arc, const std::int8_t* all,
                                    const std::int32_t* offset, const std::int32_t* fixed,
                                    std::size_t arc_count, std::size_t count);

/// AVX2 gathers, 8 cells per step. Call only when avx2_available().
std::int64_t correlate_fixed_avx2(const std::int8_t* arc, const std::int8_t* all,
                                  const std::int32_t* offset, const std::int32_t* fixed,
                                  std::size_t arc_count, std::size_t count);

/// AVX-512F gathers, 16 cells per step. Call only when avx512_available().
std::int64_t correlate_fixed_avx512(const std::int8_t* arc, const std::int8_t* all,
                                    const std::int32_t* offset, const std::int32_t* fixed,
                                    std::size_t arc_count, std::size_t count);

/// Whether this CPU runs correlate_fixed_avx512 (x86-64 with AVX-512F).
bool avx512_available();

/// Whether this CPU runs correlate_fixed_avx2 (x86-64 with AVX2; false elsewhere).
bool avx2_available();

/// The fastest path this CPU has, chosen once at run time: AVX-512, AVX2, else scalar.
/// GRIDLOC_SIMD=scalar|avx2|avx512 in the environment picks one (if the CPU has it).
std::int64_t correlate_fixed(const std::int8_t* arc, const std::int8_t* all,
                             const std::int32_t* offset, const std::int32_t* fixed,
                             std::size_t arc_count, std::size_t count);

/// The path correlate_fixed uses: "avx512", "avx2" or "scalar".
const char* fixed_kernel_name();

}  // namespace gridloc
