// nscd/solvers/thread_range.hpp — an OpenMP thread's share of a loop over a step's contacts
// (the stepper's loops around the solve: each thread one contiguous range, in thread order), and
// from how many contacts such a loop goes on the threads.
#pragma once

#include <cstddef>
#include <utility>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace nscd {

/// From this many contacts on, the loops over a step's contacts outside the sweep run on the
/// threads asked for: the stepper's loops around the solve (records built, warm-start lookups,
/// end-of-step records, the step guard) and the colouring's heavier passes (each contact's strip,
/// the records' copy). Each visits a contact once for tens of nanoseconds, and a parallel region
/// (its fork and join) costs a few microseconds at 2 threads: from a few hundred contacts on, the
/// half of the loop a second thread takes saves more than the region costs (docs/benchmarks.md,
/// "Threads: the thresholds"). A contact's result never depends on the threads (each its own
/// record; the sums made after, in contact order). The colored sweep's own layout decisions stay
/// at kParallelMin (contact_system.hpp).
inline constexpr std::size_t kLoopParallelMin = 512;
/// The threads a loop over `contacts` contacts outside the sweep runs on, of `threads` asked for.
inline int loop_threads(std::size_t contacts, int threads) { return contacts >= kLoopParallelMin ? threads : 1; }

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
