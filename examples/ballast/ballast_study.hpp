// examples/ballast/ballast_study.hpp — the ballast settlement study (Saussine et al. 2006,
// §3–4): options, sample preparation, loading cycles, checkpoints and resume.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>

namespace ballast {

/// Every parameter of a run (SI units). Defaults: the paper's values where it gives them.
struct Config {
  // sample (nscd::scenes::BallastOptions)
  std::uint64_t seed = 2006;
  double box_width = 1.0;
  double grading_fraction = 1.0;    ///< scales the paper's 361/242/121 grain counts
  double mu = 0.5;
  int pads = 50;
  double k = 4100.0;          ///< N/m per spring, the paper's calibration
  double nu = 80.0;           ///< N·s/m per spring
  double k_factor = 1.0;      ///< stiffness multiplier applied when the cycles start (paper §4.2: 1, 100, 1000)
  double spring_length = 0.1;
  double pad_height = 0.1;    ///< m, the springs' length: no pad can sink below its neighbours' sides; the pads' mass is that of a 1 cm pad
  double sleeper_width = 0.15;
  int bars = 3;
  // load F = A + B cos(2π f s − φ), s = t − t0, along a direction inclined from vertical
  double load_mean = -1000.0;       ///< A (N/m: per metre of thickness, 2D)
  double load_amplitude = -500.0;   ///< B (N/m)
  double frequency = 20.0;          ///< f (Hz)
  double phase = -3.14159265358979323846;  ///< φ (rad)
  double inclination = 0.0;         ///< degrees from vertical, toward +x
  double ramp_cycles = 1.0;         ///< linear ramp-in of the load over this many cycles
  bool guided_sleeper = false;      ///< fix the sleeper's x and rotation
  // numerics
  double dt = 2e-4;
  double theta = 0.5;
  double alert = 1.25e-3;
  std::string solver = "NLGS";       ///< NLGS or NEWTON_AC
  double newton_tol = 1e-8;          ///< NEWTON_AC: natural-map residual / |q|
  int newton_presweeps = 0;         ///< NEWTON_AC hybrid: NLGS sweeps first (0: pure Newton)
  double newton_presweep_tol = 1e-3; ///< NEWTON_AC hybrid: the sweeps stop at this Quad criterion
  int newton_max_iterations = 500;   ///< NEWTON_AC: Newton iterations per step
  std::string policy = "NonStrict";  ///< the paper's non-strict Gauss–Seidel (§3.2): the quadratic mean QuadDV < 1
  double tol = 1.666e-4;
  int check_every = 10;
  int min_sweeps = 0;
  int max_sweeps = 1000;
  // The sweep: graph-coloured strips, over-relaxed, with Anderson mixing (docs/studies.md §5.9:
  // the cheapest setting that meets the overlap target; on the loaded layer the strips need fewer
  // sweeps than the rows of cells that suit a falling deposit; --order fixed --relaxation 1
  // --anderson 0 is the paper's NLGS)
  double relaxation = 1.3;      ///< NLGS relaxation ω
  int anderson = 3;             ///< NLGS Anderson mixing depth, colored orders (0: off)
  std::string order = "colored"; ///< NLGS sweep order
  int threads = 1;                   ///< colored order: threads of the sweep (results do not depend on it)
  int solve_threads = 0;             ///< the solve's threads, fixed; 0: chosen by measure (StepperOptions)
  int loop_threads = 0;              ///< the loops' threads around the solve, fixed; 0: chosen by measure
  bool solve_profile = false;  ///< --solve-profile: the solve's threads' time by part (NlgsOptions::profile)
  std::string plan_model;            ///< thread counts ("1,2,8"): the next step's plan on a model, at the end
  // the stepper's checks (issue #9; StepperOptions; stored in checkpoints, kept on --resume)
  bool strict_alert = false;        ///< a step moving a body beyond the alert distance is an error
  int residual_check_every = 50;    ///< natural-map residual every N steps (0: never)
  double residual_flag = 1e-3;      ///< "converged" above this residual is flagged
  double residual_limit = 0.0;      ///< > 0: stop when a checked step's residual is above this
  // the overlap projection (docs/theory.md §8.4) and the overlap budget
  bool projection = true;           ///< remove overlaps beyond the slop after each solve
  double projection_slop = 1e-4;    ///< the overlap left alone, as a fraction of --alert
  double projection_share = 1.0;    ///< the share of the excess removed in one step
  double overlap_limit = -1.0;      ///< m; < 0: kOverlapLimitFraction × the smallest grain; 0: none
  bool strict_overlap = false;      ///< stop (with a checkpoint) at the end of the cycle that passed the limit
  // preparation
  double prep_max_time = 3.0;       ///< s of simulated time for the deposit, at most
  double settle_time = 0.6;         ///< s of simulated time for the sleeper to settle, at most
  double equilibrium_speed = 1e-3;  ///< m/s, rms speed below which the sample is at rest
  // run
  int cycles = 30;
  int checkpoint_every = 10;        ///< cycles between checkpoints (0: only at the end)
  double checkpoint_wall = 600.0;   ///< wall s: a checkpoint at the first cycle end after that long since the last (0: none)
  int steps_every = 10;             ///< steps between rows of steps.csv
  int vtk_every = 125;              ///< steps between VTK frames (0: none)
  std::string output = "out/ballast";
  std::string sample;               ///< a prepared sample to load (sample.nscd of an earlier run)
  bool prepare_only = false;
  std::string resume;               ///< an output directory to resume
  int stop_after_cycles = 0;        ///< stop this process after that many cycles (tests, batch slots)
  double progress_every = 2.0;      ///< wall seconds between progress lines
  bool overwrite = false;           ///< replace the run found in a non-empty output folder
  bool continue_run = false;        ///< --continue: resume --output if it holds a checkpoint, else start there (batch jobs)
  std::set<std::string> given;      ///< options set on the command line or in --config (by parse)
};

/// Parses the command line (and --config FILE), records the options given in c.given and
/// checks them (check). Returns false after --help. Throws std::invalid_argument with a
/// one-line message naming the option (and the config file's line) on bad input.
bool parse(int argc, char** argv, Config& c);

/// Every option within its range and no two that contradict each other; throws
/// std::invalid_argument naming the option and its value.
void check(const Config& c);

/// The options that define a run, as key → value text (stored in checkpoints for --resume);
/// scene_map: those that define the sample (stored in sample.nscd).
std::map<std::string, std::string> to_map(const Config& c);
std::map<std::string, std::string> scene_map(const Config& c);
/// Reads stored options back, strictly (the whole value, in range for its type); the error
/// names `source` (the file) and the key.
void from_map(const std::map<std::string, std::string>& m, Config& c, const std::string& source = "checkpoint");

/// Refuses every option in cli.given whose value differs from `stored` (the resumed run's
/// options, or with scene_only the loaded sample's): std::invalid_argument naming it.
void refuse_changes(const Config& cli, const std::map<std::string, std::string>& stored, bool scene_only,
                    const std::string& source);

/// Runs the study; returns the exit status: 0 done, 1 error, 3 impossible result, 143 stopped
/// by SIGTERM at the end of a cycle after writing its checkpoint (resume it with --resume or
/// --continue).
int run(Config c);

}  // namespace ballast
