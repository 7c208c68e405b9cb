// tools/core_throughput.cpp — how much a second core adds to work that shares nothing, in three
// kinds of loop, each thread its own work: a sine and a cosine an entry (arguments below 512, so
// that every entry costs the same; each thread its half of the arrays), chains of multiply-adds
// (bound by the core's arithmetic units) and sums over a 16 KB array (bound by its L1 loads).
// Near 2× in all three says the machine gives two threads two cores' work: what a run on two
// threads loses is then what its threads share, the cache lines that cross between the cores and
// the waits at the barriers (tools/core_latency.cpp measures a crossing). The last two tell two
// cores from two hardware threads of one core, which share the arithmetic units and the L1: there
// those two stay near 1×. Below 2×, the second core is partly someone else's and bounds every
// two-thread figure measured there (docs/record/benchmarks-history.md §11.7, §11.8).
//   g++ -O2 -fopenmp tools/core_throughput.cpp -o /tmp/core_throughput && /tmp/core_throughput [ROUNDS]
// Prints each round's ratios (the 2-thread throughput over the 1-thread one) and their medians.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// ms to fill `a` with sin·cos of `b`, 20 times over, on `threads` threads (static halves)
double fill_ms(std::vector<double>& a, const std::vector<double>& b, int threads) {
  const auto n = static_cast<long>(a.size());
  const auto t0 = Clock::now();
  for (int rep = 0; rep < 20; ++rep) {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (long i = 0; i < n; ++i) a[i] = std::sin(b[i] + rep) * std::cos(b[i] * static_cast<double>(i % 1024));
  }
  return ms_since(t0);
}

using Double4 = double __attribute__((vector_size(32)));

// ms for each of `threads` threads to run 8 independent chains of x = x·m + c, 4 lanes each
double chains_ms(int threads, double& sink) {
  const auto t0 = Clock::now();
#pragma omp parallel num_threads(threads) reduction(+ : sink)
  {
    Double4 x[8];
    for (int k = 0; k < 8; ++k) x[k] = Double4{1.0, 1.0, 1.0, 1.0} + 1e-9 * k;
    const double m = 0.999999999, c = 1e-9;
    for (long i = 0; i < 25000000L; ++i)
      for (int k = 0; k < 8; ++k) x[k] = x[k] * m + c;
    for (int k = 0; k < 8; ++k) sink += x[k][0];
  }
  return ms_since(t0);
}

// ms for each of `threads` threads to sum its own 16 KB array 200,000 times
double loads_ms(int threads, double& sink) {
  const auto t0 = Clock::now();
#pragma omp parallel num_threads(threads) reduction(+ : sink)
  {
    std::vector<Double4> v(512, Double4{1.0, 1.0, 1.0, 1.0});
    Double4 s[4] = {};
    for (int r = 0; r < 200000; ++r)
      for (std::size_t i = 0; i < v.size(); i += 4)
        for (int k = 0; k < 4; ++k) s[k] += v[i + static_cast<std::size_t>(k)];
    sink += (s[0] + s[1] + s[2] + s[3])[0];
  }
  return ms_since(t0);
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  std::vector<double> a(1 << 20), b(1 << 20, 0.5);
  std::vector<double> trig, chains, loads;
  double sink = 0.0;
  for (int r = 0; r < rounds; ++r) {
    // the same total work on two threads (halves), or twice the work (each its own)
    trig.push_back(fill_ms(a, b, 1) / fill_ms(a, b, 2));
    chains.push_back(2.0 * chains_ms(1, sink) / chains_ms(2, sink));
    loads.push_back(2.0 * loads_ms(1, sink) / loads_ms(2, sink));
    std::printf("round %d: sin-cos %.2fx, multiply-add chains %.2fx, L1 loads %.2fx\n", r + 1, trig.back(),
                chains.back(), loads.back());
  }
  std::printf("median: 2 threads against one: sin-cos %.2fx, multiply-add chains %.2fx, L1 loads %.2fx (checksum %g)\n",
              median(trig), median(chains), median(loads), a[7] + (sink > 0.0 ? 0.0 : 1.0));
  return 0;
}
