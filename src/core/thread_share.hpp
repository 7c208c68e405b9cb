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

/// The chunks of [0, count): one up to kSumWhole items, else kSumChunk items each (the last
/// shorter): how many, and where chunk k starts (k = their count: count).
inline std::size_t sum_chunk_count(std::size_t count) {
  return count <= kSumWhole ? 1 : (count + kSumChunk - 1) / kSumChunk;
}
inline std::size_t sum_chunk_start(std::size_t count, std::size_t k) {
  return count <= kSumWhole ? (k == 0 ? 0 : count) : std::min(count, k * kSumChunk);
}

/// part(bound(k), bound(k + 1), p) into a fresh Part p for each chunk k of `chunks`, then
/// merge(p) in chunk order, so that the result has the same bits on any number of threads: the
/// parts made on `threads` threads when there are several chunks (static), else one chunk
/// after the other, with no scratch.
template <class Part, class Bound, class F, class M>
void reduce_chunks(std::size_t chunks, const Bound& bound, int threads, const F& part, const M& merge) {
  if (threads > 1 && chunks > 1) {
    std::vector<Part> parts(chunks);
    const auto m = static_cast<std::ptrdiff_t>(chunks);
#pragma omp parallel for num_threads(static_cast<int>(std::min<std::ptrdiff_t>(threads, m))) schedule(static)
    for (std::ptrdiff_t k = 0; k < m; ++k) {
      const auto u = static_cast<std::size_t>(k);
      part(bound(u), bound(u + 1), parts[u]);
    }
    for (const Part& p : parts) merge(p);
    return;
  }
  for (std::size_t k = 0; k < chunks; ++k) {
    Part p{};
    part(bound(k), bound(k + 1), p);
    merge(p);
  }
}

/// Σ term(i) over [0, count), chunk by chunk (sum_chunk_count): the same bits on any number of
/// threads, and for up to kSumWhole items the plain loop's.
template <class F>
double ordered_sum(std::size_t count, int threads, const F& term) {
  double total = 0.0;
  reduce_chunks<double>(
      sum_chunk_count(count), [count](std::size_t k) { return sum_chunk_start(count, k); }, threads,
      [&](std::size_t i0, std::size_t i1, double& sum) {
        for (std::size_t i = i0; i < i1; ++i) sum += term(i);
      },
      [&](double sum) { total += sum; });
  return total;
}

}  // namespace nscd
