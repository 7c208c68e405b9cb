// nscd/core/thread_share.hpp — an OpenMP thread's number and its share of a loop: one contiguous
// range each, in thread order (the detection's and the stepper's loops over contacts or pairs).
#pragma once

#include <algorithm>
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

/// Sums that do not depend on the threads are made in chunks that depend on the count only:
/// each chunk in item order, then the chunks in order. Up to kSumWhole items, one chunk (the
/// plain loop's sum: too little work for a parallel region); beyond, chunks of kSumChunk items,
/// enough of them for the threads to share evenly.
inline constexpr std::size_t kSumWhole = 4096, kSumChunk = 1024;

/// part(i0, i1, parts[k]) for each chunk k = [bounds[k], bounds[k+1]) of a range, on `threads`
/// threads when there are several chunks (static), each part fresh; the caller merges the
/// parts in chunk order, so that the result has the same bits on any number of threads.
template <class Part, class F>
void chunk_parts(const std::vector<std::size_t>& bounds, int threads, std::vector<Part>& parts, const F& part) {
  const auto m = static_cast<std::ptrdiff_t>(bounds.size() > 1 ? bounds.size() - 1 : 0);
  parts.assign(static_cast<std::size_t>(m), Part{});
  if (threads > 1 && m > 1) {
#pragma omp parallel for num_threads(static_cast<int>(std::min<std::ptrdiff_t>(threads, m))) schedule(static)
    for (std::ptrdiff_t k = 0; k < m; ++k)
      part(bounds[static_cast<std::size_t>(k)], bounds[static_cast<std::size_t>(k) + 1], parts[static_cast<std::size_t>(k)]);
  } else {
    for (std::ptrdiff_t k = 0; k < m; ++k)
      part(bounds[static_cast<std::size_t>(k)], bounds[static_cast<std::size_t>(k) + 1], parts[static_cast<std::size_t>(k)]);
  }
}

/// The bounds of [0, count)'s chunks: 0, count up to kSumWhole items; else 0, kSumChunk,
/// 2 kSumChunk, …, count.
inline void sum_chunks(std::size_t count, std::vector<std::size_t>& bounds) {
  bounds.assign(1, 0);
  const std::size_t step = count <= kSumWhole ? count : kSumChunk;
  for (std::size_t i = step; i < count; i += step) bounds.push_back(i);
  bounds.push_back(count);
}

/// Σ term(i) over [0, count), chunk by chunk (sum_chunks): the same bits on any number of
/// threads, and for up to kSumWhole items the plain loop's.
template <class F>
double ordered_sum(std::size_t count, int threads, const F& term) {
  std::vector<std::size_t> bounds;
  std::vector<double> parts;
  sum_chunks(count, bounds);
  chunk_parts(bounds, threads, parts, [&](std::size_t i0, std::size_t i1, double& sum) {
    for (std::size_t i = i0; i < i1; ++i) sum += term(i);
  });
  double total = 0.0;
  for (const double p : parts) total += p;
  return total;
}

}  // namespace nscd
