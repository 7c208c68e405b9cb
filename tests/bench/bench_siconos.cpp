// tests/bench/bench_siconos.cpp — NLGS on the Siconos granular problems (Google Benchmark):
// sweeps and time to reach a relative natural-map error, from r = 0.
//
// Problems: fc2d_granularflowonwall_02020_00213 (2020 contacts) and _07002_00801 (7002), from
// shared/data/siconos-fc2d (README there: Siconos' NSGS needs 567 sweeps, 0.064 s, for 1e-4 on
// the 2020 one, and reaches no better than 5.4e-7 in 10^4 sweeps).
// Targets: relative_q = natural map / |q| <= 1e-4, 1e-6, 1e-8. NLGS (fixed order, ω = 1; the
// _relaxW rows over-relaxed, ω = W) runs in
// chunks of exactly 10 sweeps, the impulses carried from chunk to chunk (warm r), and the
// natural-map error is computed after each chunk; it stops when the target is met or at
// 100000 sweeps (then reached = 0).
//
// Counters: sweeps, relative_q and relative_siconos reached (Siconos divides by
// max(|q|, |r|, |u|)), reached (1/0), nlgs_seconds (the sweeps alone) and the benchmark's
// own real time (sweeps plus the error checks, one iteration).
// Data: $NSCD_TEST_DATA_DIR/siconos-fc2d if set, else the build's copy of tests/data (the
// configure step extracts the compressed 7002-contact file there).
// Run (Release build):
//   build/tests/bench_siconos --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "nscd/core/error.hpp"
#include "nscd/solvers/local_problem.hpp"
#include "nscd/solvers/nlgs.hpp"

using namespace nscd;
namespace fs = std::filesystem;

namespace {

constexpr int kChunk = 10;           // sweeps between error checks
constexpr int kMaxSweeps = 100000;

fs::path data_dir() {
  if (const char* env = std::getenv("NSCD_TEST_DATA_DIR")) return fs::path(env) / "siconos-fc2d";
  return fs::path(NSCD_TEST_DATA_DIR) / "siconos-fc2d";  // the build's copy (top-level CMakeLists.txt)
}

/// Problems are read once (the 7002-contact file takes ~0.1 s) and shared by the benchmarks.
const FrictionProblem2D* problem(const std::string& name, std::string& error) {
  static std::map<std::string, std::unique_ptr<FrictionProblem2D>> cache;
  auto& p = cache[name];
  if (!p) {
    try {
      p = std::make_unique<FrictionProblem2D>(read_siconos_fc2d(data_dir() / name));
    } catch (const Error& e) {
      error = e.what();
      return nullptr;
    }
  }
  return p.get();
}

void BM_NlgsToError(benchmark::State& state, const std::string& name, double target, double omega = 1.0) {
  std::string error;
  const FrictionProblem2D* p = problem(name, error);
  if (!p) {
    state.SkipWithError(error.c_str());
    return;
  }
  NlgsOptions o;
  o.policy = ConvergencePolicy::Quad;
  o.min_sweeps = o.max_sweeps = kChunk;  // exactly one chunk per call, whatever the criteria say
  o.check_every = kChunk;
  o.relaxation = omega;
  int sweeps = 0;
  double nlgs_seconds = 0.0;
  ProblemError e;
  std::vector<double> r;
  for (auto _ : state) {
    r.assign(2 * p->nc, 0.0);
    sweeps = 0;
    nlgs_seconds = 0.0;
    do {
      const auto t0 = std::chrono::steady_clock::now();
      sweeps += nlgs_solve(*p, r, o).sweeps;
      nlgs_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      e = natural_map_error(*p, r);
    } while (e.relative_q > target && sweeps < kMaxSweeps);
    benchmark::DoNotOptimize(r.data());
  }
  state.counters["contacts"] = static_cast<double>(p->nc);
  state.counters["target"] = target;
  state.counters["omega"] = omega;
  state.counters["sweeps"] = sweeps;
  state.counters["relative_q"] = e.relative_q;
  state.counters["relative_siconos"] = e.relative_siconos;
  state.counters["reached"] = e.relative_q <= target ? 1.0 : 0.0;
  state.counters["nlgs_seconds"] = nlgs_seconds;
}

const std::string k2020 = "fc2d_granularflowonwall_02020_00213.dat";
const std::string k7002 = "fc2d_granularflowonwall_07002_00801.dat";

}  // namespace

#define NSCD_SICONOS_BENCH(tag, file, target)                                                  \
  BENCHMARK_CAPTURE(BM_NlgsToError, tag, file, target)->Iterations(1)->UseRealTime()->Unit( \
      benchmark::kMillisecond)

NSCD_SICONOS_BENCH(flow2020_1e-4, k2020, 1e-4);
NSCD_SICONOS_BENCH(flow2020_1e-6, k2020, 1e-6);
NSCD_SICONOS_BENCH(flow2020_1e-8, k2020, 1e-8);
NSCD_SICONOS_BENCH(flow7002_1e-4, k7002, 1e-4);
NSCD_SICONOS_BENCH(flow7002_1e-6, k7002, 1e-6);
NSCD_SICONOS_BENCH(flow7002_1e-8, k7002, 1e-8);

// Over-relaxation (issue #8): the same protocol with ω = 1.2 ... 1.6 (checked sweeps plain,
// theory §9.5); the tag ends with ω.
#define NSCD_SICONOS_RELAX(tag, file, target, omega)                                                   \
  BENCHMARK_CAPTURE(BM_NlgsToError, tag, file, target, omega)->Iterations(1)->UseRealTime()->Unit( \
      benchmark::kMillisecond)

NSCD_SICONOS_RELAX(flow2020_1e-6_relax1.2, k2020, 1e-6, 1.2);
NSCD_SICONOS_RELAX(flow2020_1e-6_relax1.3, k2020, 1e-6, 1.3);
NSCD_SICONOS_RELAX(flow2020_1e-6_relax1.4, k2020, 1e-6, 1.4);
NSCD_SICONOS_RELAX(flow2020_1e-6_relax1.5, k2020, 1e-6, 1.5);
NSCD_SICONOS_RELAX(flow2020_1e-6_relax1.6, k2020, 1e-6, 1.6);
NSCD_SICONOS_RELAX(flow2020_1e-8_relax1.3, k2020, 1e-8, 1.3);
NSCD_SICONOS_RELAX(flow7002_1e-6_relax1.2, k7002, 1e-6, 1.2);
NSCD_SICONOS_RELAX(flow7002_1e-6_relax1.3, k7002, 1e-6, 1.3);
NSCD_SICONOS_RELAX(flow7002_1e-6_relax1.4, k7002, 1e-6, 1.4);
NSCD_SICONOS_RELAX(flow7002_1e-6_relax1.5, k7002, 1e-6, 1.5);
NSCD_SICONOS_RELAX(flow7002_1e-6_relax1.6, k7002, 1e-6, 1.6);
NSCD_SICONOS_RELAX(flow7002_1e-8_relax1.3, k7002, 1e-8, 1.3);
