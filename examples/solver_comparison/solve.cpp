// examples/solver_comparison/solve.cpp — step 2 of the comparison: every problem solved from
// r = 0 by NLGS (three convergence policies, each at four tolerances) and by NEWTON_AC (four
// tolerances), each solve timed, its answer measured on the common scale: the natural-map
// residual over ||q|| (natural_map_error(...).relative_q).
//
// NLGS stops on its own criteria (convergence.hpp), so its tolerance is not a residual: a run
// "reaches" tol only when its residual_q <= tol, the same test as for NEWTON_AC. NLGS has no
// clock of its own: it is run in chunks of 200 sweeps (a multiple of its 10 sweeps between
// checks, so the checks fall where they would in one call) and stopped after --time-cap
// seconds or --max-sweeps sweeps. NEWTON_AC (the solver's defaults but the iteration cap,
// --newton-max-iterations) cannot be stopped by the clock: it runs to its tolerance or its cap.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "comparison.hpp"
#include "nscd/solvers/newton_ac.hpp"
#include "nscd/solvers/nlgs.hpp"

using namespace nscd;

namespace comparison {
namespace {

constexpr int kChunk = 200;  // NLGS sweeps between two looks at the clock


struct Outcome {
  int iterations = 0;
  bool capped = false;
  std::vector<double> r;
};

Outcome run_nlgs(const FrictionProblem2D& p, ConvergencePolicy policy, double tol, const Config& c) {
  Outcome o;
  o.r.assign(2 * p.nc, 0.0);
  NlgsOptions opt;
  opt.policy = policy;
  opt.tol = tol;
  opt.check_every = 10;
  const auto t0 = Clock::now();
  for (;;) {
    opt.max_sweeps = std::min(kChunk, c.max_sweeps - o.iterations);
    const NlgsResult res = nlgs_solve(p, o.r, opt);
    o.iterations += res.sweeps;
    if (res.converged) return o;
    if (o.iterations >= c.max_sweeps || since(t0) >= c.time_cap) {
      o.capped = true;
      return o;
    }
  }
}

Outcome run_newton(const FrictionProblem2D& p, double tol, const Config& c) {
  Outcome o;
  o.r.assign(2 * p.nc, 0.0);
  NewtonOptions opt;
  opt.tol = tol;
  opt.max_iterations = c.newton_max_iterations;
  const NewtonResult res = newton_ac_solve(p, o.r, opt);
  o.iterations = res.iterations;
  o.capped = !res.converged;
  return o;
}

// Runs `solve` once, and again up to c.repeats times in all when it took less than
// c.repeat_below seconds; the median time is kept (the answers are identical: the solvers are
// deterministic and a capped solve takes longer than any repeat threshold in use).
template <class F>
Row timed(const Config& c, const FrictionProblem2D& p, F solve) {
  std::vector<double> times;
  Outcome out;
  do {
    const auto t0 = Clock::now();
    out = solve();
    times.push_back(since(t0));
  } while (static_cast<int>(times.size()) < c.repeats && times.front() < c.repeat_below);
  std::sort(times.begin(), times.end());
  Row row;
  row.contacts = p.nc;
  row.iterations = out.iterations;
  row.capped = out.capped;
  row.seconds = times[times.size() / 2];
  row.residual_q = natural_map_error(p, out.r).relative_q;
  return row;
}

}  // namespace

std::vector<double> nlgs_tolerances(const Config& c) {
  return c.quick ? std::vector<double>{1e-2, 1e-4} : std::vector<double>{1e-2, 1e-4, 1e-6, 1e-8};
}

std::vector<double> newton_tolerances(const Config& c) {
  return c.quick ? std::vector<double>{1e-4, 1e-8} : std::vector<double>{1e-4, 1e-6, 1e-8, 1e-10};
}

std::vector<Row> solve_all(const Config& c, const std::vector<NamedProblem>& problems) {
  const std::vector<ConvergencePolicy> policies =
      c.quick ? std::vector<ConvergencePolicy>{ConvergencePolicy::QM16, ConvergencePolicy::Energy}
              : std::vector<ConvergencePolicy>{ConvergencePolicy::QM16, ConvergencePolicy::Quad, ConvergencePolicy::Energy};
  std::vector<Row> rows;
  auto report = [&](Row row, const NamedProblem& np, const std::string& solver, const std::string& policy, double tol) {
    row.problem = np.name;
    row.solver = solver;
    row.policy = policy;
    row.tol = tol;
    row.reached = row.residual_q <= tol;
    std::printf("  %-16s %-9s %-6s tol %.0e  %7d it  residual/|q| %.2e  %9.4f s  %s\n", np.name.c_str(), solver.c_str(),
                policy.c_str(), tol, row.iterations, row.residual_q, row.seconds,
                row.reached ? "reached" : (row.capped ? "NOT reached (cap)" : "NOT reached"));
    std::fflush(stdout);
    rows.push_back(row);
  };
  for (const NamedProblem& np : problems) {
    const FrictionProblem2D& p = np.problem;
    for (const ConvergencePolicy pol : policies)
      for (const double tol : nlgs_tolerances(c))
        report(timed(c, p, [&] { return run_nlgs(p, pol, tol, c); }), np, "NLGS", std::string(name_of(pol)), tol);
    if (!newton_ac_available()) continue;
    for (const double tol : newton_tolerances(c))
      report(timed(c, p, [&] { return run_newton(p, tol, c); }), np, "NEWTON_AC", "-", tol);
  }
  return rows;
}

}  // namespace comparison
