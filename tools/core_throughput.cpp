// tools/core_throughput.cpp — how much a second core adds to work that shares nothing: the same
// arithmetic loop (a sine and a cosine an entry, of arguments below 512 so that every entry costs
// the same; each thread its own half of the arrays) on one thread, then on two. Near 2× says the
// machine gives two threads two cores' work, so that what a run on two threads loses is what its
// threads share: the cache lines that cross between the cores and the waits at the barriers
// (tools/core_latency.cpp measures a crossing). Below 2×, the second core is partly someone
// else's and bounds every two-thread figure measured there (docs/benchmarks.md §11.7).
//   g++ -O2 -fopenmp tools/core_throughput.cpp -o /tmp/core_throughput && /tmp/core_throughput [ROUNDS]
// Prints each round's times (ms) at 1 and 2 threads and the median of their ratios.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

// ms to fill `a` with sin·cos of `b`, 20 times over, on `threads` threads (static halves)
double fill_ms(std::vector<double>& a, const std::vector<double>& b, int threads) {
  const auto n = static_cast<long>(a.size());
  const auto t0 = std::chrono::steady_clock::now();
  for (int rep = 0; rep < 20; ++rep) {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (long i = 0; i < n; ++i) a[i] = std::sin(b[i] + rep) * std::cos(b[i] * static_cast<double>(i % 1024));
  }
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  std::vector<double> a(1 << 20), b(1 << 20, 0.5);
  std::vector<double> ratio;
  for (int r = 0; r < rounds; ++r) {
    const double one = fill_ms(a, b, 1), two = fill_ms(a, b, 2);
    ratio.push_back(one / two);
    std::printf("round %d: 1 thread %.1f ms, 2 threads %.1f ms, %.2fx\n", r + 1, one, two, one / two);
  }
  std::nth_element(ratio.begin(), ratio.begin() + rounds / 2, ratio.end());
  std::printf("median: 2 threads %.2fx one (a[7] = %g)\n", ratio[rounds / 2], a[7]);
  return 0;
}
