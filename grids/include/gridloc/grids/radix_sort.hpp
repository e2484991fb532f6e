#pragma once
/// A stable LSD radix sort of unsigned keys by 8-bit digits: for the few hundred to few
/// thousand cell indices of a local grid, cheaper than std::sort's comparisons.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace gridloc {

/// Sorts `keys` by the bits [low_bit, low_bit + bits) of each key, stably (keys equal there
/// keep their order), using `scratch` as buffer.
template <typename Key>
void radix_sort(std::vector<Key>& keys, std::vector<Key>& scratch, int low_bit, int bits) {
  scratch.resize(keys.size());
  for (int shift = low_bit; shift < low_bit + bits; shift += 8) {
    std::size_t count[257] = {};
    for (Key k : keys) ++count[((k >> shift) & 255u) + 1];
    for (std::size_t b = 1; b < 257; ++b) count[b] += count[b - 1];
    for (Key k : keys) scratch[count[(k >> shift) & 255u]++] = k;
    keys.swap(scratch);
  }
}

/// Bits needed to hold values below `bound` (at least 1).
inline int bits_below(std::uint64_t bound) {
  int bits = 1;
  while (bits < 64 && (std::uint64_t{1} << bits) < bound) ++bits;
  return bits;
}

}  // namespace gridloc
