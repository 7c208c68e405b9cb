// examples/ballast/ballast_study.cpp — the run, step by step:
//   1. the sample: load it (--sample, --resume) or prepare it: grains deposited on the
//      sublayer until rest, the sleeper placed and settled; saved as sample.nscd
//   2. the load: F(t) on the sleeper from t0 (the start of the cycles), with a ramp-in
//   3. the cycles: steps.csv (thinned), cycles.csv, VTK frames, a progress line with ETA,
//      checkpoints every K cycles (checkpoint.nscd, atomic)
//   4. summary.txt and the final checkpoint
// Steps 0 (the output folder) and 1 are in ballast_sample.cpp; what a checkpoint carries of the
// run, and what a resumed run takes up again, in run_state.cpp.
#include "ballast_study.hpp"
#include "ballast_sample.hpp"
#include "run_state.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/io/csv.hpp"
#include "nscd/io/text_reader.hpp"
#include "nscd/io/vtk_writer.hpp"
#include "nscd/shared/analysis.hpp"
#include "nscd/shared/ballast.hpp"
#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/plan_table.hpp"
#include "nscd/shared/driver/run_main.hpp"
#include "nscd/shared/driver/summary.hpp"
#include "nscd/shared/driver_checks.hpp"
#include "nscd/shared/overlap_growth.hpp"
#include "nscd/shared/postpro.hpp"
#include "nscd/shared/progress.hpp"
#include "nscd/shared/step_watch.hpp"
#include "nscd/solvers/moreau_jean.hpp"

namespace fs = std::filesystem;
using namespace nscd;
using nscd::scenes::format_duration;
using nscd::scenes::mean_speed;
using nscd::scenes::rms_speed;

namespace ballast {
namespace {

// SIGTERM during the cycles (a batch scheduler's notice before it kills the job, GNU parallel
// stopping its jobs): the run ends at the end of the current cycle with a checkpoint. The
// handler is installed for the cycles only (the preparation has no checkpoint: it dies as
// before) and the previous one put back after them.
volatile std::sig_atomic_t g_terminate = 0;
void on_sigterm(int) { g_terminate = 1; }
class SigtermCheckpoint {
 public:
  SigtermCheckpoint() {
    g_terminate = 0;
    struct sigaction sa {};
    sa.sa_handler = on_sigterm;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGTERM, &sa, &old_);
  }
  ~SigtermCheckpoint() { sigaction(SIGTERM, &old_, nullptr); }
  SigtermCheckpoint(const SigtermCheckpoint&) = delete;
  SigtermCheckpoint& operator=(const SigtermCheckpoint&) = delete;
  bool requested() const { return g_terminate != 0; }

 private:
  struct sigaction old_ {};
};

StepperOptions stepper_options(const Config& c) {
  StepperOptions s;
  s.solver = parse_solver_kind(c.solver, "--solver");
  s.newton.tol = c.newton_tol;
  s.newton.max_iterations = c.newton_max_iterations;
  s.newton.presweeps = c.newton_presweeps;
  s.newton.presweep_tol = c.newton_presweep_tol;
  s.nlgs.policy = parse_convergence_policy(c.policy);
  s.nlgs.tol = c.tol;
  s.nlgs.check_every = c.check_every;
  s.nlgs.min_sweeps = c.min_sweeps;
  s.nlgs.max_sweeps = c.max_sweeps;
  s.nlgs.relaxation = c.relaxation;
  s.nlgs.anderson = c.anderson;
  s.nlgs.order = parse_sweep_order(c.order);
  s.nlgs.threads = c.threads;
  s.threads = c.threads;  // the rest of the step's too
  s.solve_threads = c.solve_threads;
  s.loop_threads = c.loop_threads;
  s.nlgs.profile = c.solve_profile;
  s.strict_alert = c.strict_alert;
  s.residual_check_every = c.residual_check_every;
  s.residual_flag = c.residual_flag;
  s.residual_limit = c.residual_limit;
  s.projection.enabled = c.projection;
  s.projection.slop = c.projection_slop;
  s.projection.share = c.projection_share;
  s.failure_dump = (fs::path(c.output) / "refused_step_problem.txt").string();  // a refused step's problem
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

// 2. The load and the sublayer stiffness of this run (a resumed run has them from its checkpoint).
void apply_load(Run& r) {
  const Config& c = r.c;
  Registry& reg = r.s.scene.reg;
  if (c.guided_sleeper && !r.resumed) {
    fix_dof(reg, r.s.sleeper, Dof::X);
    fix_dof(reg, r.s.sleeper, Dof::Rot);
  }
  if (!r.cycles_started) {
    if (c.k_factor != 1.0) scenes::scale_sublayer_stiffness(r.s, c.k_factor);
    r.st.t0 = reg.time;
    r.st.y_ref = reg.bodies.y[r.s.sleeper.index()];
    r.st.x_ref = reg.bodies.x[r.s.sleeper.index()];
    impose_load(reg, r.s.sleeper, c, r.st.t0);
  }
}

// The columns of cycles.csv and steps.csv: the POSTPRO series (issue #11, docs/output.md) come
// after the columns of before, and NEWTON_AC's NLGS presweeps (which `sweeps`, the Newton
// iterations, leaves out) last.
std::vector<std::string> cycle_columns() {
  std::vector<std::string> cols = {"cycle", "time", "settlement_min_load", "settlement_max_load", "lateral_displacement",
                                   "mean_grain_speed", "mean_overlap", "max_overlap", "mean_sweeps", "unconverged_steps",
                                   "wall_time", "total_overlap", "kinetic_energy", "contact_dissipation",
                                   "contact_dissipation_cycle", "damper_dissipation", "damper_dissipation_cycle"};
  cols.insert(cols.end(), scenes::network_columns().begin(), scenes::network_columns().end());
  cols.push_back("mean_presweeps");
  return cols;
}
std::vector<std::string> step_columns() {
  std::vector<std::string> cols = {"step", "time", "load", "settlement", "contacts", "active", "sweeps", "converged",
                                   "quad_dv", "maxm_dv", "mean_overlap", "max_overlap", "rms_grain_speed", "detect_s",
                                   "solve_s", "kinetic_energy", "contact_dissipation", "damper_dissipation"};
  cols.insert(cols.end(), scenes::network_columns().begin(), scenes::network_columns().end());
  // the step's wall time, and the threads its solve and the loops around it ran on (chosen by
  // measure unless fixed: StepperOptions::solve_threads, loop_threads)
  cols.insert(cols.end(), {"presweeps", "step_s", "solve_threads", "loop_threads"});
  return cols;
}

// 3. The outputs of the cycles (a resumed run has dropped what was written after its checkpoint).
struct Outputs {
  Outputs(const Run& r, const fs::path& out, const std::vector<std::string>& cycle_cols, const std::vector<std::string>& step_cols)
      : cycles_csv(out / "cycles.csv", cycle_cols, r.resumed, 1),
        steps_csv(out / "steps.csv", step_cols, r.resumed, 100),
        network(r.s.scene.reg, r.s.scene.grains) {
    if (r.c.vtk_every > 0) {
      vtk = std::make_unique<VtkWriter>(out / "vtk");
      if (r.resumed) vtk->resume(r.s.scene.reg.time);  // frames up to the checkpoint stay listed
      else vtk->write_frame(r.s.scene.reg);
    }
  }
  CsvWriter cycles_csv;
  CsvWriter steps_csv;
  const scenes::NetworkMeter network;
  std::unique_ptr<VtkWriter> vtk;
  std::vector<double> row;  // reused: no allocation per row
};

std::unique_ptr<Outputs> open_outputs(const Run& r, const fs::path& out) {
  const std::vector<std::string> cycle_cols = cycle_columns(), step_cols = step_columns();
  if (r.resumed) {
    truncate_csv(out / "cycles.csv", r.st.cycles_done, cycle_cols);
    truncate_csv(out / "steps.csv", static_cast<double>(r.s.scene.reg.step), step_cols);
  }
  return std::make_unique<Outputs>(r, out, cycle_cols, step_cols);
}

void print_cycles_header(const Config& c, int n_cycle, const fs::path& out) {
  const bool newton = c.solver == "NEWTON_AC";
  // the sweep's order and relaxation are named when they are not the paper's (fixed, 1)
  std::string sweep;
  if (!newton && c.order != "fixed") sweep += ", order " + c.order;
  if (!newton && c.relaxation != 1.0) sweep += ", relaxation " + exact(c.relaxation);
  if (!newton && c.anderson != 0) sweep += ", Anderson mixing depth " + std::to_string(c.anderson);
  if (const std::string w = driver::threads_warning("ballast", c.threads); !w.empty()) std::fprintf(stderr, "%s\n", w.c_str());
  std::printf("ballast: %d cycles of %d steps (f = %g Hz, dt = %g s), k = %g N/m x %g, %s %s tol %g%s, output %s\n", c.cycles, n_cycle,
              c.frequency, c.dt, c.k, c.k_factor, c.solver.c_str(), newton ? "" : c.policy.c_str(),
              newton ? c.newton_tol : c.tol, sweep.c_str(), out.string().c_str());
}

// The sums over the steps of one cycle.
struct CycleSums {
  double speed = 0.0, overlap = 0.0, overlap_max = 0.0, total = 0.0, contact_diss = 0.0, damper_diss = 0.0;
  std::int64_t sweeps = 0, unconverged = 0, max_sweeps = 0, presweeps = 0;
};

void write_step_row(Run& r, Outputs& o, const StepReport& rep, double settlement) {
  const Registry& reg = r.s.scene.reg;
  const BodyId sl = r.s.sleeper;
  const double load = external_force(reg, sl, reg.time).fy + reg.bodies.mass[sl.index()] * (-reg.params.gravity.y);
  o.row = {double(reg.step), reg.time, load, settlement, double(rep.contacts), double(rep.active), double(rep.sweeps),
           rep.converged ? 1.0 : 0.0, rep.criteria.quad_dv, rep.criteria.maxm_dv, rep.mean_overlap, rep.max_overlap,
           rms_speed(reg, r.s.scene.grains, r.c.threads), rep.detect_seconds, rep.solve_seconds,
           kinetic_energy(reg, r.c.threads), r.st.contact_dissipation, r.st.damper_dissipation};
  scenes::append_network_values(o.network.measure(reg, r.c.threads), o.row);
  o.row.insert(o.row.end(), {double(rep.presweeps), rep.step_seconds, double(rep.solve_threads), double(rep.loop_threads)});
  o.steps_csv.row(o.row);
}

// The steps of one cycle: their sums, the settlements at its largest and smallest load
// (s_max, s_min), the rows of steps.csv and the VTK frames.
CycleSums step_cycle(Run& r, MoreauJean& mj, Outputs& o, scenes::StepWatch& watch, int n_cycle, double& s_min, double& s_max) {
  Registry& reg = r.s.scene.reg;
  CycleSums sum;
  for (int j = 1; j <= n_cycle; ++j) {
    const StepReport rep = mj.step();
    watch.observe(reg, rep, mj.options());
    const double settlement = r.st.y_ref - reg.bodies.y[r.s.sleeper.index()];
    const double v = mean_speed(reg, r.s.scene.grains);
    sum.speed += v;
    sum.overlap += rep.mean_overlap;
    sum.total += rep.total_overlap;
    sum.overlap_max = std::max(sum.overlap_max, rep.max_overlap);
    sum.sweeps += rep.sweeps;
    sum.max_sweeps = std::max<std::int64_t>(sum.max_sweeps, rep.sweeps);
    sum.presweeps += rep.presweeps;
    sum.unconverged += rep.converged ? 0 : 1;
    sum.contact_diss += rep.contact_dissipation;
    sum.damper_diss += rep.damper_dissipation;
    r.st.contact_dissipation += rep.contact_dissipation;
    r.st.damper_dissipation += rep.damper_dissipation;
    if (j == n_cycle / 2) s_max = settlement;  // F = A + B: the largest load of the cycle
    if (j == n_cycle) s_min = settlement;      // F = A − B: the smallest
    if (reg.step % r.c.steps_every == 0) write_step_row(r, o, rep, settlement);
    if (o.vtk && reg.step % r.c.vtk_every == 0) o.vtk->write_frame(reg);
  }
  return sum;
}

// The end of a cycle: the run's totals, and its row of cycles.csv.
void close_cycle(Run& r, Outputs& o, const CycleSums& sum, int n_cycle, double s_min, double s_max, std::clock_t cpu0,
                 Clock::time_point wall0) {
  RunState& st = r.st;
  const Registry& reg = r.s.scene.reg;
  st.sweeps += sum.sweeps;
  st.steps += n_cycle;
  st.unconverged += sum.unconverged;
  if (st.max_sweeps >= 0) st.max_sweeps = std::max(st.max_sweeps, sum.max_sweeps);
  if (st.presweeps >= 0) st.presweeps += sum.presweeps;
  st.max_overlap = std::max(st.max_overlap, sum.overlap_max);
  st.sum_mean_overlap += sum.overlap;
  st.sum_total_overlap += sum.total;
  st.cpu_seconds += double(std::clock() - cpu0) / CLOCKS_PER_SEC;
  st.last_settlement_min = s_min;
  st.last_settlement_max = s_max;
  o.row = {double(st.cycles_done), reg.time, s_min, s_max, reg.bodies.x[r.s.sleeper.index()] - st.x_ref, sum.speed / n_cycle,
           sum.overlap / n_cycle, sum.overlap_max, double(sum.sweeps) / n_cycle, double(sum.unconverged), since(wall0),
           sum.total / n_cycle, kinetic_energy(reg, r.c.threads), st.contact_dissipation, sum.contact_diss,
           st.damper_dissipation, sum.damper_diss};
  scenes::append_network_values(o.network.measure(reg, r.c.threads), o.row);
  o.row.push_back(double(sum.presweeps) / n_cycle);
  o.cycles_csv.row(o.row);
}

// A physically impossible state at the end of a cycle ("" if none).
std::string impossible_state(const Run& r, double s_min, double s_max) {
  std::string impossible = scenes::implausible(r.s.scene.reg, r.s.scene.grains, r.s.scene.box_width, 0.0);
  if (impossible.empty()) impossible = scenes::grain_below_sublayer(r.s);
  if (impossible.empty() && !(std::abs(s_min) <= r.st.y_ref && std::abs(s_max) <= r.st.y_ref))
    impossible = "the settlement (" + exact(s_min) + " m) is larger than the whole layer (the sleeper started " + exact(r.st.y_ref) +
                 " m above the floor)";
  if (!impossible.empty()) impossible = "cycle " + std::to_string(r.st.cycles_done) + ": " + impossible;
  return impossible;
}

// How the cycles ended, for the summary and the exit status.
struct CyclesEnd {
  int first_cycle = 0;
  Clock::time_point wall0;
  std::clock_t cpu0 = 0;
  std::string impossible;    // a physically impossible state, found at the end of a cycle
  bool over_budget = false;  // --strict-overlap: the overlap budget was passed in the cycle just done
  bool terminated = false;   // SIGTERM
};

void print_progress(const Run& r, const CycleSums& sum, const CyclesEnd& e, int n_cycle, int last_cycle, double s_min,
                    double s_max) {
  const int done = r.st.cycles_done;
  const double per = since(e.wall0) / double(done - e.first_cycle);
  char pre[48] = "";  // the hybrid's NLGS sweeps, which the Newton iterations leave out
  if (sum.presweeps > 0) std::snprintf(pre, sizeof pre, " (+%.1f NLGS)", double(sum.presweeps) / n_cycle);
  std::printf("cycle %5d/%d  settlement %.4f mm (max load %.4f mm)  sweeps/step %.1f%s  max overlap %.2e m  %.2f s/cycle  ETA %s\n",
              done, r.c.cycles, 1e3 * s_min, 1e3 * s_max, double(sum.sweeps) / n_cycle, pre, sum.overlap_max, per,
              format_duration(per * (last_cycle - done)).c_str());
  std::fflush(stdout);
}

// 3. The cycles, until --cycles (or --stop-after-cycles), an impossible state, the overlap
// budget passed (--strict-overlap) or SIGTERM.
CyclesEnd run_cycles(Run& r, MoreauJean& mj, Outputs& o, scenes::StepWatch& watch, int n_cycle, const fs::path& out,
                     const SigtermCheckpoint& sigterm) {
  const Config& c = r.c;
  RunState& st = r.st;
  CyclesEnd e;
  e.wall0 = Clock::now();
  auto last_checkpoint = Clock::now();
  e.cpu0 = std::clock();
  e.first_cycle = st.cycles_done;
  const int last_cycle = c.stop_after_cycles > 0 ? std::min(c.cycles, st.cycles_done + c.stop_after_cycles) : c.cycles;
  auto last_print = Clock::now();
  double s_max = 0.0, s_min = 0.0;
  for (int cycle = st.cycles_done; cycle < last_cycle; ++cycle) {
    const auto cw = Clock::now();
    const std::clock_t cc = std::clock();
    const CycleSums sum = step_cycle(r, mj, o, watch, n_cycle, s_min, s_max);
    st.cycles_done = cycle + 1;
    close_cycle(r, o, sum, n_cycle, s_min, s_max, cc, cw);
    e.impossible = impossible_state(r, s_min, s_max);
    if (!e.impossible.empty()) break;  // the last checkpoint (before this state) is kept
    e.over_budget = c.strict_overlap && watch.over_limit_steps > 0;
    // Checkpoints at cycle ends only (a checkpoint carries no partial cycle): every
    // --checkpoint-every cycles, at the first cycle end --checkpoint-wall seconds after the
    // last one, and on SIGTERM, which then ends the run.
    e.terminated = sigterm.requested();
    if ((c.checkpoint_every > 0 && st.cycles_done % c.checkpoint_every == 0) ||
        (c.checkpoint_wall > 0 && since(last_checkpoint) >= c.checkpoint_wall) || e.terminated || e.over_budget) {
      o.steps_csv.flush();
      save_checkpoint(out / "checkpoint.nscd", r.s.scene.reg, mj.warm_start_memory(), state_map(c, st, r.sample_used));
      last_checkpoint = Clock::now();
    }
    if (e.over_budget) break;
    if (e.terminated) {
      std::printf("ballast: SIGTERM: stopped after cycle %d with its checkpoint; continue with --resume %s\n", st.cycles_done,
                  out.string().c_str());
      break;
    }
    if (since(last_print) >= c.progress_every || st.cycles_done == last_cycle) {
      last_print = Clock::now();
      print_progress(r, sum, e, n_cycle, last_cycle, s_min, s_max);
    }
  }
  o.steps_csv.flush();
  o.cycles_csv.flush();
  return e;
}

// The wall and processor times of the run, for the summary.
struct RunTimes {
  Clock::time_point wall0;  // the start of the run
  double prep_wall = 0.0;   // s: the sample's loading or preparation
  double cycles_wall = 0.0, cycles_cpu = 0.0;
  int run_cycles = 0;       // the cycles this process ran
};

// 4. summary.txt, written whole at the end (atomic_write), 17 significant digits: what the run
// used (a loaded sample's own values, a resumed run's stored options) and what it found.
void write_summary(const Run& r, const CyclesEnd& e, const scenes::StepWatch& watch, int n_cycle, double k_sample,
                   const RunTimes& t, const fs::path& out) {
  const Config& c = r.c;
  const RunState& st = r.st;
  driver::Summary summary;
  std::ostream& sum = summary.stream();
  sum << "result = " << (!e.impossible.empty() ? "impossible: " + e.impossible : e.over_budget ? "stopped: overlap budget passed" : "valid") << "\n"
      << "sample = " << (r.sample_used.empty() ? "prepared by this run" : r.sample_used) << "\n"
      << "solver = " << c.solver << "\n"
      << "order = " << c.order << "\n"
      << "relaxation = " << exact(c.relaxation) << "\n"
      << "anderson = " << c.anderson << "\n"
      << "cycles = " << st.cycles_done << "\n"
      << "final_settlement = " << st.last_settlement_min << "\n"
      << "final_settlement_max_load = " << st.last_settlement_max << "\n"
      << "mean_sweeps = " << (st.steps ? double(st.sweeps) / double(st.steps) : 0.0) << "\n"
      << "max_sweeps = " << (st.max_sweeps >= 0 ? double(st.max_sweeps) : std::nan("")) << "\n"
      << "mean_presweeps = " << (st.presweeps >= 0 && st.steps ? double(st.presweeps) / double(st.steps) : std::nan("")) << "\n"
      << "max_overlap = " << st.max_overlap << "\n"
      << "mean_overlap = " << (st.steps ? st.sum_mean_overlap / double(st.steps) : 0.0) << "\n"
      << "cumulated_overlap = " << (st.steps ? st.sum_total_overlap / double(st.steps) : 0.0) << "\n"
      << "projection = " << (c.projection ? "on" : "off") << "\n"
      << "projection_slop = " << c.projection_slop * c.alert << "\n"
      << "unconverged_steps = " << st.unconverged << "\n"
      << "steps_per_cycle = " << n_cycle << "\n"
      << "grains = " << r.s.scene.grains.size() << "\n"
      << "pads = " << r.s.pads.size() << "\n"
      << "pad_height = " << exact(c.pad_height) << "\n"
      << "k = " << k_sample << "\n"
      << "k_factor = " << c.k_factor << "\n"
      << "seed = " << c.seed << "\n"
      << "mu = " << c.mu << "\n"
      << "nu = " << c.nu << "\n"
      << "box_width = " << c.box_width << "\n"
      << "dt = " << c.dt << "\n"
      << "frequency = " << c.frequency << "\n"
      << "load_mean = " << c.load_mean << "\n"
      << "load_amplitude = " << c.load_amplitude << "\n"
      << "wall_time = " << since(t.wall0) << "\n"
      << "preparation_wall_time = " << t.prep_wall << "\n"
      << "time_per_cycle = " << (t.run_cycles > 0 ? t.cycles_wall / t.run_cycles : 0.0) << "\n"
      << "cpu_time_per_cycle = " << (t.run_cycles > 0 ? t.cycles_cpu / t.run_cycles : 0.0) << "\n"
      << "cpu_time_cycles = " << st.cpu_seconds << "\n"
      << watch.summary();
  if (st.cycles_done > 0) {
    const int block = scenes::overlap_block_length(st.cycles_done);
    summary.lines(scenes::overlap_growth_lines(scenes::overlap_blocks(out / "cycles.csv", block), block));
  }
  summary.write(out / "summary.txt");
}

// The closing words and the exit status: 3 for an impossible state or the overlap budget
// passed, 143 for SIGTERM, else 0.
int finish(const Run& r, const CyclesEnd& e, const scenes::StepWatch& watch, bool vtk, const RunTimes& t, const fs::path& out) {
  const RunState& st = r.st;
  if (e.over_budget) {
    std::fflush(stdout);
    std::fprintf(stderr, "ballast: error: the overlap budget %g m was passed (first at step %lld; --strict-overlap): the run stops after "
                 "cycle %d with its checkpoint (exit 3)\n", watch.overlap_limit, static_cast<long long>(watch.first_over_limit), st.cycles_done);
    return driver::kExitImpossible;
  }
  if (!e.impossible.empty()) {
    std::fflush(stdout);
    std::fprintf(stderr, "ballast: error: physically impossible result at %s; the run stops (exit 3), its last checkpoint is kept\n",
                 e.impossible.c_str());
    return driver::kExitImpossible;
  }
  if (e.terminated) {
    std::fflush(stdout);
    std::fprintf(stderr, "ballast: stopped by SIGTERM after cycle %d of %d (exit 143); %s/checkpoint.nscd holds it\n", st.cycles_done,
                 r.c.cycles, out.string().c_str());
    return driver::kExitTerminated;
  }
  std::printf("done: %d cycles, settlement %.4f mm at the smallest load (%.4f mm at the largest), %.2f s/cycle, mean sweeps %.1f,\n"
              "      max overlap %.2e m; outputs in %s (summary.txt, cycles.csv, steps.csv, checkpoint.nscd%s)\n",
              st.cycles_done, 1e3 * st.last_settlement_min, 1e3 * st.last_settlement_max,
              t.run_cycles > 0 ? t.cycles_wall / t.run_cycles : 0.0, st.steps ? double(st.sweeps) / double(st.steps) : 0.0,
              st.max_overlap, out.string().c_str(), vtk ? ", vtk/" : "");
  std::fputs(watch.closing_line().c_str(), stdout);
  std::fputs(watch.solve_profile_table().c_str(), stdout);
  return 0;
}

}  // namespace

int run(Config c) {
  RunTimes t;
  t.wall0 = Clock::now();
  if (c.continue_run && !apply_continue(c)) return 0;
  Run r;
  r.cli = c;
  r.c = std::move(c);
  check(r.c);  // Config built by hand (tests, other drivers) gets the same checks as the command line
  r.sample_used = r.c.sample;
  claim_output(r);
  obtain_sample(r);
  Registry& reg = r.s.scene.reg;
  // the sample's own stiffness (before any --k-factor) and seed, for the summary
  const double k_sample = reg.links.empty() ? r.c.k : reg.links.law[0].k / (r.cycles_started ? r.c.k_factor : 1.0);
  refuse_excess_load(r, k_sample);
  reg.params.dt = r.c.dt;
  reg.params.theta = r.c.theta;
  reg.params.alert = r.c.alert;
  validate(reg.params);
  MoreauJean mj(reg, stepper_options(r.c));
  mj.set_warm_start_memory(r.warm);
  driver::input_accepted();  // options, sample and checkpoint accepted: from here, errors are the run's (exit 1)
  if (r.c.pad_height < r.c.spring_length)
    std::printf("WARNING: the pads (%g m) are shorter than the springs (%g m): a pad sinking more than its height below a "
                "neighbour opens a way under that neighbour, and grains can leave the layer through the sublayer "
                "(--pad-height %g closes it)\n", r.c.pad_height, r.c.spring_length, r.c.spring_length);
  scenes::StepWatch watch;  // counts of this process's steps (not carried by checkpoints)
  watch.overlap_limit = scenes::overlap_budget(r.c.overlap_limit, scenes::smallest_grain_size(reg, r.s.scene.grains));
  const fs::path out(r.c.output);
  if (r.c.resume.empty() && r.c.sample.empty()) prepare_sample(r, mj, watch, out);
  t.prep_wall = since(t.wall0);
  if (r.c.prepare_only) return 0;
  apply_load(r);
  const int n_cycle = static_cast<int>(std::lround(1.0 / (r.c.frequency * r.c.dt)));
  const std::unique_ptr<Outputs> o = open_outputs(r, out);
  print_cycles_header(r.c, n_cycle, out);
  const SigtermCheckpoint sigterm;
  const CyclesEnd e = run_cycles(r, mj, *o, watch, n_cycle, out, sigterm);
  // the final checkpoint (none of an impossible state) and frame
  if (e.impossible.empty()) save_checkpoint(out / "checkpoint.nscd", reg, mj.warm_start_memory(), state_map(r.c, r.st, r.sample_used));
  if (o->vtk && r.st.cycles_done > e.first_cycle && reg.step % r.c.vtk_every != 0) o->vtk->write_frame(reg);
  t.run_cycles = r.st.cycles_done - e.first_cycle;
  t.cycles_wall = since(e.wall0);
  t.cycles_cpu = double(std::clock() - e.cpu0) / CLOCKS_PER_SEC;
  write_summary(r, e, watch, n_cycle, k_sample, t, out);
  if (!r.c.plan_model.empty() && e.impossible.empty())  // (begins a step the run never finishes: last)
    driver::print_next_step_plan(mj, driver::parse_thread_list(r.c.plan_model, "--plan-model"));
  return finish(r, e, watch, o->vtk != nullptr, t, out);
}

}  // namespace ballast
