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
#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/run_main.hpp"
#include "nscd/shared/driver/settle.hpp"
#include "nscd/shared/driver/summary.hpp"
#include "nscd/shared/driver_checks.hpp"
#include "nscd/shared/grading.hpp"
#include "nscd/shared/postpro.hpp"
#include "nscd/shared/progress.hpp"
#include "nscd/shared/sample_file.hpp"
#include "nscd/shared/step_watch.hpp"

using namespace nscd;

namespace deposit {

namespace {

using Clock = std::chrono::steady_clock;

// ---- 1. the scenes -----------------------------------------------------------------------
// The LMGC90 benchmark: 700 regular pentagons, circumradius uniform in [12.5, 25] mm, on a
// 28 × 25 lattice of pitch 55 mm (first site 27.5 mm from the left wall and the floor), in a box
// 1.54 m wide with fixed walls.
scenes::Scene lmgc90_scene(std::uint64_t seed, const std::string& sample_file, const std::string& walls) {
  scenes::Scene s;
  s.grain_material = add_material(s.reg, "grain", 2700.0);
  s.wall_material = add_material(s.reg, "wall", 2700.0);
  s.box_width = 1.54;
  s.box_height = 1.45;
  // walls 5 cm thick (POLYG), or LMGC90's JONCx of half-thickness 25 mm with the same inner faces
  s.walls = walls == "jonc" ? scenes::add_jonc_box(s.reg, s.wall_material, s.box_width, s.box_height, 0.025)
                            : scenes::add_box(s.reg, s.wall_material, s.box_width, s.box_height, 0.05);
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
    scenes::Scene s = lmgc90_scene(c.seed, c.sample_file, c.walls);
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

// 0. The output folder: never mixed with an earlier run's files.
void claim_output(const Config& c) {
  const std::string note = scenes::claim_output_folder(
      c.output, {"steps.csv", "summary.txt", "final_state.nscd", "final_state.nscd.tmp", "vtk", "problems", "refused_step_problem.txt", "summary.txt.tmp"},
      c.overwrite, false);
  if (!note.empty()) std::printf("deposit: %s\n", note.c_str());
}

// 2. Time stepping and contact law.
void set_stepping(Registry& reg, const Config& c) {
  reg.params.dt = c.dt;
  reg.params.theta = c.theta;
  reg.params.alert = c.alert;
  validate(reg.params);
  set_default_contact_law(reg, LawSpec{parse_law_kind(c.law, "--law"), c.mu});
}

// 2. The solver and the stepper's checks.
StepperOptions stepper_options(const Config& c, const std::filesystem::path& out) {
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
  so.threads = c.threads;  // the rest of the step's too
  so.solve_threads = c.solve_threads;
  so.loop_threads = c.loop_threads;
  so.nlgs.profile = c.solve_profile;
  so.warm_start = c.warm_start;
  so.nlgs.skip_zero = c.skip_zero;
  so.nlgs.anderson = c.anderson;
  so.strict_alert = c.strict_alert;
  so.residual_check_every = c.residual_check_every;
  so.residual_flag = c.residual_flag;
  so.residual_limit = c.residual_limit;
  so.projection.enabled = c.projection;
  so.projection.slop = c.projection_slop;
  so.projection.share = c.projection_share;
  so.failure_dump = (out / "refused_step_problem.txt").string();  // a refused step's problem
  return so;
}

// The columns of steps.csv: the POSTPRO series (issue #11, docs/output.md) come after the
// columns of before.
std::vector<std::string> step_columns() {
  std::vector<std::string> cols = {"step", "time", "contacts", "active", "warm_started", "sweeps", "converged", "mean_dvor",
                                   "quad_dv", "maxm_dv", "quad_dvr", "maxm_dvr", "residual_q", "mean_overlap", "max_overlap",
                                   "rms_speed", "detect_s", "solve_s", "step_s", "kinetic_energy", "contact_dissipation",
                                   "contact_dissipation_step"};
  cols.insert(cols.end(), scenes::network_columns().begin(), scenes::network_columns().end());
  // the threads the step's solve and the loops around it ran on (chosen by measure unless fixed)
  cols.insert(cols.end(), {"solve_threads", "loop_threads"});
  return cols;
}

// steps.csv and the VTK frames (the first one at once).
struct Outputs {
  Outputs(const Registry& reg, const scenes::Scene& s, const Config& c, const std::filesystem::path& out)
      : steps_csv(out / "steps.csv", step_columns()), network(reg, s.grains), threads(c.threads) {
    if (!c.no_vtk) {
      vtk = std::make_unique<VtkWriter>(out / "vtk");
      vtk->write_frame(reg);
    }
  }
  CsvWriter steps_csv;
  const scenes::NetworkMeter network;
  std::vector<double> row;  // reused: no allocation per row
  std::unique_ptr<VtkWriter> vtk;
  int threads = 1;  // the sums of a row's statistics (the same bits on any number)
};

// One step; the first --dump-unconverged unconverged steps write their problem to problems/.
// Throws at the first step past the overlap budget with --strict-overlap.
StepReport step_once(MoreauJean& mj, Registry& reg, const Config& c, const StepperOptions& so, const std::filesystem::path& out,
                     scenes::StepWatch& watch, int& dumped) {
  StepReport r;
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
  if (c.strict_overlap && watch.over_limit_steps > 0) scenes::stop_over_budget(reg, mj, out, r, watch, {{"solver", c.solver}});
  return r;
}

// The sums and firsts over the steps, for the summary.
struct Totals {
  std::int64_t mixes = 0, mix_returns = 0;
  std::int64_t unconverged = 0, capped = 0, first_contact = -1, first_active = -1;
  double sum_sweeps = 0.0, max_overlap = 0.0, solve_s = 0.0, detect_s = 0.0, prepare_s = 0.0, end_s = 0.0;
  double contact_dissipation = 0.0;  // since the first step (J/m)
  std::vector<double> step_seconds;

  void add(const StepReport& r, std::int64_t n, bool newton, int max_sweeps) {
    sum_sweeps += r.sweeps;
    mixes += r.mixes;
    mix_returns += r.mix_returns;
    max_overlap = std::max(max_overlap, r.max_overlap);
    solve_s += r.solve_seconds;
    detect_s += r.detect_seconds;
    prepare_s += r.prepare_seconds;
    end_s += r.end_seconds;
    step_seconds.push_back(r.step_seconds);
    if (!r.converged) ++unconverged;
    if (!newton && !r.converged && r.sweeps >= max_sweeps) ++capped;
    if (first_contact < 0 && r.contacts > 0) first_contact = n;
    if (first_active < 0 && r.active > 0) first_active = n;
    contact_dissipation += r.contact_dissipation;
  }
};

void write_step_row(Outputs& o, const Registry& reg, const StepReport& r, double rms_speed, double contact_dissipation) {
  o.row = {double(r.step), r.time, double(r.contacts), double(r.active), double(r.warm_started), double(r.sweeps),
           r.converged ? 1.0 : 0.0, r.criteria.mean_dvor, r.criteria.quad_dv, r.criteria.maxm_dv, r.criteria.quad_dvr,
           r.criteria.maxm_dvr, r.residual, r.mean_overlap, r.max_overlap, rms_speed, r.detect_seconds, r.solve_seconds,
           r.step_seconds, kinetic_energy(reg, o.threads), contact_dissipation, r.contact_dissipation};
  scenes::append_network_values(o.network.measure(reg, o.threads), o.row);
  o.row.insert(o.row.end(), {double(r.solve_threads), double(r.loop_threads)});
  o.steps_csv.row(o.row);
}

// The progress line, every --progress-every wall seconds, at rest and at the last step.
class Progress {
 public:
  Progress(const Config& c, Clock::time_point wall0, std::int64_t max_steps)
      : c_(c), wall0_(wall0), max_steps_(max_steps), eta_(std::max(10.0, 2.0 * c.progress_every)) {
    // ETA from the cost per step of the current phase (the free fall is far cheaper than the impacts)
    eta_.observe(0, 0.0);
  }
  void after(const driver::SettleStep& st) {
    const StepReport& r = st.report;
    const std::int64_t n = st.steps;
    const auto now = Clock::now();
    eta_.observe(n, std::chrono::duration<double>(now - wall0_).count());
    const double since = std::chrono::duration<double>(now - last_print_).count();
    if (!(since >= c_.progress_every || st.at_rest || n == max_steps_)) return;
    last_print_ = now;
    const double elapsed = std::chrono::duration<double>(last_print_ - wall0_).count();
    // not a bound: the steps left can cost more than the current ones; without --steps the run
    // also stops earlier, once at rest
    char eta[160];
    std::snprintf(eta, sizeof eta, "ETA %s at %.3g ms/step%s", scenes::format_duration(eta_.eta(max_steps_ - n)).c_str(),
                  1e3 * eta_.seconds_per_step(), c_.steps == 0 ? " to the --max-time limit (sooner at rest)" : "");
    std::printf("step %7lld  t %.4f s  contacts %5zu  sweeps %4d%s  rms speed %.2e m/s  max overlap %.2e m  elapsed %s  %s\n",
                static_cast<long long>(n), r.time, r.contacts, r.sweeps, r.converged ? "" : "!", st.rms_speed, r.max_overlap,
                scenes::format_duration(elapsed).c_str(), eta);
    std::fflush(stdout);
  }

 private:
  const Config& c_;
  Clock::time_point wall0_;
  std::int64_t max_steps_;
  Clock::time_point last_print_ = Clock::now();
  scenes::StepCostEta eta_;
};

// When the stepping stops: at rest (nscd::driver::settle) without --steps, else at the limit.
driver::SettleRule settle_rule(const Config& c, std::int64_t max_steps) {
  driver::SettleRule rule;
  rule.speed = c.equilibrium_speed;
  rule.window = c.equilibrium_window;
  rule.min_time = c.min_time;
  rule.max_steps = max_steps;
  rule.stop_at_rest = c.steps == 0;
  rule.threads = c.threads;
  return rule;
}

// What the summary reports of the final state.
struct FinalState {
  double wall = 0.0;        // s, the whole run
  scenes::Window win;       // the bulk window of the packing fraction
  double phi = 0.0;         // packing fraction
  scenes::ContactNetwork net;
  double settled_ms = 0.0;  // settled cost: median step time over the last 10 % of the steps
  std::string impossible;   // a physically impossible result ("" if none)
};

FinalState measure_final_state(const Registry& reg, const scenes::Scene& s, double dmax, const Totals& t, Clock::time_point wall0) {
  FinalState f;
  f.wall = std::chrono::duration<double>(Clock::now() - wall0).count();
  f.win = scenes::bulk_window(reg, s.grains, s.box_width, dmax);
  f.phi = scenes::packing_fraction(reg, s.grains, f.win);
  f.net = scenes::contact_network(reg, s.grains);
  const std::vector<double>& step_seconds = t.step_seconds;
  std::vector<double> tail(step_seconds.end() - static_cast<std::ptrdiff_t>(std::max<std::size_t>(1, step_seconds.size() / 10)), step_seconds.end());
  std::nth_element(tail.begin(), tail.begin() + static_cast<std::ptrdiff_t>(tail.size() / 2), tail.end());
  f.settled_ms = 1e3 * tail[tail.size() / 2];
  // a physically impossible result is written as such, and the exit status says it
  f.impossible = scenes::implausible(reg, s.grains, s.box_width, 0.0);
  if (f.impossible.empty() && !(f.phi <= 1.0)) f.impossible = "packing fraction " + exact(f.phi) + " > 1 (grains overlap massively)";
  return f;
}

// 4. summary.txt, written whole at the end (atomic_write), 17 significant digits.
void write_summary(const Config& c, const scenes::Scene& s, const driver::SettleResult& settled, const Totals& t,
                   const FinalState& f, const scenes::StepWatch& watch, const std::filesystem::path& out) {
  const Registry& reg = s.reg;
  const StepReport& r = settled.last;
  const std::int64_t done = settled.steps;
  driver::Summary summary;
  std::ostream& sum = summary.stream();
  sum << "result = " << (f.impossible.empty() ? "valid" : "impossible: " + f.impossible) << "\n"
      << "scene = " << c.scene << "\n"
      << "sample_file = " << (c.sample_file.empty() ? "none" : c.sample_file) << "\n"
      << "solver = " << c.solver << "\n"
      << "order = " << c.order << "\n"
      << "relaxation = " << c.relaxation << "\n"
      << "anderson = " << c.anderson << "\n"
      << "grains = " << s.grains.size() << "\n"
      << "seed = " << c.seed << "\n"
      << "dt = " << c.dt << "\n"
      << "mu = " << c.mu << "\n"
      << "density = " << c.density << "\n"
      << "pitch_factor = " << c.pitch_factor << "\n"
      << "steps = " << done << "\n"
      << "simulated_time = " << reg.time << "\n"
      << "equilibrium_reached = " << (settled.at_rest ? 1 : 0) << "\n"
      << "wall_time = " << f.wall << "\n"
      << "solve_time = " << t.solve_s << "\n"
      << "detect_time = " << t.detect_s << "\n"
      << "prepare_time = " << t.prepare_s << "\n"
      << "end_time = " << t.end_s << "\n"
      << "ms_per_step = " << 1e3 * f.wall / double(done) << "\n"
      << "settled_ms_per_step = " << f.settled_ms << "\n"
      << "mean_sweeps = " << t.sum_sweeps / double(done) << "\n"
      << "mean_iterations = " << t.sum_sweeps / double(done) << "\n"
      << "unconverged_steps = " << t.unconverged << "\n"
      << "capped_steps = " << t.capped << "\n"
      << "anderson_mixes = " << t.mixes << "\n"
      << "anderson_returns = " << t.mix_returns << "\n"
      << "first_contact_step = " << t.first_contact << "\n"
      << "first_active_contact_step = " << t.first_active << "\n"
      << "final_contacts = " << r.contacts << "\n"
      << "final_sweeps = " << r.sweeps << "\n"
      << "packing_fraction = " << f.phi << "\n"
      << "packing_window = " << f.win.xmin << " " << f.win.ymin << " " << f.win.xmax << " " << f.win.ymax << "\n"
      << "coordination_number = " << f.net.coordination_number << "\n"
      << "double_contact_share = " << f.net.double_contact_share << "\n"
      << "mean_overlap = " << r.mean_overlap << "\n"
      << "max_overlap = " << t.max_overlap << "\n"
      << "final_max_overlap = " << r.max_overlap << "\n"
      << "rms_grain_speed = " << scenes::rms_speed(reg, s.grains) << "\n"
      << watch.summary();
  summary.write(out / "summary.txt");
}

// The final state (none of an impossible result), the closing words and the exit status.
int finish(const Config& c, const Registry& reg, MoreauJean& mj, const driver::SettleResult& settled, const Totals& t,
           const FinalState& f, const scenes::StepWatch& watch, const std::filesystem::path& out, bool vtk) {
  if (!f.impossible.empty()) {
    std::fflush(stdout);
    std::fprintf(stderr, "deposit: error: physically impossible result: %s; no final state written (exit 3)\n", f.impossible.c_str());
    return 3;
  }
  save_checkpoint(out / "final_state.nscd", reg, mj.warm_start_memory(), {{"solver", c.solver}});
  const std::int64_t done = settled.steps;
  std::printf("done: %lld steps, %.3f s simulated, wall %.1f s (%.2f ms/step, settled %.2f ms/step), mean sweeps %.1f,\n"
              "      packing fraction %.3f, coordination %.2f, double contacts %.2f, max overlap %.2e m (final %.2e m)%s\n"
              "      outputs: %s/{summary.txt, steps.csv, final_state.nscd%s}\n",
              static_cast<long long>(done), reg.time, f.wall, 1e3 * f.wall / double(done), f.settled_ms, t.sum_sweeps / double(done),
              f.phi, f.net.coordination_number, f.net.double_contact_share, t.max_overlap, settled.last.max_overlap,
              c.steps == 0 && !settled.at_rest ? "\n      WARNING: equilibrium not reached within --max-time" : "",
              out.string().c_str(), vtk ? ", vtk/" : "");
  std::fputs(watch.closing_line().c_str(), stdout);
  std::fputs(watch.solve_profile_table().c_str(), stdout);
  return 0;
}

}  // namespace

int run(const Config& c) {
  const auto wall0 = Clock::now();
  check(c);  // a Config built by hand gets the command line's checks
  claim_output(c);
  // 1. Scene.
  double dmax = 0.0;
  scenes::Scene s = build_scene(c, dmax);
  Registry& reg = s.reg;

  // 2. Time stepping, law and solver.
  set_stepping(reg, c);
  const std::filesystem::path out(c.output);
  const StepperOptions so = stepper_options(c, out);
  MoreauJean mj(reg, so);
  scenes::StepWatch watch;
  watch.overlap_limit = scenes::overlap_budget(c.overlap_limit, scenes::smallest_grain_size(reg, s.grains));
  Outputs o(reg, s, c, out);
  const bool newton = so.solver == SolverKind::NEWTON_AC;
  if (const std::string w = driver::threads_warning("deposit", c.threads); !w.empty()) std::fprintf(stderr, "%s\n", w.c_str());
  std::printf("deposit: scene %s, %zu grains, %zu bodies, dt %g s, theta %g, %s %s tol %g, output %s\n", c.scene.c_str(),
              s.grains.size(), reg.bodies.size(), c.dt, c.theta, c.solver.c_str(), newton ? "" : c.policy.c_str(),
              newton ? c.newton_tol : c.tol, out.string().c_str());

  // 3. Steps, until equilibrium (nscd::driver::settle) or the limit.
  driver::input_accepted();  // options and scene accepted: from here, errors are the run's (exit 1)
  const std::int64_t max_steps = c.steps > 0 ? c.steps : static_cast<std::int64_t>(std::ceil(c.max_time / c.dt - 1e-9));
  Totals t;
  Progress progress(c, wall0, max_steps);
  t.step_seconds.reserve(static_cast<std::size_t>(max_steps));
  int dumped = 0;
  auto one_step = [&] { return step_once(mj, reg, c, so, out, watch, dumped); };
  auto after_step = [&](const driver::SettleStep& st) {
    t.add(st.report, st.steps, newton, c.max_sweeps);
    write_step_row(o, reg, st.report, st.rms_speed, t.contact_dissipation);
    if (o.vtk && c.vtk_every > 0 && st.steps % c.vtk_every == 0) o.vtk->write_frame(reg);
    progress.after(st);
  };
  const driver::SettleResult settled = driver::settle(reg, s.grains, settle_rule(c, max_steps), one_step, after_step);
  o.steps_csv.flush();
  if (o.vtk && (c.vtk_every == 0 || settled.steps % c.vtk_every != 0)) o.vtk->write_frame(reg);

  // 4. Summary and final state.
  const FinalState f = measure_final_state(reg, s, dmax, t, wall0);
  write_summary(c, s, settled, t, f, watch, out);
  return finish(c, reg, mj, settled, t, f, watch, out, o.vtk != nullptr);
}

}  // namespace deposit
