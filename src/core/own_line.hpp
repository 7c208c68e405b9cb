// nscd/core/own_line.hpp — values on cache lines of their own: per-thread values in an array,
// and arrays whose ranges threads write apart.
#pragma once

#include <cstddef>
#include <new>
#include <vector>

namespace nscd {

/// The cache line of the x86-64 and AArch64 machines nscd runs on.
inline constexpr std::size_t kCacheLine = 64;

/// One thread's list or counts among the other threads' in an array, alone on its cache lines,
/// so that a thread writing its own never writes a line another thread writes: two vectors'
/// headers side by side share a line, and each push_back would take it from the other core.
template <class T>
struct alignas(kCacheLine) OwnLine {
  T v;
};

/// An allocator whose arrays start on a cache line, so that a range of entries that starts on a
/// line's first entry shares none of its lines with the entries before it.
template <class T>
struct LineAllocator {
  using value_type = T;
  LineAllocator() = default;
  template <class U>
  LineAllocator(const LineAllocator<U>&) {}
  T* allocate(std::size_t n) {
    return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t{kCacheLine}));
  }
  void deallocate(T* p, std::size_t) { ::operator delete(p, std::align_val_t{kCacheLine}); }
  template <class U>
  bool operator==(const LineAllocator<U>&) const {
    return true;
  }
};

/// A vector whose entries start on a cache line (LineAllocator).
template <class T>
using LineVector = std::vector<T, LineAllocator<T>>;

}  // namespace nscd
