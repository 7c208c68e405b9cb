// nscd/core/thread_share.hpp — an OpenMP thread's number and its share of a loop: one contiguous
// range each, in thread order (the detection's and the stepper's loops over contacts or pairs).
#pragma once

#include <cstddef>
#include <utility>
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

}  // namespace nscd
