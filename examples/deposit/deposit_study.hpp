// examples/deposit/deposit_study.hpp — the deposit study shared by the `deposit` and
// `lmgc90_deposit_case` drivers: options, the run loop, and its outputs.
#pragma once

#include <cstdint>
#include <set>
#include <string>

#include "nscd/shared/samples.hpp"
#include "nscd/solvers/moreau_jean.hpp"

namespace deposit {

/// Largest --grains (about 1 KB of state per grain and a box 1.4 km wide: beyond, a typo).
inline constexpr std::int64_t kMaxGrains = 1'000'000;

/// Every parameter of a deposit run (SI units).
struct Config {
  // scene
  std::string scene = "paper";      ///< "paper" (Saussine 2006) or "lmgc90" (the LMGC90 benchmark)
  std::uint64_t seed = nscd::scenes::kDefaultSeed;
  std::string sample_file;          ///< lmgc90 scene: the grains read from this file (sample_file.hpp)
  std::string walls = "polyg";      ///< lmgc90 scene: "polyg" (POLYG rectangles) or "jonc" (JONCx, LMGC90's)
  std::int64_t grains = 0;          ///< paper scene: 0 = the paper's 724; N = paper_grading(N), box scaled
  double box_width = nscd::scenes::kPaperBoxWidth;
  double pitch_factor = nscd::scenes::kLoosePitchFactor;
  double density = nscd::scenes::kPaperDensity;
  double mu = nscd::scenes::kPaperFriction;
  std::string law = "IQS_CLB";
  // time stepping
  double dt = 2e-4;
  double theta = 0.5;
  double alert = 1.25e-3;
  // solver
  std::string solver = "NLGS";      ///< NLGS or NEWTON_AC
  double newton_tol = 1e-8;         ///< NEWTON_AC: natural-map residual / |q|
  int newton_presweeps = 0;         ///< NEWTON_AC hybrid: NLGS sweeps first (0: pure Newton)
  int newton_max_iterations = 500;  ///< NEWTON_AC: Newton iterations per step
  // NLGS
  std::string policy = "QM/16";
  double tol = 1.666e-4;
  int check_every = 10;
  int min_sweeps = 0;
  int max_sweeps = 1000;
  // the sweep: cells row by row, over-relaxed, mixed (docs/studies.md §5.9; --order fixed
  // --relaxation 1 --anderson 0 is LMGC90's and the paper's NLGS)
  double relaxation = 1.3;
  std::string order = "colored-rows";
  int threads = 1;
  int solve_threads = 0;  ///< the solve's threads, fixed; 0: chosen by measure (StepperOptions)
  int loop_threads = 0;   ///< the loops' threads around the solve, fixed; 0: chosen by measure
  bool solve_profile = false;  ///< --solve-profile: the solve's threads' time by part (NlgsOptions::profile)
  bool warm_start = true;
  int anderson = 3;                 ///< Anderson mixing depth of the colored orders (0: off)
  bool skip_zero = false;           ///< LMGC90's rule: visit zero-impulse contacts less often
  // stopping
  std::int64_t steps = 0;           ///< fixed number of steps (0: stop at equilibrium)
  double max_time = 4.0;            ///< s of simulated time, upper bound
  double min_time = 0.2;            ///< s, no equilibrium test before
  double equilibrium_speed = 1e-3;  ///< m/s: rms grain speed below it for `equilibrium_window` s
  double equilibrium_window = 0.05; ///< s
  // outputs
  std::string output = "out/deposit";
  std::int64_t vtk_every = 500;     ///< steps between VTK frames (0: none)
  bool no_vtk = false;
  double progress_every = 2.0;      ///< s of wall time between progress lines
  int dump_unconverged = 0;         ///< dump the local problems of the first N unconverged steps
  // the stepper's checks (issue #9; StepperOptions)
  bool strict_alert = false;        ///< a step moving a body beyond the alert distance is an error
  int residual_check_every = 50;    ///< natural-map residual every N steps (0: never)
  double residual_flag = 1e-3;      ///< "converged" above this residual is flagged
  double residual_limit = 0.0;      ///< > 0: stop when a checked step's residual is above this
  bool projection = true;           ///< remove overlaps beyond the slop after each solve (docs/theory.md §8.4)
  double projection_slop = 1e-4;    ///< the overlap left alone, as a fraction of --alert
  double projection_share = 1.0;    ///< the share of the excess removed in one step
  double overlap_limit = -1.0;      ///< m; < 0: kOverlapLimitFraction × the smallest grain; 0: none
  bool strict_overlap = false;      ///< stop with an error at the first step past the overlap limit
  bool overwrite = false;           ///< replace the run found in a non-empty output folder
  std::set<std::string> given;      ///< options set on the command line or in --config (by parse)
};

/// Parses argv (and `--config FILE`, whose errors name the file and the line), records the
/// options given in c.given and checks them (check); returns false after printing --help.
/// Throws nscd::driver::InputError (a std::invalid_argument) with a one-line message naming the
/// option on bad input. The options: one table in options.cpp.
bool parse(int argc, char** argv, Config& c, const std::string& program, const std::string& about);

/// Every option within its range and none that the run cannot honour (e.g. --box-width with
/// --scene lmgc90); throws std::invalid_argument naming the option and its value.
void check(const Config& c);

/// Runs the study; returns the process exit status (3: a physically impossible result, e.g. a
/// packing fraction above 1 or a grain outside the box, said on stderr and in summary.txt).
int run(const Config& c);

}  // namespace deposit
