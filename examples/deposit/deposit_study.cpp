// examples/deposit/deposit_study.cpp — see deposit_study.hpp. The run, step by step:
//   1. build the scene (the paper's sample, or the LMGC90 benchmark scene)
//   2. set the time stepping, the contact law and the NLGS options
//   3. step until equilibrium (or a fixed number of steps), writing steps.csv, VTK frames
//      and a progress line with an ETA
//   4. write summary.txt and the final state (final_state.nscd) for reuse
#include "deposit_study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/io/csv.hpp"
#include "nscd/io/text_reader.hpp"
#include "nscd/io/vtk_writer.hpp"
#include "nscd/shared/analysis.hpp"
#include "nscd/shared/driver_checks.hpp"
#include "nscd/shared/grading.hpp"
#include "nscd/shared/postpro.hpp"
#include "nscd/shared/progress.hpp"
#include "nscd/shared/sample_file.hpp"
#include "nscd/shared/step_watch.hpp"

namespace po = boost::program_options;
using namespace nscd;

namespace deposit {

void add_options(po::options_description& d, Config& c) {
  auto o = d.add_options();
  o("scene", po::value(&c.scene)->default_value(c.scene), "scene: 'paper' (724 graded pentagons, Saussine 2006) or 'lmgc90' (700 pentagons, the LMGC90 benchmark)");
  o("seed", po::value(&c.seed)->default_value(c.seed), "random seed: grading shuffle and orientations");
  o("sample-file", po::value(&c.sample_file)->default_value(c.sample_file), "scene lmgc90: read the grains (centres, radii, orientations, vertices) from this file instead of drawing them, e.g. tests/data/lmgc90/deposit_700.txt, LMGC90's own sample (format: shared/sample_file.hpp)");
  o("grains", po::value(&c.grains)->default_value(c.grains), "paper scene: N grains of the paper's grading (same 1/2, 1/3, 1/6 class shares), the box width scaled to 1 m x N / 724 so that the layer depth stays the paper's (0: the paper's 724 grains in --box-width)");
  o("box-width", po::value(&c.box_width)->default_value(c.box_width), "box width (m), paper scene");
  o("pitch-factor", po::value(&c.pitch_factor)->default_value(c.pitch_factor), "start lattice pitch / largest diameter, paper scene (> 1: no initial contact)");
  o("density", po::value(&c.density)->default_value(c.density), "grain density (kg/m^3)");
  o("mu", po::value(&c.mu)->default_value(c.mu), "friction coefficient, every contact");
  o("law", po::value(&c.law)->default_value(c.law), "contact law: IQS_CLB or GAP_SGR_CLB");
  o("dt", po::value(&c.dt)->default_value(c.dt), "time step h (s)");
  o("theta", po::value(&c.theta)->default_value(c.theta), "theta of the theta-method, in [0.5, 1]");
  o("alert", po::value(&c.alert)->default_value(c.alert), "alert distance of the detection (m)");
  o("solver", po::value(&c.solver)->default_value(c.solver), "contact solver: NLGS or NEWTON_AC (global semismooth Newton on SuiteSparse)");
  o("newton-tol", po::value(&c.newton_tol)->default_value(c.newton_tol), "NEWTON_AC tolerance: natural-map residual over |q|");
  o("newton-presweeps", po::value(&c.newton_presweeps)->default_value(c.newton_presweeps), "NEWTON_AC hybrid: at most this many NLGS sweeps (to Quad 1e-3) before Newton, 0: pure Newton");
  o("newton-max-iterations", po::value(&c.newton_max_iterations)->default_value(c.newton_max_iterations), "NEWTON_AC: Newton iterations per step, at most");
  o("policy", po::value(&c.policy)->default_value(c.policy), "NLGS convergence: Quad, Maxm, QM/16, Strict, NonStrict, Energy");
  o("tol", po::value(&c.tol)->default_value(c.tol), "NLGS tolerance");
  o("check-every", po::value(&c.check_every)->default_value(c.check_every), "NLGS sweeps between convergence checks");
  o("min-sweeps", po::value(&c.min_sweeps)->default_value(c.min_sweeps), "NLGS minimum sweeps per step");
  o("max-sweeps", po::value(&c.max_sweeps)->default_value(c.max_sweeps), "NLGS maximum sweeps per step");
  o("relaxation", po::value(&c.relaxation)->default_value(c.relaxation), "NLGS relaxation, in (0, 2)");
  o("order", po::value(&c.order)->default_value(c.order), "NLGS sweep order: fixed, reversed, shuffled, alternating, colored (graph-coloured, parallel with --threads)");
  o("threads", po::value(&c.threads)->default_value(c.threads), "threads (OpenMP) of the NLGS sweep and the narrow phase; > 1 needs --order colored; the results do not depend on it");
  o("warm-start", po::value(&c.warm_start)->default_value(c.warm_start), "start each step from the last step's forces (true/false)");
  o("skip-zero", po::value(&c.skip_zero)->default_value(c.skip_zero)->implicit_value(true), "LMGC90's skip rule: between checks, visit contacts with a zero impulse after 1, 3, 6, ... sweeps only");
  o("steps", po::value(&c.steps)->default_value(c.steps), "fixed number of steps (0: run to equilibrium)");
  o("max-time", po::value(&c.max_time)->default_value(c.max_time), "simulated time limit (s)");
  o("min-time", po::value(&c.min_time)->default_value(c.min_time), "no equilibrium test before this time (s)");
  o("equilibrium-speed", po::value(&c.equilibrium_speed)->default_value(c.equilibrium_speed), "equilibrium: rms grain speed below this (m/s) ...");
  o("equilibrium-window", po::value(&c.equilibrium_window)->default_value(c.equilibrium_window), "... for this long (s)");
  o("output", po::value(&c.output)->default_value(c.output), "output directory");
  o("vtk-every", po::value(&c.vtk_every)->default_value(c.vtk_every), "steps between VTK frames (0: first and last only)");
  o("no-vtk", po::bool_switch(&c.no_vtk), "write no VTK file");
  o("dump-unconverged", po::value(&c.dump_unconverged)->default_value(c.dump_unconverged), "write the contact problems of the first N steps whose solver did not converge to OUTPUT/problems/step_<n>.txt (nscd dump format, with the solver's impulses), to re-solve them with any solver");
  o("strict-alert", po::bool_switch(&c.strict_alert), "stop with an error when a step moves a body farther than the alert distance (default: warn and count)");
  o("residual-check-every", po::value(&c.residual_check_every)->default_value(c.residual_check_every), "compute the natural-map residual / |q| of the contact problem every N steps, independently of the solver's criterion (0: never); results are unchanged");
  o("residual-flag", po::value(&c.residual_flag)->default_value(c.residual_flag), "a checked step that the solver calls converged with a residual above this is counted (false_converged_steps) and warned about");
  o("residual-limit", po::value(&c.residual_limit)->default_value(c.residual_limit), "stop with an error when a checked step's residual is above this (0: never)");
  o("progress-every", po::value(&c.progress_every)->default_value(c.progress_every), "wall seconds between progress lines");
  o("overwrite", po::bool_switch(&c.overwrite), "replace the run found in a non-empty --output folder (its files are deleted first)");
}

bool parse(int argc, char** argv, Config& c, const std::string& program, const std::string& about) {
  po::options_description desc("Options (also accepted as 'key = value' lines in --config FILE)");
  std::string config;
  desc.add_options()("help,h", "print this help")("config", po::value(&config), "read options from this file (command line wins)");
  add_options(desc, c);
  po::variables_map vm;
  for (int i = 1; i < argc; ++i) scenes::refuse_percent_sign(argv[i], "argument ");
  try {
    po::store(po::parse_command_line(argc, argv, desc), vm);
    if (vm.count("help")) {
      std::cout << program << " — " << about << "\n\n" << desc << "\n";
      return false;
    }
  } catch (const po::error& e) {
    throw std::invalid_argument(e.what());
  }
  if (vm.count("config")) {
    // line by line, each entry checked on its own so that an error names the file and the line
    const std::string file = vm["config"].as<std::string>();
    std::vector<KeyValue> entries;
    try {
      entries = read_key_value_file(file);
    } catch (const Error& e) {
      throw std::invalid_argument(e.what());
    }
    for (const KeyValue& kv : entries) {
      const std::string where = "config file '" + file + "', line " + std::to_string(kv.line) + ": ";
      scenes::refuse_percent_sign(kv.key + " = " + kv.value, where);
      if (kv.key == "config" || kv.key == "help") throw std::invalid_argument(where + "'" + kv.key + "' cannot be given in a config file");
      try {
        po::store(po::command_line_parser(std::vector<std::string>{"--" + kv.key + "=" + kv.value}).options(desc).run(), vm);
      } catch (const po::error& e) {
        throw std::invalid_argument(where + e.what());
      }
    }
  }
  try {
    po::notify(vm);
  } catch (const po::error& e) {
    throw std::invalid_argument(e.what());
  }
  c.given.clear();
  for (const auto& [name, value] : vm)
    if (!value.defaulted() && name != "config") c.given.insert(name);
  check(c);
  return true;
}

void check(const Config& c) {
  auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
  };
  auto pos = [](double v) { return std::isfinite(v) && v > 0.0; };
  const std::pair<const char*, double> reals[] = {
      {"box-width", c.box_width}, {"pitch-factor", c.pitch_factor}, {"density", c.density}, {"mu", c.mu}, {"dt", c.dt},
      {"theta", c.theta}, {"alert", c.alert}, {"newton-tol", c.newton_tol}, {"tol", c.tol}, {"relaxation", c.relaxation},
      {"max-time", c.max_time}, {"min-time", c.min_time}, {"equilibrium-speed", c.equilibrium_speed},
      {"equilibrium-window", c.equilibrium_window}, {"progress-every", c.progress_every}, {"residual-flag", c.residual_flag},
      {"residual-limit", c.residual_limit}};
  for (const auto& [name, v] : reals) require(std::isfinite(v), std::string("--") + name + " must be a finite number, got " + exact(v));
  require(c.scene == "paper" || c.scene == "lmgc90", "--scene must be 'paper' or 'lmgc90', got '" + c.scene + "'");
  if (c.scene == "lmgc90") scenes::refuse_options(c.given, {"box-width", "pitch-factor", "grains"}, "--scene lmgc90 (its box and lattice are fixed)");
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
  require(c.relaxation > 0 && c.relaxation < 2, "--relaxation must lie in (0, 2), got " + exact(c.relaxation));
  require(c.check_every >= 1 && c.min_sweeps >= 0 && c.max_sweeps >= 1 && c.min_sweeps <= c.max_sweeps,
          "--check-every and --max-sweeps must be >= 1, --min-sweeps in [0, max-sweeps]");
  require(c.newton_presweeps >= 0 && c.newton_max_iterations >= 1, "--newton-presweeps must be >= 0 and --newton-max-iterations >= 1");
  require(pos(c.equilibrium_speed) && pos(c.progress_every), "--equilibrium-speed and --progress-every must be > 0");
  // the colored order's threads (NlgsOptions::threads) and the stepper's checks (StepperOptions)
  require(c.threads >= 1 && c.threads <= 256, "--threads must lie in [1, 256], got " + std::to_string(c.threads));
  require(c.threads == 1 || c.order == "colored",
          "--threads " + std::to_string(c.threads) + " needs --order colored (the other orders sweep on one thread), got --order " + c.order);
  require(c.residual_check_every >= 0, "--residual-check-every must be >= 0 (0: never), got " + std::to_string(c.residual_check_every));
  require(pos(c.residual_flag), "--residual-flag must be > 0, got " + exact(c.residual_flag));
  require(c.residual_limit >= 0, "--residual-limit must be >= 0 (0: never), got " + exact(c.residual_limit));
}

namespace {

using Clock = std::chrono::steady_clock;

// ---- 1. the scenes -----------------------------------------------------------------------
// The LMGC90 benchmark: 700 regular pentagons, circumradius uniform in [12.5, 25] mm, on a
// 28 × 25 lattice of pitch 55 mm (first site 27.5 mm from the left wall and the floor), in a box
// 1.54 m wide with fixed walls.
scenes::Scene lmgc90_scene(std::uint64_t seed, const std::string& sample_file) {
  scenes::Scene s;
  s.grain_material = add_material(s.reg, "grain", 2700.0);
  s.wall_material = add_material(s.reg, "wall", 2700.0);
  s.box_width = 1.54;
  s.box_height = 1.45;
  s.walls = scenes::add_box(s.reg, s.wall_material, s.box_width, s.box_height, 0.05);
  if (!sample_file.empty()) {
    // LMGC90's own sample (contrib/lmgc90/deposit_700.py): lattice corner at (0, 25 mm), so
    // the first row stands 52.5 mm above the floor
    const std::vector<scenes::SampleGrain> g = scenes::read_sample_file(sample_file);
    for (const scenes::SampleGrain& grain : g)
      for (const Vec2& v : grain.vertices)
        if (!(v.x > 0.0 && v.x < s.box_width && v.y > 0.0 && v.y < s.box_height))
          throw Error("sample file '" + sample_file + "', line " + std::to_string(grain.line) + ": vertex (" + exact(v.x) + ", " +
                      exact(v.y) + ") is outside the box (0 < x < " + exact(s.box_width) + ", 0 < y < " + exact(s.box_height) + " m)");
    s.lattice = {0.0275, 0.0525, 28, 0.055, 0.055, 0};
    s.grains = scenes::add_sample_grains(s.reg, s.grain_material, g);
    return s;
  }
  const std::vector<double> d = scenes::expand_grading(scenes::uniform_radius_grading(700, 0.0125, 0.025, seed), seed);
  s.lattice = {0.0275, 0.0275, 28, 0.055, 0.055, seed ^ 0x9E3779B97F4A7C15ull};
  s.grains = scenes::add_pentagons_on_lattice(s.reg, s.grain_material, d, s.lattice);
  return s;
}

scenes::Scene build_scene(const Config& c, double& dmax) {
  if (c.scene == "lmgc90") {
    dmax = 0.05;
    scenes::Scene s = lmgc90_scene(c.seed, c.sample_file);
    set_material_density(s.reg, s.grain_material, c.density);
    return s;
  }
  scenes::SampleOptions o;
  o.seed = c.seed;
  o.box_width = c.box_width;
  if (c.grains > 0) {
    o.grains = static_cast<std::size_t>(c.grains);
    o.box_width = scenes::scaled_box_width(o.grains);
  }
  o.pitch_factor = c.pitch_factor;
  scenes::Scene s = scenes::paper_sample(o);
  set_material_density(s.reg, s.grain_material, c.density);
  dmax = scenes::largest_diameter(scenes::paper_grading());
  return s;
}

}  // namespace

int run(const Config& c) {
  const auto wall0 = Clock::now();
  check(c);  // a Config built by hand gets the command line's checks
  // 0. The output folder: never mixed with an earlier run's files.
  const std::string note = scenes::claim_output_folder(
      c.output, {"steps.csv", "summary.txt", "final_state.nscd", "final_state.nscd.tmp", "vtk", "problems", "refused_step_problem.txt"},
      c.overwrite, false);
  if (!note.empty()) std::printf("deposit: %s\n", note.c_str());
  // 1. Scene.
  double dmax = 0.0;
  scenes::Scene s = build_scene(c, dmax);
  Registry& reg = s.reg;

  // 2. Time stepping, law and solver.
  reg.params.dt = c.dt;
  reg.params.theta = c.theta;
  reg.params.alert = c.alert;
  validate(reg.params);
  set_default_contact_law(reg, LawSpec{parse_law_kind(c.law, "--law"), c.mu});
  StepperOptions so;
  so.solver = parse_solver_kind(c.solver, "--solver");
  so.newton.tol = c.newton_tol;
  so.newton.max_iterations = c.newton_max_iterations;
  so.newton.presweeps = c.newton_presweeps;
  so.nlgs.policy = parse_convergence_policy(c.policy);
  so.nlgs.tol = c.tol;
  so.nlgs.check_every = c.check_every;
  so.nlgs.min_sweeps = c.min_sweeps;
  so.nlgs.max_sweeps = c.max_sweeps;
  so.nlgs.relaxation = c.relaxation;
  so.nlgs.order = parse_sweep_order(c.order);
  so.nlgs.threads = c.threads;
  so.warm_start = c.warm_start;
  so.nlgs.skip_zero = c.skip_zero;
  const std::filesystem::path out(c.output);
  so.strict_alert = c.strict_alert;
  so.residual_check_every = c.residual_check_every;
  so.residual_flag = c.residual_flag;
  so.residual_limit = c.residual_limit;
  so.failure_dump = (out / "refused_step_problem.txt").string();  // a refused step's problem
  MoreauJean mj(reg, so);
  scenes::StepWatch watch;

  // the POSTPRO series (issue #11, docs/output.md) come after the columns of before
  std::vector<std::string> step_columns = {"step", "time", "contacts", "active", "warm_started", "sweeps", "converged", "mean_dvor",
                                           "quad_dv", "maxm_dv", "quad_dvr", "maxm_dvr", "residual_q", "mean_overlap", "max_overlap",
                                           "rms_speed", "detect_s", "solve_s", "step_s", "kinetic_energy", "contact_dissipation",
                                           "contact_dissipation_step"};
  step_columns.insert(step_columns.end(), scenes::network_columns().begin(), scenes::network_columns().end());
  CsvWriter steps_csv(out / "steps.csv", step_columns);
  const scenes::NetworkMeter network(reg, s.grains);
  std::vector<double> row;  // reused: no allocation per row
  double contact_dissipation = 0.0;  // since the first step (J/m)
  std::unique_ptr<VtkWriter> vtk;
  if (!c.no_vtk) {
    vtk = std::make_unique<VtkWriter>(out / "vtk");
    vtk->write_frame(reg);
  }
  const bool newton = so.solver == SolverKind::NEWTON_AC;
  std::printf("deposit: scene %s, %zu grains, %zu bodies, dt %g s, theta %g, %s %s tol %g, output %s\n", c.scene.c_str(),
              s.grains.size(), reg.bodies.size(), c.dt, c.theta, c.solver.c_str(), newton ? "" : c.policy.c_str(),
              newton ? c.newton_tol : c.tol, out.string().c_str());

  // 3. Steps.
  const std::int64_t max_steps = c.steps > 0 ? c.steps : static_cast<std::int64_t>(std::ceil(c.max_time / c.dt - 1e-9));
  const auto calm_needed = static_cast<std::int64_t>(std::ceil(c.equilibrium_window / c.dt));
  std::int64_t calm = 0, unconverged = 0, capped = 0, first_contact = -1, first_active = -1;
  double sum_sweeps = 0.0, max_overlap = 0.0, solve_s = 0.0, detect_s = 0.0;
  bool equilibrium = false;
  StepReport r;
  auto last_print = Clock::now();
  std::vector<double> step_seconds;
  step_seconds.reserve(static_cast<std::size_t>(max_steps));
  std::int64_t n = 0;
  int dumped = 0;
  for (n = 1; n <= max_steps; ++n) {
    if (dumped < c.dump_unconverged) {
      // the step call by call, so that an unconverged step's problem can be written
      const auto t_step = Clock::now();
      mj.begin_step();
      mj.detect();
      mj.prepare();
      mj.solve();
      if (!mj.report().converged) {
        std::filesystem::create_directories(out / "problems");
        write_problem(out / "problems" / ("step_" + std::to_string(reg.step + 1) + ".txt"), mj.local_problem(),
                      mj.impulses());
        ++dumped;
      }
      mj.end_step();
      r = mj.report();
      r.step_seconds = std::chrono::duration<double>(Clock::now() - t_step).count();
    } else {
      r = mj.step();
    }
    watch.observe(reg, r, so);
    const double v = scenes::rms_speed(reg, s.grains);
    sum_sweeps += r.sweeps;
    max_overlap = std::max(max_overlap, r.max_overlap);
    solve_s += r.solve_seconds;
    detect_s += r.detect_seconds;
    step_seconds.push_back(r.step_seconds);
    if (!r.converged) ++unconverged;
    if (!newton && !r.converged && r.sweeps >= c.max_sweeps) ++capped;
    if (first_contact < 0 && r.contacts > 0) first_contact = n;
    if (first_active < 0 && r.active > 0) first_active = n;
    contact_dissipation += r.contact_dissipation;
    row = {double(r.step), r.time, double(r.contacts), double(r.active), double(r.warm_started), double(r.sweeps),
           r.converged ? 1.0 : 0.0, r.criteria.mean_dvor, r.criteria.quad_dv, r.criteria.maxm_dv, r.criteria.quad_dvr,
           r.criteria.maxm_dvr, r.residual, r.mean_overlap, r.max_overlap, v, r.detect_seconds, r.solve_seconds, r.step_seconds,
           kinetic_energy(reg), contact_dissipation, r.contact_dissipation};
    scenes::append_network_values(network.measure(reg), row);
    steps_csv.row(row);
    if (vtk && c.vtk_every > 0 && n % c.vtk_every == 0) vtk->write_frame(reg);
    if (c.steps == 0 && reg.time >= c.min_time) {
      calm = v < c.equilibrium_speed ? calm + 1 : 0;
      if (calm >= calm_needed) equilibrium = true;
    }
    const double since = std::chrono::duration<double>(Clock::now() - last_print).count();
    if (since >= c.progress_every || equilibrium || n == max_steps) {
      last_print = Clock::now();
      const double elapsed = std::chrono::duration<double>(last_print - wall0).count();
      const double eta = elapsed / double(n) * double(max_steps - n);
      std::printf("step %7lld  t %.4f s  contacts %5zu  sweeps %4d%s  rms speed %.2e m/s  max overlap %.2e m  elapsed %s  ETA %s%s\n",
                  static_cast<long long>(n), r.time, r.contacts, r.sweeps, r.converged ? "" : "!", v, r.max_overlap,
                  scenes::format_duration(elapsed).c_str(), scenes::format_duration(eta).c_str(), c.steps == 0 ? " (at most)" : "");
      std::fflush(stdout);
    }
    if (equilibrium) break;
  }
  const std::int64_t done = std::min(n, max_steps);
  steps_csv.flush();
  if (vtk && (c.vtk_every == 0 || done % c.vtk_every != 0)) vtk->write_frame(reg);

  // 4. Summary and final state.
  const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
  const scenes::Window win = scenes::bulk_window(reg, s.grains, s.box_width, dmax);
  const double phi = scenes::packing_fraction(reg, s.grains, win);
  const scenes::ContactNetwork net = scenes::contact_network(reg, s.grains);
  // settled cost: median step time over the last 10 % of the steps
  std::vector<double> tail(step_seconds.end() - static_cast<std::ptrdiff_t>(std::max<std::size_t>(1, step_seconds.size() / 10)), step_seconds.end());
  std::nth_element(tail.begin(), tail.begin() + static_cast<std::ptrdiff_t>(tail.size() / 2), tail.end());
  const double settled_ms = 1e3 * tail[tail.size() / 2];
  // a physically impossible result is written as such, and the exit status says it
  std::string impossible = scenes::implausible(reg, s.grains, s.box_width, 0.0);
  if (impossible.empty() && !(phi <= 1.0)) impossible = "packing fraction " + exact(phi) + " > 1 (grains overlap massively)";
  std::ofstream sum(out / "summary.txt");
  sum.precision(17);
  sum << "result = " << (impossible.empty() ? "valid" : "impossible: " + impossible) << "\n"
      << "scene = " << c.scene << "\n"
      << "sample_file = " << (c.sample_file.empty() ? "none" : c.sample_file) << "\n"
      << "solver = " << c.solver << "\n"
      << "grains = " << s.grains.size() << "\n"
      << "seed = " << c.seed << "\n"
      << "dt = " << c.dt << "\n"
      << "mu = " << c.mu << "\n"
      << "density = " << c.density << "\n"
      << "pitch_factor = " << c.pitch_factor << "\n"
      << "steps = " << done << "\n"
      << "simulated_time = " << reg.time << "\n"
      << "equilibrium_reached = " << (equilibrium ? 1 : 0) << "\n"
      << "wall_time = " << wall << "\n"
      << "solve_time = " << solve_s << "\n"
      << "detect_time = " << detect_s << "\n"
      << "ms_per_step = " << 1e3 * wall / double(done) << "\n"
      << "settled_ms_per_step = " << settled_ms << "\n"
      << "mean_sweeps = " << sum_sweeps / double(done) << "\n"
      << "mean_iterations = " << sum_sweeps / double(done) << "\n"
      << "unconverged_steps = " << unconverged << "\n"
      << "capped_steps = " << capped << "\n"
      << "first_contact_step = " << first_contact << "\n"
      << "first_active_contact_step = " << first_active << "\n"
      << "final_contacts = " << r.contacts << "\n"
      << "final_sweeps = " << r.sweeps << "\n"
      << "packing_fraction = " << phi << "\n"
      << "packing_window = " << win.xmin << " " << win.ymin << " " << win.xmax << " " << win.ymax << "\n"
      << "coordination_number = " << net.coordination_number << "\n"
      << "double_contact_share = " << net.double_contact_share << "\n"
      << "mean_overlap = " << r.mean_overlap << "\n"
      << "max_overlap = " << max_overlap << "\n"
      << "final_max_overlap = " << r.max_overlap << "\n"
      << "rms_grain_speed = " << scenes::rms_speed(reg, s.grains) << "\n"
      << watch.summary();
  if (!sum) throw Error("cannot write " + (out / "summary.txt").string());
  if (!impossible.empty()) {
    std::fflush(stdout);
    std::fprintf(stderr, "deposit: error: physically impossible result: %s; no final state written (exit 3)\n", impossible.c_str());
    return 3;
  }
  save_checkpoint(out / "final_state.nscd", reg, mj.warm_start_memory(), {{"solver", c.solver}});
  std::printf("done: %lld steps, %.3f s simulated, wall %.1f s (%.2f ms/step, settled %.2f ms/step), mean sweeps %.1f,\n"
              "      packing fraction %.3f, coordination %.2f, double contacts %.2f, max overlap %.2e m (final %.2e m)%s\n"
              "      outputs: %s/{summary.txt, steps.csv, final_state.nscd%s}\n",
              static_cast<long long>(done), reg.time, wall, 1e3 * wall / double(done), settled_ms, sum_sweeps / double(done), phi,
              net.coordination_number, net.double_contact_share, max_overlap, r.max_overlap,
              c.steps == 0 && !equilibrium ? "\n      WARNING: equilibrium not reached within --max-time" : "",
              out.string().c_str(), vtk ? ", vtk/" : "");
  std::fputs(watch.closing_line().c_str(), stdout);
  return 0;
}

}  // namespace deposit
