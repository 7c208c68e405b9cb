// examples/ballast/options.cpp — the ballast study's options: one table (nscd::driver::OptionTable,
// shared/driver/options.hpp) drives the command line / config file parsing and the key → value
// copy stored in checkpoints (Run and Scene options) and samples (Scene options) for --resume
// and --sample.
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "ballast_study.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/text_reader.hpp"
#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/overlap_options.hpp"
#include "nscd/shared/driver/plan_table.hpp"
#include "nscd/solvers/nlgs.hpp"

namespace ballast {
namespace {

using nscd::driver::InputError;
using nscd::driver::Kind;

// Scene: defines the prepared sample (recorded in sample.nscd; with --sample it must equal the
//        sample's value). Run: defines the run (recorded in checkpoints; with --resume it must
//        equal the stored value). Free: this process only (never stored, free with --resume).
using Opt = nscd::driver::Option<Config>;
constexpr Kind Scene = Kind::Scene, Run = Kind::Run, Free = Kind::Free;

const std::vector<Opt>& table() {
  static const std::vector<Opt> t = {
      {"seed", &Config::seed, "random seed of the sample (grading shuffle, orientations)", Scene},
      {"box-width", &Config::box_width, "box width (m)", Scene},
      {"grading-fraction", &Config::grading_fraction, "scales the paper's grain counts 361/242/121 (e.g. 0.1 for a small sample)", Scene},
      {"mu", &Config::mu, "friction coefficient of every contact", Scene},
      {"pads", &Config::pads, "number of sublayer pads (each on one spring)", Scene},
      {"k", &Config::k, "spring stiffness k_N per pad (N/m; paper: 4100)", Scene},
      {"nu", &Config::nu, "spring viscosity per pad (N s/m; paper: 80)", Scene},
      {"k-factor", &Config::k_factor, "stiffness multiplier applied when the cycles start (paper 4.2: 1, 100, 1000)", Run},
      {"spring-length", &Config::spring_length, "spring reference length L0 (m)", Scene},
      {"pad-height", &Config::pad_height, "height of the sublayer pads (m; their mass is kept, that of a 1 cm pad): at least --spring-length, so that no pad can sink below its neighbours' sides and let grains under it (the sublayer is then continuous, as the paper's elastomer); shorter pads are accepted with a warning", Scene},
      {"sleeper-width", &Config::sleeper_width, "sleeper width (m)", Scene},
      {"bars", &Config::bars, "square bars under the sleeper (0: none)", Scene},
      {"load-mean", &Config::load_mean, "A of F = A + B cos(2 pi f s - phi) (N/m: per metre of thickness, 2D; paper: -1000)", Run},
      {"load-amplitude", &Config::load_amplitude, "B (N/m; paper: -500)", Run},
      {"frequency", &Config::frequency, "f (Hz; paper: 20)", Run},
      {"phase", &Config::phase, "phi (rad; paper: -pi)", Run},
      {"inclination", &Config::inclination, "load direction from vertical (degrees, toward +x; paper: 0-15)", Run},
      {"ramp-cycles", &Config::ramp_cycles, "linear ramp-in of the load (cycles)", Run},
      {"guided-sleeper", &Config::guided_sleeper, "fix the sleeper's horizontal motion and rotation (true/false)", Run},
      {"dt", &Config::dt, "time step (s); 1/(f dt) must be an integer", Run},
      {"theta", &Config::theta, "theta of the theta-method, in [0.5, 1]", Run},
      {"alert", &Config::alert, "alert distance (m)", Run},
      {"solver", &Config::solver, "contact solver: NLGS (the paper's) or NEWTON_AC (global semismooth Newton, SuiteSparse)", Run},
      {"newton-tol", &Config::newton_tol, "NEWTON_AC tolerance: natural-map residual over |q|", Run},
      {"newton-presweeps", &Config::newton_presweeps, "NEWTON_AC hybrid: at most this many NLGS sweeps (to Quad --newton-presweep-tol) before Newton, 0: pure Newton", Run},
      {"newton-presweep-tol", &Config::newton_presweep_tol, "NEWTON_AC hybrid: the NLGS sweeps stop at this Quad criterion", Run},
      {"newton-max-iterations", &Config::newton_max_iterations, "NEWTON_AC: Newton iterations per step, at most", Run},
      {"policy", &Config::policy, "NLGS convergence: Quad, Maxm, QM/16, Strict, NonStrict (the paper's non-strict GS), Energy", Run},
      {"tol", &Config::tol, "NLGS tolerance", Run},
      {"check-every", &Config::check_every, "NLGS sweeps between convergence checks", Run},
      {"min-sweeps", &Config::min_sweeps, "NLGS minimum sweeps per step", Run},
      {"max-sweeps", &Config::max_sweeps, "NLGS maximum sweeps per step", Run},
      {"relaxation", &Config::relaxation, "NLGS relaxation omega in (0, 2) of the sweeps between checks (checked sweeps are plain); 1: the paper's; 1.3 needs about 0.75x the sweeps on the loaded ballast, with larger overlaps over long runs (docs/studies.md 5.8)", Run},
      {"order", &Config::order, "NLGS sweep order: fixed, reversed, shuffled, alternating, colored (graph-coloured, parallel with --threads; a small scene in strips across its longer side), colored-rows (the same, a small scene in cells swept row by row from the bottom), colored-cells (the cells swept row by row from the top, each cell upward: on 4 threads or more the rows sweep at once)", Run},
      {"anderson", &Config::anderson, "Anderson mixing of the NLGS sweeps, depth 1 to 8 (0: off), in any --order; the mixed sweeps are plain, --relaxation takes over where the mixing stalls and the mixing again where the relaxed sweeps stall (docs/theory.md 9.5b)", Run},
      nscd::driver::threads_option<Config>(),
      nscd::driver::solve_threads_option<Config>(),
      nscd::driver::loop_threads_option<Config>(),
      nscd::driver::solve_profile_option<Config>(),
      {"plan-model", &Config::plan_model, "thread counts (e.g. 1,2,4,8,16): after the cycles, print what the planned sweep of the next step's system allows each count, on a model (shared/driver/plan_table.hpp; results unchanged); needs --order colored, colored-rows or colored-cells", Free, nscd::driver::kNoDefault},
      // the stepper's checks (StepperOptions; Run: a resumed run keeps the checks it was started with)
      {"strict-alert", &Config::strict_alert, "stop with an error when a step moves a body farther than the alert distance (default: warn and count)", Run},
      {"residual-check-every", &Config::residual_check_every, "compute the natural-map residual / |q| of the contact problem every N steps, independently of the solver's criterion (0: never); results are unchanged", Run},
      {"residual-flag", &Config::residual_flag, "a checked step that the solver calls converged with a residual above this is counted (false_converged_steps) and warned about", Run},
      {"residual-limit", &Config::residual_limit, "stop with an error when a checked step's residual is above this (0: never)", Run},
      {"projection", &Config::projection, "after each solve, move the grains apart where an overlap passes the slop (positions only, velocities untouched; docs/theory.md 8.4); false: the paper's scheme, whose overlaps creep over long runs", Run},
      {"projection-slop", &Config::projection_slop, "overlap the projection leaves alone, as a fraction of --alert (1e-4 x 1.25 mm = 125 nm)", Run},
      {"projection-share", &Config::projection_share, "share of an overlap's excess beyond the slop that the projection removes in one step, in (0, 1]", Run},
      nscd::driver::overlap_limit_option<Config>(nscd::driver::OverlapYardstick::Grain),
      nscd::driver::strict_overlap_option<Config>(nscd::driver::StrictStop::AtCycleEnd, nscd::driver::kNone),
      {"prep-max-time", &Config::prep_max_time, "deposit: simulated time limit (s)", Scene},
      {"settle-time", &Config::settle_time, "sleeper settling: simulated time limit (s)", Scene},
      {"equilibrium-speed", &Config::equilibrium_speed, "rest: rms speed below this (m/s)", Scene},
      {"cycles", &Config::cycles, "loading cycles to run (total, including resumed ones)", Free},
      {"checkpoint-every", &Config::checkpoint_every, "cycles between checkpoints (0: at the end only)", Run},
      {"checkpoint-wall", &Config::checkpoint_wall, "wall seconds between checkpoints besides --checkpoint-every: one at the first cycle end after that long (0: none)", Free},
      {"steps-every", &Config::steps_every, "steps between rows of steps.csv", Run},
      {"vtk-every", &Config::vtk_every, "steps between VTK frames (0: none)", Run},
      {"output", &Config::output, "output directory", Free},
      {"sample", &Config::sample, "load a prepared sample (sample.nscd of an earlier run) instead of preparing one", Free},
      {"prepare-only", &Config::prepare_only, "prepare the sample, save it and stop (true/false)", Free},
      {"resume", &Config::resume, "continue the run saved in this output directory (its checkpoint.nscd)", Free},
      {"continue", &Config::continue_run, "batch jobs: if --output holds this run's checkpoint, resume it (nothing to do once it has --cycles); otherwise start it there as --overwrite would", Free},
      {"stop-after-cycles", &Config::stop_after_cycles, "stop this process after that many cycles (0: no limit)", Free},
      {"progress-every", &Config::progress_every, "wall seconds between progress lines", Free},
      {"overwrite", &Config::overwrite, "replace the run found in a non-empty --output folder (its files are deleted first)", Free},
  };
  return t;
}

// The table with the toolkit's machinery; every bool is "--name" alone = true, or --name=false.
const nscd::driver::OptionTable<Config>& options() {
  static const nscd::driver::OptionTable<Config> t = [] {
    std::vector<Opt> rows = table();
    for (Opt& o : rows)
      if (std::holds_alternative<bool Config::*>(o.member)) o.flags |= nscd::driver::kImplicit;
    return nscd::driver::OptionTable<Config>(
        "ballast",
        "the ballast settlement study (Saussine et al. 2006): a sleeper loaded by\n"
        "F = A + B cos(2 pi f t - phi) on a layer of graded pentagons over a visco-elastic sublayer.",
        std::move(rows));
  }();
  return t;
}

std::string text(double v) { return nscd::exact(v); }

}  // namespace

bool parse(int argc, char** argv, Config& c) {
  if (!options().parse(argc, argv, c, &c.given)) return false;
  // the default mixing goes with the default colored order: another order given alone sweeps unmixed
  if (!nscd::driver::is_colored_order(c.order) && !c.given.count("anderson")) c.anderson = 0;
  check(c);
  return true;
}

void check(const Config& c) {
  using driver::require;
  auto pos = [](double v) { return std::isfinite(v) && v > 0.0; };
  // every real finite (Boost reads "inf" and "nan" as numbers)
  options().require_finite(c);
  require(c.cycles >= 0 && c.stop_after_cycles >= 0 && c.checkpoint_every >= 0, "--cycles, --stop-after-cycles, --checkpoint-every must be >= 0");
  require(c.checkpoint_wall >= 0, "--checkpoint-wall must be >= 0 (0: none), got " + text(c.checkpoint_wall));
  require(!c.continue_run || (c.resume.empty() && !c.prepare_only), "--continue cannot go with --resume or --prepare-only (it resumes --output when it holds a checkpoint)");
  require(c.cycles > 0 || c.prepare_only,
          "--cycles 0 runs no loading cycle: give --prepare-only to prepare and save the sample only, or --cycles N > 0");
  require(!c.prepare_only || (c.sample.empty() && c.resume.empty()), "--prepare-only prepares a new sample: it cannot go with --sample or --resume");
  require(c.sample.empty() || c.resume.empty(), "--sample and --resume cannot go together (a resumed run continues on its own sample)");
  require(!c.overwrite || c.resume.empty(), "--overwrite and --resume cannot go together: --resume continues the run in the folder, --overwrite replaces it");
  require(c.steps_every >= 1 && c.vtk_every >= 0, "--steps-every must be >= 1 and --vtk-every >= 0");
  require(c.frequency > 0, "--frequency must be > 0, got " + text(c.frequency));
  require(std::abs(c.inclination) <= 90.0, "--inclination must lie in [-90, 90] degrees, got " + text(c.inclination));
  require(c.k_factor > 0, "--k-factor must be > 0, got " + text(c.k_factor));
  require(c.ramp_cycles >= 0, "--ramp-cycles must be >= 0");
  require(c.prep_max_time > 0 && c.settle_time >= 0 && c.equilibrium_speed > 0, "--prep-max-time and --equilibrium-speed must be > 0, --settle-time >= 0");
  require(c.progress_every > 0, "--progress-every must be > 0");
  require(c.theta >= 0.5 && c.theta <= 1.0, "--theta must lie in [0.5, 1], got " + text(c.theta));
  require(pos(c.alert), "--alert must be > 0, got " + text(c.alert));
  require(pos(c.dt), "--dt must be > 0, got " + text(c.dt));
  // A grain at rest falls g dt² in one step: more than the alert distance and detection cannot
  // follow even a free fall from rest (docs/user-guide.md, "Ranges").
  const double dt_max = std::sqrt(c.alert / 9.81);
  require(c.dt <= dt_max, "--dt " + text(c.dt) + " s is too long for --alert " + text(c.alert) + " m: a grain falls g dt^2 = " +
                               text(9.81 * c.dt * c.dt) + " m in one step from rest, more than the alert distance (dt must be <= sqrt(alert/g) = " +
                               text(dt_max) + " s)");
  const double n = 1.0 / (c.frequency * c.dt);
  require(std::abs(n - std::round(n)) < 1e-6 * n && n >= 2, "1/(frequency dt) must be an integer >= 2 (steps per cycle); got " + text(n));
  require(pos(c.tol) && pos(c.newton_tol) && pos(c.newton_presweep_tol), "--tol, --newton-tol and --newton-presweep-tol must be > 0");
  require(c.check_every >= 1 && c.min_sweeps >= 0 && c.max_sweeps >= 1 && c.min_sweeps <= c.max_sweeps,
          "--check-every and --max-sweeps must be >= 1, --min-sweeps in [0, max-sweeps]");
  require(c.newton_presweeps >= 0 && c.newton_max_iterations >= 1, "--newton-presweeps must be >= 0 and --newton-max-iterations >= 1");
  require(c.relaxation > 0 && c.relaxation < 2, "--relaxation must lie in (0, 2), got " + text(c.relaxation));
  try {
    nscd::parse_sweep_order(c.order);
  } catch (const nscd::Error& e) {
    throw InputError(std::string("--order: ") + e.what());
  }
  // a resumed run's order comes from its checkpoint: checked there (ballast_study.cpp, run)
  nscd::driver::check_threads(c.threads, c.solve_threads, c.loop_threads, c.resume.empty() ? c.order : "colored");
  if (!c.plan_model.empty()) {
    nscd::driver::parse_thread_list(c.plan_model, "--plan-model");
    require(nscd::driver::is_colored_order(c.order) || !c.resume.empty(),
            "--plan-model needs --order colored, colored-rows or colored-cells (the other orders plan no sweep), got --order " + c.order);
  }
  require(c.relaxation == 1.0 || c.check_every >= 2,
          "--relaxation " + text(c.relaxation) + " needs --check-every >= 2: a checked sweep is plain Gauss-Seidel, so with a check every sweep the relaxation would never be used");
  require(c.anderson >= 0 && c.anderson <= 8, "--anderson must lie in [0, 8] (0: off), got " + std::to_string(c.anderson));
  require(c.residual_check_every >= 0, "--residual-check-every must be >= 0 (0: never), got " + std::to_string(c.residual_check_every));
  require(pos(c.residual_flag), "--residual-flag must be > 0, got " + text(c.residual_flag));
  require(c.residual_limit >= 0, "--residual-limit must be >= 0 (0: never), got " + text(c.residual_limit));
  require(c.projection_slop >= 0 && c.projection_slop <= 1, "--projection-slop must lie in [0, 1] (a fraction of --alert), got " + text(c.projection_slop));
  require(c.projection_share > 0 && c.projection_share <= 1, "--projection-share must lie in (0, 1], got " + text(c.projection_share));
  nscd::driver::check_overlap_options(c.overlap_limit, c.strict_overlap, nscd::driver::OverlapYardstick::Grain);
  // the scene (nscd::scenes::validate checks the rest when a sample is prepared)
  require(c.mu >= 0, "--mu must be >= 0, got " + text(c.mu));
  require(c.pads >= 1 && c.bars >= 0, "--pads must be >= 1 and --bars >= 0");
  require(c.k >= 0 && c.nu >= 0, "--k and --nu must be >= 0");
  require(pos(c.box_width) && pos(c.spring_length) && pos(c.sleeper_width) && pos(c.pad_height),
          "--box-width, --spring-length, --sleeper-width and --pad-height must be > 0");
  require(pos(c.grading_fraction) && c.grading_fraction <= 1000, "--grading-fraction must lie in (0, 1000]");
}

std::map<std::string, std::string> to_map(const Config& c) { return options().to_map(c, false); }
std::map<std::string, std::string> scene_map(const Config& c) { return options().to_map(c, true); }

void from_map(const std::map<std::string, std::string>& m, Config& c, const std::string& source) { options().from_map(m, c, source); }

void refuse_changes(const Config& cli, const std::map<std::string, std::string>& stored, bool scene_only, const std::string& source) {
  options().refuse_changes(cli, cli.given, stored, scene_only, source);
}

}  // namespace ballast
