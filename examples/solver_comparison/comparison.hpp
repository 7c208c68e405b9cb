// examples/solver_comparison/comparison.hpp — the solver comparison's pieces, shared by
// main.cpp (options, the run), problems.cpp (collecting the problems) and solve.cpp (solving,
// timing, the outputs).
#pragma once

#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

#include "nscd/solvers/local_problem.hpp"

namespace comparison {

using Clock = std::chrono::steady_clock;

/// Seconds of the steady clock since t0 (the solves' and the runs' timings).
inline double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Every parameter of a comparison run.
struct Config {
  std::string output = "out/solver_comparison";
  bool quick = false;               ///< small problems and a subset of tolerances (smoke test)
  std::string data_dir;             ///< the Siconos problems (default: the repository's tests/data)
  std::string ballast_sample;       ///< a prepared ballast sample (sample.nscd); empty: prepare one
  std::string only;                 ///< comma-separated problem names to keep (empty: all)
  double time_cap = 30.0;           ///< s: an NLGS solve stops after this (checked every 200 sweeps)
  int max_sweeps = 100000;          ///< NLGS sweeps at most
  int newton_max_iterations = 5000; ///< NEWTON_AC iterations at most (more than NewtonOptions' default)
  int repeats = 3;                  ///< solves shorter than repeat_below are run this many times (median)
  double repeat_below = 5.0;        ///< s
  bool plot = true;                 ///< draw work_precision.png with contrib/plots/plot_work_precision.py
  bool whole_runs = true;           ///< also time short deposit runs with each solver (full mode)
};

/// A problem to solve and where it comes from.
struct NamedProblem {
  std::string name;     ///< file stem of problems/<name>.txt and the csv's `problem`
  std::string origin;   ///< one line: how it was made
  nscd::FrictionProblem2D problem;
};

/// One solve: a row of problems.csv.
struct Row {
  std::string problem;
  std::size_t contacts = 0;
  std::string solver;   ///< NLGS or NEWTON_AC
  std::string policy;   ///< NLGS convergence policy; "-" for NEWTON_AC
  double tol = 0.0;     ///< the solver's own tolerance
  int iterations = 0;   ///< NLGS sweeps or Newton iterations (linear solves)
  double residual_q = 0.0;  ///< natural-map residual / ||q|| of the returned r
  double seconds = 0.0;     ///< median over the repeats
  bool reached = false;     ///< residual_q <= tol
  bool capped = false;      ///< stopped by the time cap or max_sweeps / max_iterations
};

/// The problems of the run (see main.cpp, step 1), written to <output>/problems/<name>.txt.
/// Prints one line per problem (contacts, how long it took to make).
std::vector<NamedProblem> collect_problems(const Config& c);

/// Solves every problem with every solver setting (main.cpp, step 2), printing a line per solve.
std::vector<Row> solve_all(const Config& c, const std::vector<NamedProblem>& problems);

/// The tolerances of the run (quick: a subset).
std::vector<double> nlgs_tolerances(const Config& c);
std::vector<double> newton_tolerances(const Config& c);

/// <output>/problems.csv, one row per solve (main.cpp, step 3).
void write_csv(const Config& c, const std::vector<Row>& rows);
/// <output>/summary.txt: key = value lines (then `extra_summary`, more such lines), the list of
/// problems and the table of the fastest solves; returns the table's text (main.cpp, step 3).
std::string write_summary(const Config& c, const std::vector<NamedProblem>& problems, const std::vector<Row>& rows,
                          double wall_seconds, const std::string& extra_summary);

/// Whole short runs with each solver in the stepper (main.cpp, step 4): key = value lines for
/// summary.txt and a small table printed on stdout. Empty when the stepper has no solver choice.
std::string time_whole_runs(const Config& c);

}  // namespace comparison
