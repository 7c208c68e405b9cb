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
#include <boost/program_options.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>

#include "comparison.hpp"
#include "nscd/solvers/newton_ac.hpp"

namespace fs = std::filesystem;
namespace po = boost::program_options;
using comparison::Config;

namespace {

// Returns false after --help; throws std::invalid_argument on bad input.
bool parse(int argc, char** argv, Config& c) {
  po::options_description d("Options");
  bool no_plot = false, no_whole = false;
  double time_cap = -1.0, repeat_below = -1.0;
  int newton_max = -1;
  c.data_dir = NSCD_TEST_DATA_DIR "/siconos-fc2d";
  auto o = d.add_options();
  o("help,h", "print this help");
  o("output", po::value(&c.output)->default_value(c.output), "output directory");
  o("quick", po::bool_switch(&c.quick), "small problems and fewer settings (a smoke test: seconds)");
  o("data-dir", po::value(&c.data_dir)->default_value(c.data_dir), "folder of the Siconos fc2d problems");
  o("ballast-sample", po::value(&c.ballast_sample), "a prepared ballast sample (sample.nscd); default: prepare one");
  o("only", po::value(&c.only), "comma-separated problem names to keep (e.g. siconos_2020,column_1000)");
  o("time-cap", po::value(&time_cap), "s: an NLGS solve stops after this (default 30, --quick 2)");
  o("max-sweeps", po::value(&c.max_sweeps)->default_value(c.max_sweeps), "NLGS sweeps at most per solve");
  o("newton-max-iterations", po::value(&newton_max), "NEWTON_AC iterations at most per solve (default 5000, --quick 500)");
  o("repeats", po::value(&c.repeats)->default_value(c.repeats), "runs of a short solve; the median time is kept");
  o("repeat-below", po::value(&repeat_below), "s: solves shorter than this are repeated (default 5, --quick 0.5)");
  o("no-plot", po::bool_switch(&no_plot), "do not draw work_precision.png");
  o("no-whole-runs", po::bool_switch(&no_whole), "skip step 4 (the solvers inside the stepper)");
  po::variables_map vm;
  try {
    po::store(po::parse_command_line(argc, argv, d), vm);
    if (vm.count("help")) {
      std::cout << "solver_comparison — NLGS against NEWTON_AC on hard contact problems\n\n" << d << "\n";
      return false;
    }
    po::notify(vm);
  } catch (const po::error& e) {
    throw std::invalid_argument(e.what());
  }
  // options whose default depends on --quick
  c.time_cap = vm.count("time-cap") ? time_cap : (c.quick ? 2.0 : 30.0);
  c.newton_max_iterations = vm.count("newton-max-iterations") ? newton_max : (c.quick ? 500 : 5000);
  c.repeat_below = vm.count("repeat-below") ? repeat_below : (c.quick ? 0.5 : 5.0);
  c.plot = !no_plot;
  c.whole_runs = !no_whole;
  if (!(c.time_cap > 0.0)) throw std::invalid_argument("--time-cap must be > 0");
  if (c.max_sweeps < 10) throw std::invalid_argument("--max-sweeps must be >= 10");
  if (c.newton_max_iterations < 1) throw std::invalid_argument("--newton-max-iterations must be >= 1");
  if (c.repeats < 1) throw std::invalid_argument("--repeats must be >= 1");
  if (!(c.repeat_below >= 0.0)) throw std::invalid_argument("--repeat-below must be >= 0");
  if (c.output.empty()) throw std::invalid_argument("--output must not be empty");
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
  Config c;
  try {
    if (!parse(argc, argv, c)) return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "solver_comparison: %s (see --help)\n", e.what());
    return 2;
  }
  try {
    return run(c);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "solver_comparison: error: %s\n", e.what());
    return 1;
  }
}
