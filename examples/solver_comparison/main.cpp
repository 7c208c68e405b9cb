// examples/solver_comparison/main.cpp — `solver_comparison`: NLGS against NEWTON_AC on real and
// hand-made hard contact problems, on one measure of accuracy.
//
// What it shows
//   For each problem, how long each solver takes from r = 0 to reach a given residual: the
//   natural-map residual of the De Saxcé formulation over ||q|| (Acary, Brémond & Huber 2018),
//   computed on the returned impulses for both solvers. NLGS (nonlinear Gauss–Seidel) with the
//   QM/16, Quad and Energy policies at tolerances 1e-2 … 1e-8; NEWTON_AC (the global semismooth
//   Newton on the Alart–Curnier function) at 1e-4 … 1e-10. The problems: the Siconos granular
//   flows (2020 and 7002 contacts), a column of 1000 blocks (rank-deficient W, the weight of
//   1000 blocks carried through 1000 interfaces), a heap of 595 pentagons, a brick packing, the
//   LMGC90 deposit at an impact step and at a settled step, a ballast sample at peak load.
//   And what each solver costs over 200 steps of the deposit's impact phase (warm-started).
//
// Build
//   cmake -S . -B build && cmake --build build --target solver_comparison
//   (NEWTON_AC needs SuiteSparse; without it the NEWTON_AC rows are skipped, summary.txt says so)
// Run
//   build/examples/solver_comparison/solver_comparison --output out/solver_comparison
//       (the full comparison: about 11 minutes on 2 cores, a ballast sample prepared included)
//   build/examples/solver_comparison/solver_comparison --quick --output out/sc_quick   (seconds)
//   build/examples/solver_comparison/solver_comparison --ballast-sample out/ballast/sample.nscd
//   build/examples/solver_comparison/solver_comparison --only siconos_2020,column_1000 --no-whole-runs
//   NSCD_NEWTON_TRACE=1 solver_comparison ...   (one line per Newton outer iteration, on stderr)
// Outputs under --output DIR
//   problems/<name>.txt   every problem (write_problem: read_problem solves it again)
//   problems.csv          problem,contacts,solver,policy,tol,iterations,residual_q,seconds,reached
//   summary.txt           key = value lines (problems, solves, *_reached, wall_time,
//                         contacts_<problem>, whole_run_*), then the table of the fastest solves
//   work_precision.png    time against residual/|q|, one panel per problem (needs matplotlib:
//                         contrib/plots/plot_work_precision.py; a warning, not a failure, without)
//   ballast_sample/       the ballast sample prepared when --ballast-sample is not given
//
// Steps
//   1. collect the problems (problems.cpp) and write them to problems/
//   2. solve each with every setting, timed (solve.cpp)
//   3. write problems.csv, summary.txt, print the table (output.cpp); draw the PNG
//   4. whole runs: the same 200 deposit steps with each solver in the stepper (whole_runs.cpp)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <set>
#include <string>

#include "comparison.hpp"
#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/run_main.hpp"
#include "nscd/solvers/newton_ac.hpp"

namespace fs = std::filesystem;
namespace driver = nscd::driver;
using comparison::Config;

namespace {

// The command line: the run's Config and the switches that turn parts off.
struct Cli : Config {
  bool no_plot = false, no_whole_runs = false;
};

// --time-cap, --newton-max-iterations and --repeat-below have no default of their own: theirs
// depends on --quick (set in parse when not given).
const driver::OptionTable<Cli> kOptions(
    "solver_comparison", "NLGS against NEWTON_AC on hard contact problems",
    {{"output", &Cli::output, "output directory"},
     {"quick", &Cli::quick, "small problems and fewer settings (a smoke test: seconds)", driver::Kind::Free, driver::kSwitch},
     {"data-dir", &Cli::data_dir, "folder of the Siconos fc2d problems"},
     {"ballast-sample", &Cli::ballast_sample, "a prepared ballast sample (sample.nscd); default: prepare one", driver::Kind::Free, driver::kNoDefault},
     {"only", &Cli::only, "comma-separated problem names to keep (e.g. siconos_2020,column_1000)", driver::Kind::Free, driver::kNoDefault},
     {"time-cap", &Cli::time_cap, "s: an NLGS solve stops after this (default 30, --quick 2)", driver::Kind::Free, driver::kNoDefault},
     {"max-sweeps", &Cli::max_sweeps, "NLGS sweeps at most per solve"},
     {"newton-max-iterations", &Cli::newton_max_iterations, "NEWTON_AC iterations at most per solve (default 5000, --quick 500)",
      driver::Kind::Free, driver::kNoDefault},
     {"repeats", &Cli::repeats, "runs of a short solve; the median time is kept"},
     {"repeat-below", &Cli::repeat_below, "s: solves shorter than this are repeated (default 5, --quick 0.5)", driver::Kind::Free, driver::kNoDefault},
     {"no-plot", &Cli::no_plot, "do not draw work_precision.png", driver::Kind::Free, driver::kSwitch},
     {"no-whole-runs", &Cli::no_whole_runs, "skip step 4 (the solvers inside the stepper)", driver::Kind::Free, driver::kSwitch}});

// Returns false after --help; throws driver::InputError on bad input.
bool parse(int argc, char** argv, Cli& c) {
  c.data_dir = NSCD_TEST_DATA_DIR "/siconos-fc2d";
  std::set<std::string> given;
  if (!kOptions.parse(argc, argv, c, &given)) return false;
  kOptions.require_finite(c);
  // options whose default depends on --quick
  if (!given.count("time-cap")) c.time_cap = c.quick ? 2.0 : 30.0;
  if (!given.count("newton-max-iterations")) c.newton_max_iterations = c.quick ? 500 : 5000;
  if (!given.count("repeat-below")) c.repeat_below = c.quick ? 0.5 : 5.0;
  c.plot = !c.no_plot;
  c.whole_runs = !c.no_whole_runs;
  using driver::require;
  require(c.time_cap > 0.0, "--time-cap must be > 0");
  require(c.max_sweeps >= 10, "--max-sweeps must be >= 10");
  require(c.newton_max_iterations >= 1, "--newton-max-iterations must be >= 1");
  require(c.repeats >= 1, "--repeats must be >= 1");
  require(c.repeat_below >= 0.0, "--repeat-below must be >= 0");
  require(!c.output.empty(), "--output must not be empty");
  return true;
}

// Step 3's PNG: the Python script, run by the first Python that has matplotlib (the script's
// own /usr/bin/python3, where Debian's python3-matplotlib goes, then python3 on the PATH); a
// warning otherwise, never a failure.
bool plot(const Config& c) {
  const fs::path script = fs::path(NSCD_SOURCE_DIR) / "contrib/plots/plot_work_precision.py";
  const fs::path out(c.output);
  std::string python;
  for (const char* candidate : {"/usr/bin/python3", "python3"})
    if (std::system((std::string(candidate) + " -c 'import matplotlib' >/dev/null 2>&1").c_str()) == 0) {
      python = candidate;
      break;
    }
  if (python.empty()) {
    std::printf("WARNING: no python3 with matplotlib: work_precision.png not drawn "
                "(Debian: apt-get install python3-matplotlib; then run %s %s)\n",
                script.string().c_str(), (out / "problems.csv").string().c_str());
    return false;
  }
  const std::string cmd = python + " '" + script.string() + "' '" + (out / "problems.csv").string() + "' -o '" +
                          (out / "work_precision.png").string() + "'";
  std::fflush(stdout);  // the script prints too
  if (std::system(cmd.c_str()) != 0) {
    std::printf("WARNING: the plot script failed: %s\n", cmd.c_str());
    return false;
  }
  return true;
}

int run(const Config& c) {
  const auto t0 = std::chrono::steady_clock::now();
  fs::create_directories(c.output);
  std::printf("solver_comparison: %s run, output %s, NEWTON_AC %s\n", c.quick ? "quick" : "full", c.output.c_str(),
              nscd::newton_ac_available() ? "available" : "NOT available in this build (no SuiteSparse): skipped");
  std::printf("1. problems\n");
  driver::input_accepted();  // the options are checked; making the problems (a sample prepared too) is the run
  const auto problems = comparison::collect_problems(c);
  std::printf("2. solves from r = 0 (NLGS: time cap %g s, %d sweeps; NEWTON_AC: %d iterations; median of %d runs "
              "below %g s)\n", c.time_cap, c.max_sweeps, c.newton_max_iterations, c.repeats, c.repeat_below);
  const auto rows = comparison::solve_all(c, problems);
  std::printf("3. outputs\n");
  comparison::write_csv(c, rows);
  const bool png = c.plot && plot(c);
  std::string extra = "work_precision_png = " + std::to_string(png ? 1 : 0) + "\n";
  if (c.whole_runs) {
    std::printf("4. whole runs\n");
    extra += comparison::time_whole_runs(c);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string table = comparison::write_summary(c, problems, rows, wall, extra);
  std::printf("\n%s\ndone in %.1f s: %s/{problems.csv, summary.txt%s, problems/}\n", table.c_str(), wall, c.output.c_str(),
              png ? ", work_precision.png" : "");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return driver::run_main("solver_comparison", argc, argv, Cli{}, parse, [](const Cli& c) { return run(c); });
}
