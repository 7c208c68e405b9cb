// nscd/core/own_line.hpp — values on cache lines of their own: per-thread values in an array,
// and arrays whose ranges threads write apart.
#pragma once

#include <cstddef>
#include <new>
#include <vector>

namespace nscd {

/// The cache line of the x86-64 and AArch64 machines nscd runs on, and their smallest page (a
/// core's hardware prefetchers fetch ahead within a page, never across).
inline constexpr std::size_t kCacheLine = 64, kPage = 4096;

/// i rounded up to a multiple of m: a count of entries made whole lines or pages.
inline constexpr std::size_t round_up(std::size_t i, std::size_t m) { return (i + m - 1) / m * m; }

/// One thread's list or counts among the other threads' in an array, alone on its cache lines,
/// so that a thread writing its own never writes a line another thread writes: two vectors'
/// headers side by side share a line, and each push_back would take it from the other core.
template <class T>
struct alignas(kCacheLine) OwnLine {
  T v;
};

/// An allocator whose arrays start on a multiple of `Align` bytes (a cache line, a page), so
/// that a range of entries that starts on such a boundary shares none of its lines (its pages)
/// with the entries before it.
template <class T, std::size_t Align>
struct AlignedAllocator {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = AlignedAllocator<U, Align>;
  };
  AlignedAllocator() = default;
  template <class U>
  AlignedAllocator(const AlignedAllocator<U, Align>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t{Align})); }
  void deallocate(T* p, std::size_t) { ::operator delete(p, std::align_val_t{Align}); }
  template <class U>
  bool operator==(const AlignedAllocator<U, Align>&) const {
    return true;
  }
};

/// Asks for the cache line of `p` to write it (x86's PREFETCHW, a no-op on cores without it):
/// a line another core read since this core last wrote it must be taken back from that core
/// before the write, and the stores after a write that waits for its line wait too. Asked for
/// ahead, many such lines travel at once, while the core works on.
inline void claim_line(const void* p) {
#if defined(__x86_64__) || defined(__i386__)
  asm volatile("prefetchw %0" : : "m"(*static_cast<const char*>(p)));
#else
  __builtin_prefetch(p, 1);
#endif
}

/// A vector whose entries start on a cache line, or on a page.
template <class T>
using LineVector = std::vector<T, AlignedAllocator<T, kCacheLine>>;
template <class T>
using PageVector = std::vector<T, AlignedAllocator<T, kPage>>;

}  // namespace nscd
