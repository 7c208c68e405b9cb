// nscd/core/thread_share.hpp — an OpenMP thread's number and its share of a loop: one contiguous
// range each, in thread order (the detection's and the stepper's loops over contacts or pairs).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace nscd {

/// This OpenMP thread's number in its team (0 outside a parallel region, or without OpenMP).
inline std::size_t thread_index() {
#ifdef _OPENMP
  return static_cast<std::size_t>(omp_get_thread_num());
#else
  return 0;
#endif
}

/// The threads of this OpenMP team (1 outside a parallel region, or without OpenMP).
inline std::size_t thread_count() {
#ifdef _OPENMP
  return static_cast<std::size_t>(omp_get_num_threads());
#else
  return 1;
#endif
}

/// This OpenMP thread's share of [0, n): contiguous ranges in thread order (one thread: all).
inline std::pair<std::size_t, std::size_t> thread_range(std::size_t n) {
  const std::size_t t = thread_index(), team = thread_count();
  return {n * t / team, n * (t + 1) / team};
}

/// A stable fill on `threads` threads: item i of [0, n) gives count(i, t) rows (t: the calling
/// thread's index), which write(i, at, t) then writes from row `at`, the rows of items in index
/// order as on one thread. Each thread counts its range of items, one thread prefixes the counts
/// (`first`: each thread's first row, scratch) and calls grow(total) to size the output, then
/// each thread writes its own. Returns the total.
template <class Count, class Grow, class Write>
std::size_t ordered_fill(std::size_t n, int threads, std::vector<std::size_t>& first, const Count& count,
                         const Grow& grow, const Write& write) {
  first.assign(static_cast<std::size_t>(threads) + 1, 0);
#pragma omp parallel num_threads(threads)
  {
    const auto [i0, i1] = thread_range(n);
    const std::size_t t = thread_index();
    std::size_t rows = 0;
    for (std::size_t i = i0; i < i1; ++i) rows += count(i, t);
    first[t + 1] = rows;
#pragma omp barrier
#pragma omp single
    {
      for (std::size_t u = 0; u + 1 < first.size(); ++u) first[u + 1] += first[u];
      grow(first.back());
    }  // (the single's own barrier: every thread sees the output sized)
    std::size_t at = first[t];
    for (std::size_t i = i0; i < i1; ++i) at += write(i, at, t);
  }
  return first.back();
}

}  // namespace nscd
