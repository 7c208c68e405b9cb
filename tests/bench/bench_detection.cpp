// tests/bench/bench_detection.cpp — cost of PLPLx contact detection per body (Google Benchmark).
//
// Scene: pentagon_field(N, 1 cm, pitch 0.9 cm) — N equal pentagons on a square lattice,
// random orientations, N = 700 and 70,000. At this pitch almost every lattice neighbour is
// within the alert distance (1.25 mm): about 1.9 contact pairs and 2.5 contact points per
// body, i.e. each grain touches ~3.8 of its 4 neighbours, ~20 % of the pairs edge–edge.
//
//   BM_Detect       detect_plplx as a time step calls it: world geometry, broad phase,
//                   narrow phase, filling reg.contacts (warm workspace, no allocation);
//                   kept:1 the broad phase's kept list reused (the boxes have not moved by a
//                   quarter margin since it was built: find_pairs_reusing), kept:0 rebuilt.
//   BM_BroadPhase   find_pairs alone on the same bounding boxes (grid of tiles), on 1 or 2
//                   threads (wall time).
//   BM_BroadPhaseReusing  find_pairs_reusing on unchanged boxes: the kept list filtered.
//   BM_NarrowPhase  shadow_overlap alone on the same candidate pairs.
//
// Counters: sec_per_body = CPU time per iteration / N (Google Benchmark rates use the CPU
// time; printed with an SI prefix: 80n = 80 ns), points_per_body (contact points found),
// pairs_per_body (candidate pairs from the broad phase, diagonal neighbours included).
// Run (Release build):
//   build/tests/bench_detection --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdint>
#include <map>
#include <memory>

#include "nscd/interactions/broad_phase.hpp"
#include "nscd/interactions/plplx.hpp"
#include "nscd/interactions/shadow_overlap.hpp"
#include "nscd/shared/samples.hpp"

using namespace nscd;

namespace {

constexpr double kDiameter = 0.01;            // 1 cm pentagons
constexpr double kPitch = 0.9 * kDiameter;    // touching or slightly overlapping neighbours

// One scene per size, built once and shared by the three benchmarks, with a detector warmed
// by one detection (world geometry, boxes and pairs ready for the partial benchmarks).
struct Prepared {
  scenes::Scene scene;
  PlplxDetector det;
  DetectionStats stats;
};

Prepared& prepared(std::size_t n) {
  static std::map<std::size_t, std::unique_ptr<Prepared>> cache;
  auto& p = cache[n];
  if (!p) {
    p = std::make_unique<Prepared>(Prepared{scenes::pentagon_field(n, kDiameter, kPitch), {}, {}});
    p->stats = detect_plplx(p->scene.reg, p->det);
  }
  return *p;
}

void set_counters(benchmark::State& state, std::size_t n, const DetectionStats& st) {
  const double N = static_cast<double>(n);
  state.counters["sec_per_body"] =
      benchmark::Counter(N, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["points_per_body"] = static_cast<double>(st.contact_points) / N;
  state.counters["pairs_per_body"] = static_cast<double>(st.candidate_pairs) / N;
}

void BM_Detect(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  Prepared& p = prepared(n);
  p.det.threads = static_cast<int>(state.range(1));  // narrow phase threads (same contacts)
  const bool keep = state.range(2) != 0;              // the broad phase's kept list reused, or rebuilt
  DetectionStats st;
  for (auto _ : state) {
    if (!keep) p.det.broad.built.clear();
    st = detect_plplx(p.scene.reg, p.det);
    benchmark::DoNotOptimize(p.scene.reg.contacts.gap.data());
    benchmark::ClobberMemory();
  }
  p.det.threads = 1;
  set_counters(state, n, st);
}

void BM_BroadPhase(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto threads = static_cast<int>(state.range(1));
  Prepared& p = prepared(n);
  BroadPhase ws;  // own workspace, warmed by the first iteration like the detector's
  for (auto _ : state) {
    find_pairs(p.det.box, p.scene.reg.polyg.is_big, ws, threads);
    benchmark::DoNotOptimize(ws.pairs.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, n, p.stats);
}

void BM_BroadPhaseReusing(benchmark::State& state) {
  // the kept list of find_pairs_reusing, the boxes unchanged (a scene at rest, or any step whose
  // boxes moved less than a quarter margin): the kept pairs filtered
  const auto n = static_cast<std::size_t>(state.range(0));
  Prepared& p = prepared(n);
  BroadPhase ws;
  find_pairs_reusing(p.det.box, p.scene.reg.polyg.is_big, ws);
  for (auto _ : state) {
    find_pairs_reusing(p.det.box, p.scene.reg.polyg.is_big, ws);
    benchmark::DoNotOptimize(ws.pairs.data());
    benchmark::ClobberMemory();
  }
  if (ws.rebuilds != 1) state.SkipWithError("the kept list was rebuilt");
  set_counters(state, n, p.stats);
}

void BM_NarrowPhase(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  Prepared& p = prepared(n);
  const PolygTable& t = p.scene.reg.polyg;
  const double alert = p.scene.reg.params.alert;
  const PlplxDetector& d = p.det;
  auto view = [&](std::uint32_t k) {
    return ConvexView{&d.world_vertex[t.first_vertex[k]], &d.world_normal[t.first_vertex[k]], t.vertex_count[k]};
  };
  std::size_t points = 0;
  for (auto _ : state) {
    points = 0;
    // Same pairs and roles as detect_plplx: no big polygon here, the antagonist is the lower index.
    for (const auto& [i, j] : d.broad.pairs) {
      const ShadowOverlapResult r = shadow_overlap(view(i), d.world_centre[i], view(j), d.world_centre[j], alert);
      points += static_cast<std::size_t>(r.count);
      benchmark::DoNotOptimize(r);
    }
  }
  if (points != p.stats.contact_points) state.SkipWithError("narrow phase alone found a different number of points");
  set_counters(state, n, p.stats);
}

}  // namespace

BENCHMARK(BM_Detect)
    ->ArgNames({"bodies", "threads", "kept"})
    ->ArgsProduct({{700, 70000}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BroadPhase)
    ->ArgNames({"bodies", "threads"})
    ->ArgsProduct({{700, 70000}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BroadPhaseReusing)->Arg(700)->Arg(70000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_NarrowPhase)->Arg(700)->Arg(70000)->Unit(benchmark::kMicrosecond);
