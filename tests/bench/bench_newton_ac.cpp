// tests/bench/bench_newton_ac.cpp — NEWTON_AC on the reference problems, to 1e-8 from r = 0,
// with each of its two sparse LU back ends (SuiteSparse KLU, the default, and UMFPACK): the
// measurement behind the choice of KLU (docs/theory.md §9b.2, docs/solvers.md); and pure
// Newton against the hybrid (at most 1000 NLGS sweeps to Quad 1e-3 first: "/hybrid"); and, on
// the pile seen with a 2 mm alert distance (open contacts in the problem), the LU on the closed
// contacts' rows only (the default) against every row ("/all_rows").
//
// Problems: the Siconos granular flows (tests/data/siconos-fc2d: 2020 and 7002 contacts), and
// the hand-made hyperstatic scenes of nscd::scenes (a column of 1000 blocks, a pentagon pile, a
// brick box; the pile with alert 2 mm: "pile_alert"). Counters: iterations (Newton), subproblems,
// residual_q reached, reached (1/0), factor_s (time in factorisations), rows (mean rows given to
// the LU), and the benchmark's own time per solve.
// Run (Release build):
//   build/tests/bench_newton_ac --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "nscd/shared/solver_problems.hpp"
#include "nscd/solvers/local_problem.hpp"
#include "nscd/solvers/newton_ac.hpp"

using namespace nscd;
namespace fs = std::filesystem;

namespace {

fs::path data_dir() {
  if (const char* env = std::getenv("NSCD_TEST_DATA_DIR")) return fs::path(env) / "siconos-fc2d";
  return fs::path(NSCD_TEST_DATA_DIR) / "siconos-fc2d";  // the build's copy (top-level CMakeLists.txt)
}

/// Problems are built once and shared by the benchmarks.
const FrictionProblem2D& problem(const std::string& name) {
  static std::map<std::string, std::unique_ptr<FrictionProblem2D>> cache;
  auto& p = cache[name];
  if (!p) {
    if (name == "column1000") {
      Registry reg = scenes::block_column();
      p = std::make_unique<FrictionProblem2D>(scenes::problem_of(reg));
    } else if (name == "pile") {
      Registry reg = scenes::pentagon_pile();
      p = std::make_unique<FrictionProblem2D>(scenes::problem_of(reg));
    } else if (name == "pile_alert") {
      scenes::PileOptions po;
      po.alert = 2e-3;  // the pairs within 2 mm enter the problem: many of them open
      Registry reg = scenes::pentagon_pile(po);
      p = std::make_unique<FrictionProblem2D>(scenes::problem_of(reg));
    } else if (name == "bricks") {
      Registry reg = scenes::brick_box();
      p = std::make_unique<FrictionProblem2D>(scenes::problem_of(reg));
    } else {
      p = std::make_unique<FrictionProblem2D>(read_siconos_fc2d(data_dir() / (name + ".dat")));
    }
  }
  return *p;
}

void BM_NewtonAC(benchmark::State& state, const std::string& name, LinearSolver lu, int presweeps, bool eliminate) {
  if (!newton_ac_available()) {
    state.SkipWithError("NEWTON_AC not in this build");
    return;
  }
  const FrictionProblem2D& p = problem(name);
  NewtonOptions o;
  o.tol = 1e-8;
  o.max_iterations = 2000;
  o.linear_solver = lu;
  o.presweeps = presweeps;
  o.eliminate_open = eliminate;
  NewtonResult res;
  for (auto _ : state) {
    std::vector<double> r;
    res = newton_ac_solve(p, r, o);
    benchmark::DoNotOptimize(r.data());
  }
  state.counters["contacts"] = double(p.nc);
  state.counters["presweeps"] = res.presweeps;
  state.counters["iterations"] = res.iterations;
  state.counters["subproblems"] = res.outer_iterations;
  state.counters["residual_q"] = res.residual;
  state.counters["reached"] = res.converged ? 1.0 : 0.0;
  state.counters["factor_s"] = res.factor_seconds;
  state.counters["full_factor"] = res.refactorizations;
  state.counters["line_search"] = res.line_search_steps;
  state.counters["rows"] = res.iterations > 0 ? double(res.factored_rows) / res.iterations : 0.0;
}

const std::vector<std::string> kProblems = {"fc2d_granularflowonwall_02020_00213", "fc2d_granularflowonwall_07002_00801",
                                            "column1000", "pile", "bricks", "pile_alert"};

const bool registered = [] {
  for (const std::string& name : kProblems)
    for (const auto& [lu, lu_name] : {std::pair{LinearSolver::KLU, "KLU"}, std::pair{LinearSolver::UMFPACK, "UMFPACK"}})
      for (const int pre : {0, 1000})
        benchmark::RegisterBenchmark(("NewtonAC/" + name + "/" + lu_name + (pre ? "/hybrid" : "")).c_str(), BM_NewtonAC,
                                     name, lu, pre, true)
            ->Unit(benchmark::kMillisecond)
            ->Iterations(1);
  benchmark::RegisterBenchmark("NewtonAC/pile_alert/KLU/all_rows", BM_NewtonAC, std::string("pile_alert"),
                               LinearSolver::KLU, 0, false)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1);
  return true;
}();

}  // namespace
