// examples/ballast/ballast_study.cpp — the run, step by step:
//   1. the sample: load it (--sample, --resume) or prepare it: grains deposited on the
//      sublayer until rest, the sleeper placed and settled; saved as sample.nscd
//   2. the load: F(t) on the sleeper from t0 (the start of the cycles), with a ramp-in
//   3. the cycles: steps.csv (thinned), cycles.csv, VTK frames, a progress line with ETA,
//      checkpoints every K cycles (checkpoint.nscd, atomic)
//   4. summary.txt and the final checkpoint
#include "ballast_study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/io/csv.hpp"
#include "nscd/io/vtk_writer.hpp"
#include "nscd/shared/analysis.hpp"
#include "nscd/shared/ballast.hpp"
#include "nscd/shared/progress.hpp"
#include "nscd/shared/step_watch.hpp"
#include "nscd/solvers/moreau_jean.hpp"

namespace fs = std::filesystem;
using namespace nscd;
using nscd::scenes::format_duration;
using nscd::scenes::mean_speed;
using nscd::scenes::rms_speed;
using Clock = std::chrono::steady_clock;

namespace ballast {
namespace {

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string hex(double v) {
  std::ostringstream s;
  s << std::hexfloat << v;
  return s.str();
}
double unhex(const std::string& s) { return std::strtod(s.c_str(), nullptr); }

scenes::BallastOptions sample_options(const Config& c) {
  scenes::BallastOptions o;
  o.seed = c.seed;
  o.box_width = c.box_width;
  o.grading_fraction = c.grading_fraction;
  o.mu = c.mu;
  o.pads = c.pads;
  o.k = c.k;
  o.nu = c.nu;
  o.spring_length = c.spring_length;
  o.sleeper_width = c.sleeper_width;
  o.bars = c.bars;
  return o;
}

StepperOptions stepper_options(const Config& c) {
  StepperOptions s;
  s.solver = parse_solver_kind(c.solver, "--solver");
  s.newton.tol = c.newton_tol;
  s.newton.max_iterations = c.newton_max_iterations;
  s.newton.presweeps = c.newton_presweeps;
  s.nlgs.policy = parse_convergence_policy(c.policy);
  s.nlgs.tol = c.tol;
  s.nlgs.check_every = c.check_every;
  s.nlgs.min_sweeps = c.min_sweeps;
  s.nlgs.max_sweeps = c.max_sweeps;
  s.strict_alert = c.strict_alert;
  s.residual_check_every = c.residual_check_every;
  s.residual_flag = c.residual_flag;
  s.residual_limit = c.residual_limit;
  s.failure_dump = (fs::path(c.output) / "refused_step_problem.txt").string();  // a refused step's problem
  return s;
}

// Steps until the given bodies are at rest (rms speed < v for 0.05 s, after 0.05 s) or t_max.
void settle(Registry& reg, MoreauJean& mj, const std::vector<BodyId>& bodies, double v, double t_max, const char* what,
            double progress_every, scenes::StepWatch& watch) {
  const double t_start = reg.time;
  const auto window = static_cast<std::int64_t>(std::ceil(0.05 / reg.params.dt));
  std::int64_t calm = 0;
  auto last = Clock::now();
  const auto t0 = Clock::now();
  while (reg.time - t_start < t_max) {
    const StepReport r = mj.step();
    watch.observe(reg, r, mj.options());
    const double s = rms_speed(reg, bodies);
    calm = (reg.time - t_start > 0.05 && s < v) ? calm + 1 : 0;
    if (since(last) >= progress_every) {
      last = Clock::now();
      const double frac = (reg.time - t_start) / t_max;
      std::printf("  %s: t %.3f s  contacts %zu  sweeps %d  rms speed %.2e m/s  elapsed %s  ETA %s (at most)\n", what,
                  reg.time - t_start, r.contacts, r.sweeps, s, format_duration(since(t0)).c_str(), format_duration(since(t0) * (1 - frac) / frac).c_str());
      std::fflush(stdout);
    }
    if (calm >= window) {
      std::printf("  %s: at rest after %.3f s simulated (%s)\n", what, reg.time - t_start, format_duration(since(t0)).c_str());
      return;
    }
  }
  std::printf("  %s: WARNING not at rest after %.3f s simulated (rms speed above %g m/s); continuing\n", what, t_max, v);
}

// Keeps the header and the complete rows whose first column is <= last (a resumed run rewrites
// the rest). A run killed while writing can leave its last row cut short, with no end of line:
// that row is dropped whatever it reads as ("42" cut from step 4248 would read as step 42 and
// stay otherwise). The file is rewritten through a temporary file renamed over it, so a kill
// during the truncation leaves the old file.
void truncate_csv(const fs::path& file, double last) {
  std::ifstream in(file);
  if (!in) return;
  std::vector<std::string> keep;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (in.eof()) break;  // no '\n' after it: a row cut short
    char* end = nullptr;
    const double first = std::strtod(line.c_str(), &end);
    if (header || (end != line.c_str() && *end == ',' && first <= last)) keep.push_back(line);
    header = false;
  }
  in.close();
  const fs::path tmp = file.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    for (const auto& l : keep) out << l << '\n';
    if (!out.flush()) throw Error("cannot write " + tmp.string());
  }
  fs::rename(tmp, file);
}

// The state of a run that a checkpoint must carry besides the registry.
struct RunState {
  int cycles_done = 0;
  double t0 = 0.0, y_ref = 0.0, x_ref = 0.0;
  std::int64_t sweeps = 0, steps = 0, unconverged = 0;
  double max_overlap = 0.0, sum_mean_overlap = 0.0;
  double last_settlement_min = 0.0, last_settlement_max = 0.0;
};

std::map<std::string, std::string> state_map(const Config& c, const RunState& s) {
  std::map<std::string, std::string> m = to_map(c);
  m["state.cycles_done"] = std::to_string(s.cycles_done);
  m["state.t0"] = hex(s.t0);
  m["state.y_ref"] = hex(s.y_ref);
  m["state.x_ref"] = hex(s.x_ref);
  m["state.sweeps"] = std::to_string(s.sweeps);
  m["state.steps"] = std::to_string(s.steps);
  m["state.unconverged"] = std::to_string(s.unconverged);
  m["state.max_overlap"] = hex(s.max_overlap);
  m["state.sum_mean_overlap"] = hex(s.sum_mean_overlap);
  m["state.settlement_min"] = hex(s.last_settlement_min);
  m["state.settlement_max"] = hex(s.last_settlement_max);
  return m;
}

RunState state_from(const std::map<std::string, std::string>& m) {
  auto get = [&](const char* k) {
    const auto it = m.find(k);
    if (it == m.end()) throw Error(std::string("checkpoint has no '") + k + "': not a ballast run checkpoint");
    return it->second;
  };
  RunState s;
  s.cycles_done = std::stoi(get("state.cycles_done"));
  s.t0 = unhex(get("state.t0"));
  s.y_ref = unhex(get("state.y_ref"));
  s.x_ref = unhex(get("state.x_ref"));
  s.sweeps = std::stoll(get("state.sweeps"));
  s.steps = std::stoll(get("state.steps"));
  s.unconverged = std::stoll(get("state.unconverged"));
  s.max_overlap = unhex(get("state.max_overlap"));
  s.sum_mean_overlap = unhex(get("state.sum_mean_overlap"));
  s.last_settlement_min = unhex(get("state.settlement_min"));
  s.last_settlement_max = unhex(get("state.settlement_max"));
  return s;
}

// 2. The sleeper load, from t0: F = A + B cos(2π f (t − t0) − φ) along (sin β, −cos β)·(−1).
void impose_load(Registry& reg, BodyId sleeper, const Config& c, double t0) {
  const double beta = c.inclination * kPi / 180.0, ramp = c.ramp_cycles / c.frequency;
  impose_force(reg, sleeper, Dof::Y,
               TimeFunction::cosine(c.load_mean * std::cos(beta), c.load_amplitude * std::cos(beta), c.frequency, c.phase, ramp, t0));
  if (beta != 0.0)
    impose_force(reg, sleeper, Dof::X,
                 TimeFunction::cosine(-c.load_mean * std::sin(beta), -c.load_amplitude * std::sin(beta), c.frequency, c.phase, ramp, t0));
}

}  // namespace

int run(Config c) {
  const auto wall0 = Clock::now();
  const Config cli = c;
  scenes::BallastScene s;
  RunState st;
  std::vector<MoreauJean::WarmStartEntry> warm;
  bool resumed = false, cycles_started = false;

  // 1. The sample.
  if (!c.resume.empty()) {
    const fs::path cp_file = fs::path(c.resume) / "checkpoint.nscd";
    Checkpoint cp = load_checkpoint(cp_file);
    from_map(cp.extra, c);
    c.cycles = cli.cycles;  // the command line may extend the run
    c.stop_after_cycles = cli.stop_after_cycles;
    c.progress_every = cli.progress_every;
    c.output = c.resume;
    st = state_from(cp.extra);
    warm = std::move(cp.warm_start);
    s = scenes::recognise_ballast(std::move(cp.reg));
    resumed = cycles_started = true;
    std::printf("ballast: resuming %s at cycle %d (t = %.4f s)\n", c.resume.c_str(), st.cycles_done, s.scene.reg.time);
  } else if (!c.sample.empty()) {
    Checkpoint cp = load_checkpoint(c.sample);
    if (const auto it = cp.extra.find("seed"); it != cp.extra.end()) c.seed = std::stoull(it->second);
    warm = std::move(cp.warm_start);
    s = scenes::recognise_ballast(std::move(cp.reg));
    if (!s.sleeper.valid()) throw Error("sample '" + c.sample + "' has no sleeper: not a prepared ballast sample");
    std::printf("ballast: loaded the prepared sample %s (%zu grains, %zu pads)\n", c.sample.c_str(), s.scene.grains.size(), s.pads.size());
  } else {
    s = scenes::ballast_sample(sample_options(c));
    std::printf("ballast: preparing the sample (seed %llu): %zu-grain deposit on %d pads, then the sleeper\n",
                static_cast<unsigned long long>(c.seed), s.scene.grains.size(), c.pads);
  }
  Registry& reg = s.scene.reg;
  // the sample's own stiffness (before any --k-factor) and seed, for the summary
  const double k_sample = reg.links.empty() ? c.k : reg.links.law[0].k / (cycles_started ? c.k_factor : 1.0);
  reg.params.dt = c.dt;
  reg.params.theta = c.theta;
  reg.params.alert = c.alert;
  validate(reg.params);
  MoreauJean mj(reg, stepper_options(c));
  mj.set_warm_start_memory(warm);
  scenes::StepWatch watch;  // counts of this process's steps (not carried by checkpoints)
  const fs::path out(c.output);
  fs::create_directories(out);

  if (c.resume.empty() && c.sample.empty()) {
    settle(reg, mj, s.scene.grains, c.equilibrium_speed, c.prep_max_time, "deposit", c.progress_every, watch);
    scenes::place_sleeper(s, sample_options(c));
    std::vector<BodyId> moving = s.scene.grains;
    moving.push_back(s.sleeper);
    settle(reg, mj, moving, c.equilibrium_speed, c.settle_time, "sleeper", c.progress_every, watch);
    save_checkpoint(out / "sample.nscd", reg, mj.warm_start_memory(), {{"kind", "ballast-sample"}, {"seed", std::to_string(c.seed)}});
    std::printf("  sample saved: %s (reuse it with --sample)\n", (out / "sample.nscd").string().c_str());
  }
  const double prep_wall = since(wall0);
  if (c.prepare_only) return 0;

  // 2. The load and the sublayer stiffness of this run.
  if (c.guided_sleeper && !resumed) {
    fix_dof(reg, s.sleeper, Dof::X);
    fix_dof(reg, s.sleeper, Dof::Rot);
  }
  if (!cycles_started) {
    if (c.k_factor != 1.0) scenes::scale_sublayer_stiffness(s, c.k_factor);
    st.t0 = reg.time;
    st.y_ref = reg.bodies.y[s.sleeper.index()];
    st.x_ref = reg.bodies.x[s.sleeper.index()];
    impose_load(reg, s.sleeper, c, st.t0);
  }
  const int n_cycle = static_cast<int>(std::lround(1.0 / (c.frequency * c.dt)));

  // 3. Outputs (a resumed run drops what was written after its checkpoint).
  if (resumed) {
    truncate_csv(out / "cycles.csv", st.cycles_done);
    truncate_csv(out / "steps.csv", static_cast<double>(reg.step));
  }
  CsvWriter cycles_csv(out / "cycles.csv",
                       {"cycle", "time", "settlement_min_load", "settlement_max_load", "lateral_displacement", "mean_grain_speed",
                        "mean_overlap", "max_overlap", "mean_sweeps", "unconverged_steps", "wall_time"},
                       resumed, 1);
  CsvWriter steps_csv(out / "steps.csv",
                      {"step", "time", "load", "settlement", "contacts", "active", "sweeps", "converged", "quad_dv", "maxm_dv",
                       "mean_overlap", "max_overlap", "rms_grain_speed", "detect_s", "solve_s"},
                      resumed, 100);
  std::unique_ptr<VtkWriter> vtk;
  if (c.vtk_every > 0) {
    vtk = std::make_unique<VtkWriter>(out / "vtk");
    if (resumed) vtk->resume(reg.time);  // frames up to the checkpoint stay listed
    else vtk->write_frame(reg);
  }
  const int last_cycle = c.stop_after_cycles > 0 ? std::min(c.cycles, st.cycles_done + c.stop_after_cycles) : c.cycles;
  const bool newton = c.solver == "NEWTON_AC";
  std::printf("ballast: %d cycles of %d steps (f = %g Hz, dt = %g s), k = %g N/m x %g, %s %s tol %g, output %s\n", c.cycles, n_cycle,
              c.frequency, c.dt, c.k, c.k_factor, c.solver.c_str(), newton ? "" : c.policy.c_str(),
              newton ? c.newton_tol : c.tol, out.string().c_str());
  const auto cycles_wall0 = Clock::now();
  const int first_cycle = st.cycles_done;
  auto last_print = Clock::now();
  const BodyId sl = s.sleeper;
  double s_max = 0.0, s_min = 0.0;

  for (int cycle = st.cycles_done; cycle < last_cycle; ++cycle) {
    const auto cw = Clock::now();
    double speed_sum = 0.0, overlap_sum = 0.0, overlap_max = 0.0;
    std::int64_t sweeps = 0, unconverged = 0;
    for (int j = 1; j <= n_cycle; ++j) {
      const StepReport r = mj.step();
      watch.observe(reg, r, mj.options());
      const double settlement = st.y_ref - reg.bodies.y[sl.index()];
      const double v = mean_speed(reg, s.scene.grains);
      speed_sum += v;
      overlap_sum += r.mean_overlap;
      overlap_max = std::max(overlap_max, r.max_overlap);
      sweeps += r.sweeps;
      unconverged += r.converged ? 0 : 1;
      if (j == n_cycle / 2) s_max = settlement;  // F = A + B: the largest load of the cycle
      if (j == n_cycle) s_min = settlement;      // F = A − B: the smallest
      if (reg.step % c.steps_every == 0) {
        const double load = external_force(reg, sl, reg.time).fy + reg.bodies.mass[sl.index()] * (-reg.params.gravity.y);
        steps_csv.row({double(reg.step), reg.time, load, settlement, double(r.contacts), double(r.active), double(r.sweeps),
                       r.converged ? 1.0 : 0.0, r.criteria.quad_dv, r.criteria.maxm_dv, r.mean_overlap, r.max_overlap,
                       rms_speed(reg, s.scene.grains), r.detect_seconds, r.solve_seconds});
      }
      if (vtk && reg.step % c.vtk_every == 0) vtk->write_frame(reg);
    }
    st.cycles_done = cycle + 1;
    st.sweeps += sweeps;
    st.steps += n_cycle;
    st.unconverged += unconverged;
    st.max_overlap = std::max(st.max_overlap, overlap_max);
    st.sum_mean_overlap += overlap_sum;
    st.last_settlement_min = s_min;
    st.last_settlement_max = s_max;
    cycles_csv.row({double(st.cycles_done), reg.time, s_min, s_max, reg.bodies.x[sl.index()] - st.x_ref, speed_sum / n_cycle,
                    overlap_sum / n_cycle, overlap_max, double(sweeps) / n_cycle, double(unconverged), since(cw)});
    if (c.checkpoint_every > 0 && st.cycles_done % c.checkpoint_every == 0) {
      steps_csv.flush();
      save_checkpoint(out / "checkpoint.nscd", reg, mj.warm_start_memory(), state_map(c, st));
    }
    if (since(last_print) >= c.progress_every || st.cycles_done == last_cycle) {
      last_print = Clock::now();
      const double per = since(cycles_wall0) / double(st.cycles_done - first_cycle);
      std::printf("cycle %5d/%d  settlement %.4f mm (max load %.4f mm)  sweeps/step %.1f  max overlap %.2e m  %.2f s/cycle  ETA %s\n",
                  st.cycles_done, c.cycles, 1e3 * s_min, 1e3 * s_max, double(sweeps) / n_cycle, overlap_max, per,
                  format_duration(per * (last_cycle - st.cycles_done)).c_str());
      std::fflush(stdout);
    }
  }
  steps_csv.flush();

  // 4. Summary and final checkpoint.
  save_checkpoint(out / "checkpoint.nscd", reg, mj.warm_start_memory(), state_map(c, st));
  if (vtk && st.cycles_done > first_cycle && reg.step % c.vtk_every != 0) vtk->write_frame(reg);
  const int run_cycles = st.cycles_done - first_cycle;
  const double cycles_wall = since(cycles_wall0);
  std::ofstream sum(out / "summary.txt");
  sum.precision(10);
  sum << "solver = " << c.solver << "\n"
      << "cycles = " << st.cycles_done << "\n"
      << "final_settlement = " << st.last_settlement_min << "\n"
      << "final_settlement_max_load = " << st.last_settlement_max << "\n"
      << "mean_sweeps = " << (st.steps ? double(st.sweeps) / double(st.steps) : 0.0) << "\n"
      << "max_overlap = " << st.max_overlap << "\n"
      << "mean_overlap = " << (st.steps ? st.sum_mean_overlap / double(st.steps) : 0.0) << "\n"
      << "unconverged_steps = " << st.unconverged << "\n"
      << "steps_per_cycle = " << n_cycle << "\n"
      << "grains = " << s.scene.grains.size() << "\n"
      << "pads = " << s.pads.size() << "\n"
      << "k = " << k_sample << "\n"
      << "k_factor = " << c.k_factor << "\n"
      << "seed = " << c.seed << "\n"
      << "wall_time = " << since(wall0) << "\n"
      << "preparation_wall_time = " << prep_wall << "\n"
      << "time_per_cycle = " << (run_cycles > 0 ? cycles_wall / run_cycles : 0.0) << "\n"
      << watch.summary();
  if (!sum) throw Error("cannot write " + (out / "summary.txt").string());
  std::printf("done: %d cycles, settlement %.4f mm at the smallest load (%.4f mm at the largest), %.2f s/cycle, mean sweeps %.1f,\n"
              "      max overlap %.2e m; outputs in %s (summary.txt, cycles.csv, steps.csv, checkpoint.nscd%s)\n",
              st.cycles_done, 1e3 * st.last_settlement_min, 1e3 * st.last_settlement_max,
              run_cycles > 0 ? cycles_wall / run_cycles : 0.0, st.steps ? double(st.sweeps) / double(st.steps) : 0.0,
              st.max_overlap, out.string().c_str(), vtk ? ", vtk/" : "");
  std::fputs(watch.closing_line().c_str(), stdout);
  return 0;
}

}  // namespace ballast
