// examples/solver_comparison/whole_runs.cpp — step 4 of the comparison: what each solver costs
// inside the time stepper, warm-started from the previous step as in a real run.
//
// The LMGC90 deposit is stepped with NLGS to the start of its impact phase (step 1800 of the
// full run, 900 in --quick), its state copied, and the next 200 steps (100 in --quick) run
// from that same state with each setting:
//   NLGS      QM/16, tol 1.666e-4, at most 1000 sweeps (the LMGC90 run's settings)
//   NEWTON_AC tol 1e-6 and 1e-8 (natural-map residual / ||q||), NewtonOptions' other defaults
// Reported per setting: wall time of the steps, mean iterations per step, steps that stopped
// unconverged, the largest overlap, and the mean and largest residual/|q| of the steps' answers
// (measured after each solve on the dumped step problem, outside the timing).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>

#include "comparison.hpp"
#include "nscd/shared/solver_problems.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "nscd/solvers/newton_ac.hpp"

using namespace nscd;

namespace comparison {
namespace {

struct Setting {
  std::string key, label;
  StepperOptions options;
};

struct RunCost {
  double seconds = 0.0, mean_iterations = 0.0, max_overlap = 0.0, mean_residual = 0.0, max_residual = 0.0;
  int unconverged = 0;
};

// `steps` steps of a copy of the scene from the given warm-start memory.
RunCost run(Registry reg, const ContactHistory& memory, const StepperOptions& options, int steps) {
  RunCost cost;
  MoreauJean mj(reg, options);
  mj.set_warm_start_memory(memory);
  for (int k = 0; k < steps; ++k) {
    const auto t0 = Clock::now();
    mj.begin_step();
    mj.detect();
    mj.prepare();
    double dt = since(t0);
    const FrictionProblem2D p = mj.local_problem();  // not timed: the measure only
    const auto t1 = Clock::now();
    mj.solve();
    dt += since(t1);
    const double res = natural_map_error(p, mj.impulses()).relative_q;
    const auto t2 = Clock::now();
    mj.end_step();
    cost.seconds += dt + since(t2);
    const StepReport& r = mj.report();
    cost.mean_iterations += r.sweeps;
    cost.unconverged += r.converged ? 0 : 1;
    cost.max_overlap = std::max(cost.max_overlap, r.max_overlap);
    cost.mean_residual += res;
    cost.max_residual = std::max(cost.max_residual, res);
  }
  cost.mean_iterations /= steps;
  cost.mean_residual /= steps;
  return cost;
}

}  // namespace

std::string time_whole_runs(const Config& c) {
  const std::int64_t start = c.quick ? 900 : 1800;
  const int steps = c.quick ? 100 : 200;
  std::vector<Setting> settings;
  settings.push_back({"nlgs", "NLGS QM/16 tol 1.666e-4", StepperOptions{}});
  if (newton_ac_available()) {
    for (const double tol : {1e-6, 1e-8}) {
      StepperOptions o;
      o.solver = SolverKind::NEWTON_AC;
      o.newton.tol = tol;
      std::ostringstream key, label;
      key << "newton_" << (tol == 1e-6 ? "1e-6" : "1e-8");
      label << "NEWTON_AC tol " << (tol == 1e-6 ? "1e-6" : "1e-8");
      settings.push_back({key.str(), label.str(), o});
    }
  }
  // The shared start: the deposit stepped with the LMGC90 settings.
  scenes::Scene s = scenes::lmgc90_deposit();
  MoreauJean mj(s.reg);
  const auto t0 = Clock::now();
  while (s.reg.step < start) mj.step();
  std::printf("  deposit stepped to step %lld in %.1f s; %d more steps with each setting (warm start):\n",
              static_cast<long long>(start), since(t0), steps);
  std::ostringstream sum;
  sum << "whole_run_start_step = " << start << "\nwhole_run_steps = " << steps << "\n";
  for (const Setting& st : settings) {
    const RunCost k = run(s.reg, mj.warm_start_memory(), st.options, steps);
    std::printf("  %-26s %8.2f s  %7.1f it/step  %3d unconverged  max overlap %.2e m  residual/|q| mean %.1e max %.1e\n",
                st.label.c_str(), k.seconds, k.mean_iterations, k.unconverged, k.max_overlap, k.mean_residual, k.max_residual);
    std::fflush(stdout);
    sum << "whole_run_" << st.key << "_seconds = " << k.seconds << "\n"
        << "whole_run_" << st.key << "_mean_iterations = " << k.mean_iterations << "\n"
        << "whole_run_" << st.key << "_unconverged_steps = " << k.unconverged << "\n"
        << "whole_run_" << st.key << "_max_overlap = " << k.max_overlap << "\n"
        << "whole_run_" << st.key << "_mean_residual_q = " << k.mean_residual << "\n"
        << "whole_run_" << st.key << "_max_residual_q = " << k.max_residual << "\n";
  }
  return sum.str();
}

}  // namespace comparison
