// nscd/solvers/thread_range.hpp — an OpenMP thread's share of a loop over a step's contacts
// (the stepper's loops around the solve: each thread one contiguous range, in thread order).
#pragma once

#include <cstddef>
#include <utility>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace nscd {

/// This OpenMP thread's share of [0, n): contiguous ranges in thread order (one thread: all).
inline std::pair<std::size_t, std::size_t> thread_range(std::size_t n) {
#ifdef _OPENMP
  const auto t = static_cast<std::size_t>(omp_get_thread_num()), team = static_cast<std::size_t>(omp_get_num_threads());
#else
  const std::size_t t = 0, team = 1;
#endif
  return {n * t / team, n * (t + 1) / team};
}

}  // namespace nscd
