#pragma once
/// An allocator for the big grids (a padded map, a bound pyramid's levels). A block of
/// kLargeBlockBytes or more gets its own mapping, aligned to 2 MiB (a last part of 1 MiB or
/// more rounded up to a whole 2 MiB page, a shorter one left in small pages) and advised as
/// transparent huge pages where the kernel offers them (Linux: MADV_HUGEPAGE on that
/// mapping only, no process-wide setting), so filling it takes one page fault per 2 MiB
/// instead of one per 4 KiB: on a virtual machine a fault costs microseconds, and filling
/// the levels of a 20 m padded map was most of a global search's precomputation. Smaller
/// blocks, other systems and builds with AddressSanitizer use operator new.
#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

namespace gridloc {

/// Blocks from this size on are mapped on their own (1 MiB: half a huge page).
inline constexpr std::size_t kLargeBlockBytes = std::size_t{1} << 20;

/// Whether blocks of kLargeBlockBytes or more get their own huge-page mapping in this build.
bool maps_large_blocks();
/// Raw storage for LargePageAllocator: throws std::bad_alloc when none is left.
void* allocate_large(std::size_t bytes);
/// Gives back what allocate_large(bytes) returned, with the same `bytes`.
void deallocate_large(void* block, std::size_t bytes) noexcept;

template <typename T>
struct LargePageAllocator {
  using value_type = T;
  LargePageAllocator() = default;
  template <typename U>
  explicit LargePageAllocator(const LargePageAllocator<U>& /*other*/) noexcept {}
  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(allocate_large(n * sizeof(T)));
  }
  void deallocate(T* block, std::size_t n) noexcept { deallocate_large(block, n * sizeof(T)); }
  template <typename U>
  bool operator==(const LargePageAllocator<U>& /*other*/) const noexcept {
    return true;
  }
};

/// int8 cells of a big grid (row-major), in large pages.
using Int8Cells = std::vector<std::int8_t, LargePageAllocator<std::int8_t>>;

}  // namespace gridloc
