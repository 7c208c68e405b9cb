// examples/solver_comparison/problems.cpp — step 1 of the comparison: collect the problems.
//   a. the Siconos granular-flow problems (tests/data/siconos-fc2d, read_siconos_fc2d)
//   b. the hand-made scenes of nscd/shared/solver_problems.hpp: block column, pentagon pile,
//      brick box (their first step)
//   c. the LMGC90 deposit (lmgc90_deposit_case's scene and solver settings) stepped to an
//      impact-phase step and to a settled step, the problem of that step dumped
//   d. a ballast sample (the `ballast` study's preparation: deposit, sleeper) loaded by the
//      sleeper, dumped at the peak of the second load cycle
// Each problem is written to <output>/problems/<name>.txt (write_problem) to be solved again.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "ballast_study.hpp"
#include "comparison.hpp"
#include "nscd/bodies/rbdy2.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/shared/ballast.hpp"
#include "nscd/shared/solver_problems.hpp"
#include "nscd/solvers/moreau_jean.hpp"

namespace fs = std::filesystem;
using namespace nscd;

namespace comparison {
namespace {

bool wanted(const Config& c, const std::string& name) {
  if (c.only.empty()) return true;
  std::stringstream list(c.only);
  for (std::string item; std::getline(list, item, ',');)
    if (item == name) return true;
  return false;
}

// c. The LMGC90 deposit: steps with its own settings (NLGS QM/16, tol 1.666e-4, warm start),
//    dumping the problem of each step in `dump_at` (increasing) under the matching name.
void deposit_problems(const Config& c, const std::vector<std::pair<std::int64_t, std::string>>& dump_at,
                      std::vector<NamedProblem>& out) {
  scenes::Scene s = scenes::lmgc90_deposit();
  MoreauJean mj(s.reg);  // StepperOptions' defaults are the LMGC90 run's NLGS settings
  const auto t0 = Clock::now();
  auto last = t0;
  for (const auto& [step, name] : dump_at) {
    while (s.reg.step + 1 < step) {
      mj.step();
      if (since(last) > 10.0) {
        last = Clock::now();
        std::printf("  deposit: step %lld of %lld (%.0f s)\n", static_cast<long long>(s.reg.step),
                    static_cast<long long>(dump_at.back().first), since(t0));
        std::fflush(stdout);
      }
    }
    FrictionProblem2D p = scenes::problem_of(mj);  // step `step`, then finish it
    mj.solve();
    mj.end_step();
    std::ostringstream origin;
    origin << "LMGC90 deposit (700 pentagons), step " << step << " (t = " << s.reg.time << " s), NLGS QM/16 run";
    if (wanted(c, name)) out.push_back({name, origin.str(), std::move(p)});
  }
}

// d. The ballast sample under load. Without --ballast-sample, `ballast --prepare-only` is run
//    in-process into <output>/ballast_sample (quick: a tiny sample).
void ballast_problem(const Config& c, const std::string& name, std::vector<NamedProblem>& out) {
  ballast::Config bc;  // the paper's sample and load (A = -1000 N/m, B = -500 N/m, 20 Hz, φ = -π)
  if (c.quick) {       // the ballast_cli_tiny test's sample
    bc.grading_fraction = 0.05;
    bc.box_width = 0.2;
    bc.pads = 10;
    bc.sleeper_width = 0.06;
    bc.load_mean = -100.0;
    bc.load_amplitude = -50.0;
  }
  std::string sample = c.ballast_sample;
  if (sample.empty()) {
    bc.prepare_only = true;
    bc.vtk_every = 0;
    bc.progress_every = 30.0;
    bc.output = (fs::path(c.output) / "ballast_sample").string();
    bc.overwrite = true;  // this folder is the comparison's own: a rerun into the same --output re-makes it
    std::printf("  ballast: preparing a sample with `ballast --prepare-only` into %s\n", bc.output.c_str());
    std::fflush(stdout);
    if (ballast::run(bc) != 0) throw Error("preparing the ballast sample failed");
    sample = (fs::path(bc.output) / "sample.nscd").string();
  }
  Checkpoint cp = load_checkpoint(sample);
  scenes::BallastScene s = scenes::recognise_ballast(std::move(cp.reg));
  if (!s.sleeper.valid()) throw Error("'" + sample + "' has no sleeper: not a prepared ballast sample");
  Registry& reg = s.scene.reg;
  StepperOptions so;  // ballast's NLGS settings: the paper's non-strict Gauss–Seidel
  so.nlgs.policy = ConvergencePolicy::NonStrict;
  MoreauJean mj(reg, so);
  mj.set_warm_start_memory(std::move(cp.warm_start));
  // The load F = ramp · (A + B cos(2π f s − φ)), s = t − t0, ramped in over one cycle (as the
  // ballast study imposes it); with φ = −π its full peak A + B comes at s = 1.5 / f, the middle
  // of the second cycle.
  const double t0 = reg.time;
  impose_force(reg, s.sleeper, Dof::Y,
               TimeFunction::cosine(bc.load_mean, bc.load_amplitude, bc.frequency, bc.phase, 1.0 / bc.frequency, t0));
  const auto steps = static_cast<std::int64_t>(std::lround(1.5 / (bc.frequency * reg.params.dt)));
  for (std::int64_t k = 1; k < steps; ++k) mj.step();
  FrictionProblem2D p = scenes::problem_of(mj);
  std::ostringstream origin;
  origin << "ballast sample (" << s.scene.grains.size() << " grains, " << s.pads.size() << " pads, sleeper) at peak load "
         << std::abs(bc.load_mean + bc.load_amplitude) << " N/m, step " << steps << " of the loading";
  out.push_back({name, origin.str(), std::move(p)});
}

}  // namespace

std::vector<NamedProblem> collect_problems(const Config& c) {
  std::vector<NamedProblem> out;
  auto timed = [&](const std::string& name, auto make) {
    if (!wanted(c, name)) return;
    const auto t0 = Clock::now();
    make(name);
    std::printf("  %-18s %6zu contacts  (made in %.1f s)\n", name.c_str(), out.back().problem.nc, since(t0));
    std::fflush(stdout);
  };
  // a. Siconos (the 7002-contact problem only in the full run). Not the 667-contact one: its q
  //    is zero up to round-off (|q_i| <= 5e-19), so r = 0 solves it and residual/||q|| measures
  //    only that round-off.
  const fs::path data(c.data_dir);
  std::vector<std::pair<std::string, std::string>> siconos = {{"siconos_2020", "fc2d_granularflowonwall_02020_00213.dat"}};
  if (!c.quick) siconos.push_back({"siconos_7002", "fc2d_granularflowonwall_07002_00801.dat"});
  for (const auto& [name, file_name] : siconos)
    // (file by an init-capture: Clang 14 cannot capture a structured binding)
    timed(name, [&, &file = file_name](const std::string& n) {
      if (!fs::exists(data / file))
        throw Error("Siconos problem '" + (data / file).string() + "' not found (see --data-dir)");
      out.push_back({n, "Siconos " + file, read_siconos_fc2d(data / file)});
    });

  // b. The hand-made scenes, first step from rest.
  scenes::ColumnOptions col;
  col.blocks = c.quick ? 50 : 1000;
  timed("column_" + std::to_string(col.blocks), [&](const std::string& n) {
    Registry reg = scenes::block_column(col);
    out.push_back({n, "block column, " + std::to_string(col.blocks) + " blocks on a floor, first step", scenes::problem_of(reg)});
  });
  scenes::PileOptions pile;
  pile.base = c.quick ? 12 : 34;
  const int grains = pile.base * (pile.base + 1) / 2;
  timed("pile_" + std::to_string(grains), [&](const std::string& n) {
    Registry reg = scenes::pentagon_pile(pile);
    out.push_back({n, "pentagon heap, " + std::to_string(grains) + " grains on a floor, first step", scenes::problem_of(reg)});
  });
  scenes::BrickOptions bricks;
  bricks.columns = c.quick ? 4 : 10;
  bricks.rows = c.quick ? 4 : 16;
  timed("bricks_" + std::to_string(bricks.columns) + "x" + std::to_string(bricks.rows), [&](const std::string& n) {
    Registry reg = scenes::brick_box(bricks);
    out.push_back({n, "running-bond bricks in a box, first step", scenes::problem_of(reg)});
  });

  // c. The deposit: quick, an early step only (357 contacts, a quarter of a second to reach).
  const auto t0 = Clock::now();
  const std::size_t before = out.size();
  if (c.quick) {
    if (wanted(c, "deposit_early")) deposit_problems(c, {{1000, "deposit_early"}}, out);
  } else if (wanted(c, "deposit_impact") || wanted(c, "deposit_settled")) {
    deposit_problems(c, {{2000, "deposit_impact"}, {6000, "deposit_settled"}}, out);
  }
  for (std::size_t k = before; k < out.size(); ++k)
    std::printf("  %-18s %6zu contacts  (%s)\n", out[k].name.c_str(), out[k].problem.nc, out[k].origin.c_str());
  if (out.size() > before) std::printf("  (deposit stepped in %.1f s)\n", since(t0));

  // d. The loaded ballast sample.
  timed(c.quick ? "ballast_tiny" : "ballast_loaded", [&](const std::string& n) { ballast_problem(c, n, out); });

  // Dump them all.
  const fs::path dir = fs::path(c.output) / "problems";
  fs::create_directories(dir);
  for (const NamedProblem& p : out) write_problem(dir / (p.name + ".txt"), p.problem);
  return out;
}

}  // namespace comparison
