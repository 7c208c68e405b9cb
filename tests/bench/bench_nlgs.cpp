// tests/bench/bench_nlgs.cpp — cost of one NLGS contact update in a running scene (Google
// Benchmark): the quantity behind every sweep of every step.
//
// Scene: pentagon_field(N, 1 cm, pitch 0.9 cm), N = 700, 7,000 and 70,000 — about 2.5 contact points
// per grain (IQS_CLB, μ = 0.5) — without gravity, every grain moving toward the field's centre
// at 0.1 m/s per metre of distance, so that the contacts are compressed and the solver has real
// work (sticking and sliding contacts, forces spreading through the field). Each iteration
// redoes begin_step / detect / prepare with the timer paused, then times solve() with exactly
// 50 sweeps (min_sweeps = max_sweeps).
//
// BM_NlgsColorContacts times the colored order's colouring and layout of the same systems, which
// MoreauJean::prepare does once per step (outside BM_NlgsContactUpdate's timer, as the rest of
// prepare is for every order), on 1 or 2 threads (wall time).
//
// Counter: sec_per_update = solve time / (sweeps × contact points), printed with an SI prefix
// (15n = 15 ns). colored_threads: 0 = the fixed order; t > 0 = the colored order
// (nlgs_colored.hpp) on t threads (same numbers for every t); lanes: the colored order's SIMD
// lanes (nlgs_lanes.hpp), 0 = scalar, 4 = AVX2 (same numbers). Run (Release build):
//   build/tests/bench_nlgs --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "nscd/shared/samples.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "nscd/solvers/nlgs_colored.hpp"

using namespace nscd;

namespace {

constexpr int kSweeps = 50;

/// range(1): 0 = fixed order; t > 0 = colored order on t threads; range(2): its lanes (0: scalar).
void BM_NlgsContactUpdate(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto threads = static_cast<int>(state.range(1));
  const auto lanes = static_cast<int>(state.range(2));
  scenes::Scene s = scenes::pentagon_field(n, 0.01, 0.009);
  s.reg.params.gravity = {0.0, 0.0};
  scenes::converge_to_centroid(s.reg, 0.1);
  StepperOptions o;
  o.nlgs.min_sweeps = kSweeps;  // exactly kSweeps sweeps
  o.nlgs.max_sweeps = kSweeps;
  o.nlgs.check_every = 10;
  if (threads > 0) {
    o.nlgs.order = SweepOrder::Colored;
    o.nlgs.threads = threads;
    o.threads = threads;
    o.nlgs.lanes = lanes;
  }
  const Registry reg0 = s.reg;
  // One stepper for every iteration, so that its buffers are warm as from step to step of a
  // run (a fresh one would time the first touch of the colored order's bundles); each
  // iteration starts from the same state and an empty warm-start memory.
  Registry reg = reg0;
  MoreauJean mj(reg, o);
  double updates = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    reg = reg0;
    mj.set_warm_start_memory({});
    mj.begin_step();
    mj.detect();
    mj.prepare();
    state.ResumeTiming();
    mj.solve();
    state.PauseTiming();
    mj.end_step();
    updates = static_cast<double>(mj.report().sweeps) * static_cast<double>(reg.contacts.size());
    state.counters["contacts"] = static_cast<double>(reg.contacts.size());
    std::size_t active = 0;
    for (double rn : reg.contacts.rn) active += rn > 0.0;
    state.counters["active_share"] = static_cast<double>(active) / static_cast<double>(reg.contacts.size());
    state.ResumeTiming();
  }
  state.counters["sec_per_update"] =
      benchmark::Counter(updates, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

/// The colored order's colouring and layout (color_contacts), done once per step in
/// MoreauJean::prepare and so outside BM_NlgsContactUpdate's timer: on a copy of the prepared
/// system each time, with a warm workspace (its buffers reused, as from step to step).
void BM_NlgsColorContacts(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto threads = static_cast<int>(state.range(1));
  scenes::Scene s = scenes::pentagon_field(n, 0.01, 0.009);
  s.reg.params.gravity = {0.0, 0.0};
  StepperOptions o;
  MoreauJean mj(s.reg, o);
  mj.begin_step();
  mj.detect();
  mj.prepare();
  NlgsColoredWorkspace ws;
  ContactSystem sys = mj.system();
  color_contacts(sys, ws);  // warm the buffers
  for (auto _ : state) {
    state.PauseTiming();
    sys = mj.system();
    state.ResumeTiming();
    color_contacts(sys, ws, SweepOrder::Colored, threads);
  }
  state.counters["contacts"] = static_cast<double>(sys.contacts.size());
  state.counters["sec_per_contact"] = benchmark::Counter(static_cast<double>(sys.contacts.size()),
                                                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(BM_NlgsColorContacts)
    ->ArgNames({"grains", "threads"})
    ->ArgsProduct({{700, 7000, 70000}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

/// fixed order (colored_threads 0); colored order on 1 and 2 threads, scalar (lanes 0) and in
/// SIMD lanes (lanes 4: AVX2, or SSE2 where the CPU lacks AVX2).
void nlgs_args(benchmark::internal::Benchmark* b) {
  for (long grains : {700, 7000, 70000}) {
    b->Args({grains, 0, 0});
    for (long threads : {1, 2})
      for (long lanes : {0, 4}) b->Args({grains, threads, lanes});
  }
}

BENCHMARK(BM_NlgsContactUpdate)
    ->ArgNames({"grains", "colored_threads", "lanes"})
    ->Apply(nlgs_args)
    ->Unit(benchmark::kMillisecond);
