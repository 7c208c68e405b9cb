// examples/deposit/options.cpp — the deposit study's options (deposit, lmgc90_deposit_case):
// one table (nscd::driver::OptionTable, shared/driver/options.hpp) for the command line, the
// --config file and --help; then the checks of the values and of the options that cannot go
// together.
#include <cmath>
#include <string>

#include "deposit_study.hpp"
#include "nscd/io/text_reader.hpp"
#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/overlap_options.hpp"
#include "nscd/shared/driver_checks.hpp"

using namespace nscd;

namespace deposit {
namespace {

using driver::InputError;
using driver::Kind;
using driver::kImplicit;
using driver::kSwitch;

driver::OptionTable<Config> table(const std::string& program, const std::string& about) {
  return driver::OptionTable<Config>(program, about, {
      {"scene", &Config::scene, "scene: 'paper' (724 graded pentagons, Saussine 2006) or 'lmgc90' (700 pentagons, the LMGC90 benchmark)"},
      {"seed", &Config::seed, "random seed: grading shuffle and orientations"},
      {"sample-file", &Config::sample_file, "scene lmgc90: read the grains (centres, radii, orientations, vertices) from this file instead of drawing them, e.g. tests/data/lmgc90/deposit_700.txt, LMGC90's own sample (format: shared/sample_file.hpp)"},
      {"walls", &Config::walls, "scene lmgc90: 'polyg' (POLYG rectangles 5 cm thick, PLPLx contacts) or 'jonc' (JONCx of half-thickness 25 mm with the same inner faces, PLJCx contacts: LMGC90's own walls)"},
      {"grains", &Config::grains, "paper scene: N grains of the paper's grading (same 1/2, 1/3, 1/6 class shares), the box width scaled to 1 m x N / 724 so that the layer depth stays the paper's (0: the paper's 724 grains in --box-width)"},
      {"box-width", &Config::box_width, "box width (m), paper scene"},
      {"pitch-factor", &Config::pitch_factor, "start lattice pitch / largest diameter, paper scene (> 1: no initial contact)"},
      {"density", &Config::density, "grain density (kg/m^3)"},
      {"mu", &Config::mu, "friction coefficient, every contact"},
      {"law", &Config::law, "contact law: IQS_CLB or GAP_SGR_CLB"},
      {"dt", &Config::dt, "time step h (s)"},
      {"theta", &Config::theta, "theta of the theta-method, in [0.5, 1]"},
      {"alert", &Config::alert, "alert distance of the detection (m)"},
      {"solver", &Config::solver, "contact solver: NLGS or NEWTON_AC (global semismooth Newton on SuiteSparse)"},
      {"newton-tol", &Config::newton_tol, "NEWTON_AC tolerance: natural-map residual over |q|"},
      {"newton-presweeps", &Config::newton_presweeps, "NEWTON_AC hybrid: at most this many NLGS sweeps (to Quad 1e-3) before Newton, 0: pure Newton"},
      {"newton-max-iterations", &Config::newton_max_iterations, "NEWTON_AC: Newton iterations per step, at most"},
      {"policy", &Config::policy, "NLGS convergence: Quad, Maxm, QM/16, Strict, NonStrict, Energy"},
      {"tol", &Config::tol, "NLGS tolerance"},
      {"check-every", &Config::check_every, "NLGS sweeps between convergence checks"},
      {"min-sweeps", &Config::min_sweeps, "NLGS minimum sweeps per step"},
      {"max-sweeps", &Config::max_sweeps, "NLGS maximum sweeps per step"},
      {"relaxation", &Config::relaxation, "NLGS relaxation, in (0, 2)"},
      {"order", &Config::order, "NLGS sweep order: fixed, reversed, shuffled, alternating, colored (graph-coloured, parallel with --threads; a small scene in strips across its longer side), colored-rows (the same, a small scene in cells swept row by row from the bottom), colored-cells (the cells swept row by row from the top, each cell upward: on 4 threads or more the rows sweep at once)"},
      {"anderson", &Config::anderson, "Anderson mixing of the NLGS sweeps, depth 1 to 8 (0: off), in any --order; the mixed sweeps are plain, --relaxation takes over where the mixing stalls and the mixing again where the relaxed sweeps stall (docs/theory.md 9.5b)"},
      nscd::driver::threads_option<Config>(),
      nscd::driver::solve_threads_option<Config>(),
      nscd::driver::loop_threads_option<Config>(),
      nscd::driver::solve_profile_option<Config>(),
      {"warm-start", &Config::warm_start, "start each step from the last step's forces (true/false)"},
      {"skip-zero", &Config::skip_zero, "LMGC90's skip rule: between checks, visit contacts with a zero impulse after 1, 3, 6, ... sweeps only", Kind::Free, kImplicit},
      {"steps", &Config::steps, "fixed number of steps (0: run to equilibrium)"},
      {"max-time", &Config::max_time, "simulated time limit (s)"},
      {"min-time", &Config::min_time, "no equilibrium test before this time (s)"},
      {"equilibrium-speed", &Config::equilibrium_speed, "equilibrium: rms grain speed below this (m/s) ..."},
      {"equilibrium-window", &Config::equilibrium_window, "... for this long (s)"},
      {"output", &Config::output, "output directory"},
      {"vtk-every", &Config::vtk_every, "steps between VTK frames (0: first and last only)"},
      {"no-vtk", &Config::no_vtk, "write no VTK file", Kind::Free, kSwitch},
      {"dump-unconverged", &Config::dump_unconverged, "write the contact problems of the first N steps whose solver did not converge to OUTPUT/problems/step_<n>.txt (nscd dump format, with the solver's impulses), to re-solve them with any solver"},
      {"strict-alert", &Config::strict_alert, "stop with an error when a step moves a body farther than the alert distance (default: warn and count)", Kind::Free, kSwitch},
      {"residual-check-every", &Config::residual_check_every, "compute the natural-map residual / |q| of the contact problem every N steps, independently of the solver's criterion (0: never); results are unchanged"},
      {"residual-flag", &Config::residual_flag, "a checked step that the solver calls converged with a residual above this is counted (false_converged_steps) and warned about"},
      {"residual-limit", &Config::residual_limit, "stop with an error when a checked step's residual is above this (0: never)"},
      {"projection", &Config::projection, "after each solve, move the grains apart where an overlap passes the slop (positions only, velocities untouched; docs/theory.md 8.4); false: the paper's scheme", Kind::Free, kImplicit},
      {"projection-slop", &Config::projection_slop, "overlap the projection leaves alone, as a fraction of --alert"},
      {"projection-share", &Config::projection_share, "share of an overlap's excess beyond the slop that the projection removes in one step, in (0, 1]"},
      driver::overlap_limit_option<Config>(driver::OverlapYardstick::Grain),
      driver::strict_overlap_option<Config>(driver::StrictStop::AtStep),
      {"progress-every", &Config::progress_every, "wall seconds between progress lines"},
      {"overwrite", &Config::overwrite, "replace the run found in a non-empty --output folder (its files are deleted first)", Kind::Free, kSwitch},
  });
}

}  // namespace

bool parse(int argc, char** argv, Config& c, const std::string& program, const std::string& about) {
  if (!table(program, about).parse(argc, argv, c, &c.given)) return false;
  // the default mixing goes with the default colored order: another order given alone sweeps unmixed
  if ((!nscd::driver::is_colored_order(c.order)) || c.skip_zero)
    if (!c.given.count("anderson")) c.anderson = 0;
  check(c);
  return true;
}

void check(const Config& c) {
  using driver::require;
  auto pos = [](double v) { return std::isfinite(v) && v > 0.0; };
  table("deposit", "").require_finite(c);  // every real finite
  require(c.scene == "paper" || c.scene == "lmgc90", "--scene must be 'paper' or 'lmgc90', got '" + c.scene + "'");
  if (c.scene == "lmgc90") scenes::refuse_options(c.given, {"box-width", "pitch-factor", "grains"}, "--scene lmgc90 (its box and lattice are fixed)");
  require(c.walls == "polyg" || c.walls == "jonc", "--walls must be 'polyg' or 'jonc', got '" + c.walls + "'");
  if (c.scene != "lmgc90") scenes::refuse_options(c.given, {"walls"}, "--scene " + c.scene + " (its walls are POLYG; --walls is for --scene lmgc90)");
  if (!c.sample_file.empty()) {
    require(c.scene == "lmgc90", "--sample-file needs --scene lmgc90 (the file gives the grains, the LMGC90 case the box), got --scene " + c.scene);
    scenes::refuse_options(c.given, {"seed"}, "--sample-file (the file gives every grain)");
  }
  if (c.given.count("grains")) {
    scenes::refuse_options(c.given, {"box-width"}, "--grains (the box width is scaled with the number of grains)");
    require(c.grains >= 1 && c.grains <= kMaxGrains, "--grains must lie in [1, " + std::to_string(kMaxGrains) + "], got " +
                                                         std::to_string(c.grains) + " (0 grains is no deposit; beyond " +
                                                         std::to_string(kMaxGrains) + " the run needs more memory and time than a deposit driver should take)");
  } else {
    require(c.grains == 0 || (c.grains >= 1 && c.grains <= kMaxGrains), "grains must be 0 (the paper's 724) or in [1, " + std::to_string(kMaxGrains) + "], got " + std::to_string(c.grains));
  }
  if (c.no_vtk) scenes::refuse_options(c.given, {"vtk-every"}, "--no-vtk");
  require(pos(c.box_width), "--box-width must be > 0, got " + exact(c.box_width));
  // Below 0.8 d_max the start lattice overlaps neighbours deeper than the packed sample does
  // (samples.hpp): the grains are thrown apart and the packing fraction can exceed 1.
  require(c.pitch_factor >= scenes::kPackedPitchFactor && c.pitch_factor <= 100.0,
          "--pitch-factor must lie in [0.8, 100], got " + exact(c.pitch_factor) +
              " (below 0.8 the start lattice makes neighbouring grains overlap deeply)");
  require(pos(c.density), "--density must be > 0, got " + exact(c.density));
  require(c.mu >= 0, "--mu must be >= 0, got " + exact(c.mu));
  require(c.theta >= 0.5 && c.theta <= 1.0, "--theta must lie in [0.5, 1], got " + exact(c.theta));
  require(pos(c.alert), "--alert must be > 0, got " + exact(c.alert));
  require(pos(c.dt), "--dt must be > 0, got " + exact(c.dt));
  // A grain at rest falls g dt² in one step: beyond the alert distance detection cannot follow
  // even a free fall from rest (docs/user-guide.md, "Ranges").
  const double dt_max = std::sqrt(c.alert / 9.81);
  require(c.dt <= dt_max, "--dt " + exact(c.dt) + " s is too long for --alert " + exact(c.alert) + " m: a grain falls g dt^2 = " +
                               exact(9.81 * c.dt * c.dt) + " m in one step from rest, more than the alert distance (dt must be <= sqrt(alert/g) = " +
                               exact(dt_max) + " s)");
  require(pos(c.max_time) && c.min_time >= 0 && c.equilibrium_window >= 0, "--max-time must be > 0, --min-time and --equilibrium-window >= 0");
  require(c.steps >= 0 && c.vtk_every >= 0 && c.dump_unconverged >= 0, "--steps, --vtk-every and --dump-unconverged must be >= 0");
  const double steps = c.steps > 0 ? double(c.steps) : std::ceil(c.max_time / c.dt);
  require(steps <= 1e9, "the run would take " + exact(steps) + " steps (--steps, or --max-time / --dt): at most 1e9");
  require(c.law == "IQS_CLB" || c.law == "GAP_SGR_CLB", "--law must be IQS_CLB or GAP_SGR_CLB for a deposit (e = 0), got '" + c.law + "'");
  require(pos(c.tol) && pos(c.newton_tol), "--tol and --newton-tol must be > 0");
  require(c.anderson >= 0 && c.anderson <= 8, "--anderson must lie in [0, 8] (0: off), got " + std::to_string(c.anderson));
  require(c.anderson == 0 || !c.skip_zero, "--anderson and --skip-zero do not go together");
  require(c.relaxation > 0 && c.relaxation < 2, "--relaxation must lie in (0, 2), got " + exact(c.relaxation));
  require(c.relaxation == 1.0 || c.check_every >= 2,
          "--relaxation " + exact(c.relaxation) + " needs --check-every >= 2: a checked sweep is plain Gauss-Seidel, so with a check every sweep the relaxation would never be used");
  require(c.check_every >= 1 && c.min_sweeps >= 0 && c.max_sweeps >= 1 && c.min_sweeps <= c.max_sweeps,
          "--check-every and --max-sweeps must be >= 1, --min-sweeps in [0, max-sweeps]");
  require(c.newton_presweeps >= 0 && c.newton_max_iterations >= 1, "--newton-presweeps must be >= 0 and --newton-max-iterations >= 1");
  require(pos(c.equilibrium_speed) && pos(c.progress_every), "--equilibrium-speed and --progress-every must be > 0");
  // the colored order's threads (NlgsOptions::threads) and the stepper's checks (StepperOptions)
  nscd::driver::check_threads(c.threads, c.solve_threads, c.loop_threads, c.order);
  require(c.residual_check_every >= 0, "--residual-check-every must be >= 0 (0: never), got " + std::to_string(c.residual_check_every));
  require(pos(c.residual_flag), "--residual-flag must be > 0, got " + exact(c.residual_flag));
  require(c.residual_limit >= 0, "--residual-limit must be >= 0 (0: never), got " + exact(c.residual_limit));
  require(c.projection_slop >= 0 && c.projection_slop <= 1, "--projection-slop must lie in [0, 1] (a fraction of --alert), got " + exact(c.projection_slop));
  require(c.projection_share > 0 && c.projection_share <= 1, "--projection-share must lie in (0, 1], got " + exact(c.projection_share));
  driver::check_overlap_options(c.overlap_limit, c.strict_overlap, driver::OverlapYardstick::Grain);
}

}  // namespace deposit
