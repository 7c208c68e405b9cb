// tools/omp_region_cost.cpp — what one OpenMP parallel region (fork and join, static ranges)
// costs at 2 threads here, against a loop of N light iterations on one thread: the figure
// behind the threads' thresholds (kLoopParallelMin, contact_system.hpp; kDetectParallelMin,
// plplx.cpp; docs/benchmarks.md, "Threads: the thresholds").
//   g++ -O2 -fopenmp tools/omp_region_cost.cpp -o /tmp/omp_region_cost && /tmp/omp_region_cost
// Prints, per N, the median over 201 rounds of ns per call: one thread (no region), and two
// threads (one region).
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

int main() {
  using Clock = std::chrono::steady_clock;
  std::vector<double> a(1 << 16, 1.0), b(1 << 16, 0.0);
  // a per-item body of about the cost of a contact's record in the stepper's loops (a few tens
  // of nanoseconds: a dependent chain of square roots)
  auto body = [&](long i) {
    double x = a[i] + b[i];
    for (int k = 0; k < 6; ++k) x = std::sqrt(x * 1.0001 + 0.5);
    b[i] = x;
  };
  auto run = [&](long n, int threads) {
    if (threads == 1) {
      for (long i = 0; i < n; ++i) body(i);
      return;
    }
#pragma omp parallel num_threads(threads)
    {
      const long t = omp_get_thread_num(), team = omp_get_num_threads();
      for (long i = n * t / team; i < n * (t + 1) / team; ++i) body(i);
    }
  };
  std::printf("%8s %14s %14s %8s\n", "N", "1 thread ns", "2 threads ns", "speed-up");
  for (long n : {0L, 64L, 128L, 256L, 512L, 1024L, 2048L, 4096L, 8192L}) {
    double med[2];
    for (int k = 0; k < 2; ++k) {
      const int threads = k + 1;
      std::vector<double> ns;
      for (int r = 0; r < 201; ++r) {
        const int calls = 200;
        const auto t0 = Clock::now();
        for (int c = 0; c < calls; ++c) run(n, threads);
        ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / calls);
      }
      std::nth_element(ns.begin(), ns.begin() + 100, ns.end());
      med[k] = ns[100];
    }
    std::printf("%8ld %14.0f %14.0f %8.2f\n", n, med[0], med[1], med[1] > 0 ? med[0] / med[1] : 0.0);
  }
}
