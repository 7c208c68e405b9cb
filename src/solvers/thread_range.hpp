// nscd/solvers/thread_range.hpp — from how many contacts the stepper's loops around the solve go
// on the threads (each thread one contiguous range, in thread order: core/thread_share.hpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "nscd/core/thread_share.hpp"

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

/// From this many items on, a light loop runs on the threads: a copy, a finiteness check, a
/// body's end-of-step update, a gather (a few nanoseconds an item), or a loop whose threads
/// write one table between them (the warm start's index) or read what the solve's threads left
/// in their own caches in another split (the contacts' end-of-step records, the projection). On
/// a small system (the paper's 724 grains, 2,300 contacts) each such loop ran slower on two
/// threads than on one: its fork and join and the cache lines that cross between the cores cost
/// more than the half a second thread takes (docs/benchmarks.md §11). A 7,000-grain deposit's
/// loops stay on the threads.
inline constexpr std::size_t kLightParallelMin = 4096;
/// The threads a light loop over `items` items runs on, of `threads` asked for.
inline int light_threads(std::size_t items, int threads) { return items >= kLightParallelMin ? threads : 1; }

/// f(i) for i = 0 … count−1, each on its own: on `threads` threads (static ranges) when
/// `threads` > 1, else in order. Loops whose results do not depend on the threads: the
/// colouring's over a large system's contacts, the stepper's over the bodies.
template <class F>
void each_index(std::size_t count, int threads, const F& f) {
  const auto m = static_cast<std::ptrdiff_t>(count);
  if (threads > 1) {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::ptrdiff_t i = 0; i < m; ++i) f(static_cast<std::size_t>(i));
  } else {
    for (std::ptrdiff_t i = 0; i < m; ++i) f(static_cast<std::size_t>(i));
  }
}

/// f(i0, i1, parts[t]) for each thread t's range [i0, i1) of [0, count), on `threads` threads,
/// `parts` made `threads` fresh Parts first: each thread's own counts, to be merged in thread order.
template <class Part, class F>
void each_range_into(std::size_t count, int threads, std::vector<Part>& parts, const F& f) {
  parts.assign(static_cast<std::size_t>(threads), Part{});
#pragma omp parallel num_threads(threads)
  {
    const auto [i0, i1] = thread_range(count);
    f(i0, i1, parts[thread_index()]);
  }
}

/// Whether pred(i) holds for every i of [0, count): on `threads` threads (static ranges) when
/// `threads` > 1, else in order up to the first that fails (the guard's finiteness checks).
template <class P>
bool all_of_index(std::size_t count, int threads, const P& pred) {
  const auto m = static_cast<std::ptrdiff_t>(count);
  if (threads <= 1) {
    for (std::ptrdiff_t i = 0; i < m; ++i)
      if (!pred(static_cast<std::size_t>(i))) return false;
    return true;
  }
  bool ok = true;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(&& : ok)
  for (std::ptrdiff_t i = 0; i < m; ++i) ok = ok && pred(static_cast<std::size_t>(i));
  return ok;
}

/// to = from: on `threads` threads from kLightParallelMin items on, each copying its own range (a
/// large system's body arrays: one thread's copy is a few hundred microseconds at 70,000 bodies).
template <class T>
void copy_on_threads(std::vector<T>& to, const std::vector<T>& from, int threads) {
  if (light_threads(from.size(), threads) <= 1) {
    to = from;
    return;
  }
  to.resize(from.size());
#pragma omp parallel num_threads(threads)
  {
    const auto [i0, i1] = thread_range(from.size());
    std::copy(from.begin() + static_cast<std::ptrdiff_t>(i0), from.begin() + static_cast<std::ptrdiff_t>(i1),
              to.begin() + static_cast<std::ptrdiff_t>(i0));
  }
}

}  // namespace nscd
