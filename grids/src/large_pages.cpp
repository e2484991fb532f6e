#include "gridloc/grids/large_pages.hpp"

// Under AddressSanitizer the blocks come from operator new, whose bounds it checks.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GRIDLOC_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define GRIDLOC_ASAN 1
#endif
#if defined(__linux__) && !defined(GRIDLOC_ASAN)
#define GRIDLOC_MAPPED_BLOCKS 1
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace gridloc {

#if defined(GRIDLOC_MAPPED_BLOCKS)

namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;

std::size_t page_size() {
  static const auto size = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  return size;
}

std::size_t rounded_up(std::size_t bytes, std::size_t unit) {
  return (bytes + unit - 1) / unit * unit;
}

/// The mapping of a block: whole huge pages, and a last part under kLargeBlockBytes in small
/// pages (a huge page for it would waste more than it holds).
std::size_t mapping_length(std::size_t bytes) {
  const std::size_t tail = bytes % kHugePage;
  return tail >= kLargeBlockBytes ? rounded_up(bytes, kHugePage) : rounded_up(bytes, page_size());
}

}  // namespace

bool maps_large_blocks() {
  return true;
}

void* allocate_large(std::size_t bytes) {
  if (bytes < kLargeBlockBytes) return ::operator new(bytes);
  if (bytes > static_cast<std::size_t>(-1) / 2) throw std::bad_alloc();
  // Map one huge page more than needed, then give back the unaligned head and tail: the
  // block starts on a huge page.
  const std::size_t size = mapping_length(bytes);
  const std::size_t mapped_size = size + kHugePage;
  void* mapped =
      mmap(nullptr, mapped_size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapped == MAP_FAILED) throw std::bad_alloc();
  const auto start = reinterpret_cast<std::uintptr_t>(mapped);
  const std::uintptr_t aligned = rounded_up(start, kHugePage);
  const std::uintptr_t end = aligned + size;
  if (aligned > start) munmap(mapped, aligned - start);
  if (start + mapped_size > end) munmap(reinterpret_cast<void*>(end), start + mapped_size - end);
  void* block = reinterpret_cast<void*>(aligned);
  madvise(block, size, MADV_HUGEPAGE);  // advice only: without huge pages, small pages
  return block;
}

void deallocate_large(void* block, std::size_t bytes) noexcept {
  if (block == nullptr) return;
  if (bytes < kLargeBlockBytes) {
    ::operator delete(block);
    return;
  }
  munmap(block, mapping_length(bytes));
}

#else

bool maps_large_blocks() {
  return false;
}
void* allocate_large(std::size_t bytes) {
  return ::operator new(bytes);
}
void deallocate_large(void* block, std::size_t /*bytes*/) noexcept {
  ::operator delete(block);
}

#endif

}  // namespace gridloc
