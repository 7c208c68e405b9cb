// examples/scaling/main.cpp — `scaling`: what a settled step costs per grain, and where it goes
// (detection, NLGS, the rest), on a settled sample copied side by side K times (issue #8).
//
// What it shows
//   Whether the cost of a time step grows like the number of grains N: on log-log axes the
//   step cost against N should have a slope close to 1 (≤ 1.1 is the goal). The split into
//   detection / NLGS solve / the rest (free velocities, prepare, integration, checks) tells
//   which part breaks it; sweeps per step and the NLGS cost per grain per sweep tell whether
//   the solver needs more sweeps (physics: longer force chains) or each sweep costs more per
//   grain (memory: cache misses).
//
// Build   cmake -S . -B build && cmake --build build --target scaling deposit
// Run     build/examples/deposit/deposit --grains 700 --no-vtk --output out/dep700
//         build/examples/scaling/scaling --sample out/dep700/final_state.nscd --copies 100
//             --csv out/scaling.csv --machine my-laptop            (one line)
//         tools/bench_results.sh runs the whole measurement (docs/benchmarks.md §6).
// Method  load --sample (a checkpoint of a settled deposit: deposit's final_state.nscd), tile
//         it --copies times along x (nscd::scenes::tile_scene), run --warmup steps (the warm
//         start has to be rebuilt and the seams settle), then time --steps steps. The deposit
//         driver's solver settings: NLGS QM/16, tol 1.666e-4, a check every 10 sweeps, at most
//         1000 sweeps, warm start, fixed order (--nlgs-order), one thread. The step and its
//         parts are timed in CPU time of the thread (CLOCK_THREAD_CPUTIME_ID), not wall time:
//         on a loaded machine a wall-clock step longer than a scheduler slice also counts other
//         jobs' turns, which grows the cost of big scenes only (the wall time is printed and
//         written too).
// Threads --nlgs-order colored --threads 1,2: the thread counts take turns on one trajectory
//         (the numbers do not depend on the count): an untimed step at each switch, then --turn
//         timed steps, until each count has --steps. The parts are then timed in wall time, and
//         each count's speed-up against the first is given two ways: the ratio of the medians,
//         and the median of the rounds' ratios (the j-th timed steps of each count).
// Plan    --plan-model: after the warm-up, what the planned sweep of the next step's system
//         allows each --threads count on a model (shared/driver/plan_table.hpp), for counts no machine at
//         hand has; nothing is timed.
// Output  a table on stdout (the rest split into begin / prepare / end); with --csv, one row
//         per thread count appended (the header written when the file is new; a file of another
//         header is refused before anything runs): medians over the timed steps of the step's
//         time and of its parts, per grain, sweeps, contacts per grain, NLGS cost per grain per
//         sweep and per contact update, the NLGS order, the threads and the clock (cpu, wall).
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "nscd/io/checkpoint.hpp"
#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/plan_table.hpp"
#include "nscd/shared/driver/run_main.hpp"
#include "nscd/shared/step_watch.hpp"
#include "nscd/shared/tiling.hpp"
#include "nscd/solvers/moreau_jean.hpp"

using namespace nscd;

namespace {

struct Options {
  std::string sample;
  std::uint64_t copies = 1;
  std::string seams = "walls";
  std::string order = "copies";
  int warmup = 100;
  int steps = 100;
  std::string csv;
  std::string machine = "unnamed";
  std::string label;
  std::string nlgs_order = "fixed";
  std::string threads = "1";
  int turn = 5;
  bool projection = true;
  bool plan_model = false;
  bool solve_profile = false;
  std::vector<int> thread_counts;  ///< --threads parsed
};

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2 == 1) return *mid;
  return 0.5 * (*mid + *std::max_element(v.begin(), mid));
}

const driver::OptionTable<Options> kOptions(
    "scaling", "settled step cost per grain, split into detection / NLGS / the rest",
    {{"sample", &Options::sample, "checkpoint of a settled sample in a box (deposit's final_state.nscd)", driver::Kind::Free,
      driver::kRequired | driver::kNoDefault},
     {"copies", &Options::copies, "copies of the sample side by side, in [1, 10000]"},
     {"seams", &Options::seams, "between copies: 'walls' (a fixed 1 cm wall, each copy at rest in its compartment), 'plain' or 'mirrored' (the seams collapse for hundreds of steps; nscd/shared/tiling.hpp)"},
     {"order", &Options::order, "body order of the tiled grains: 'copies' (copy by copy) or 'rows' (rows across the whole width, as a wide deposit numbers them)"},
     {"warmup", &Options::warmup, "steps before the timed ones (warm start rebuilt, seams settled), >= 0"},
     {"steps", &Options::steps, "timed steps, in [1, 100000]"},
     {"csv", &Options::csv, "append one row of results to this CSV file (header written if new)", driver::Kind::Free, driver::kNoDefault},
     {"machine", &Options::machine, "machine name for the CSV row (letters, digits, - _ . only)"},
     {"label", &Options::label, "free label for the CSV row (e.g. 'tiled'; no comma)"},
     {"nlgs-order", &Options::nlgs_order, "NLGS sweep order: fixed (the deposit driver's), colored, colored-rows or colored-cells (in SIMD lanes; threads > 1 need one of these)"},
     {"threads", &Options::threads, "threads of the step (detection, NLGS sweep, the loops around the solve), or a comma-separated list (e.g. 1,2): each count then takes --turn timed steps in turn, after one untimed step, on one trajectory (the numbers do not depend on the count), until each has --steps; each count gets its row; the solve runs on each count as given, not on one chosen by measure"},
     {"turn", &Options::turn, "with several --threads counts: timed steps of a count's turn, in [1, 1000]"},
     {"projection", &Options::projection, "the overlap projection after each solve, as in the drivers (docs/theory.md 8.4; part of end_step's time); false: without it, as before it existed", driver::Kind::Free, driver::kImplicit},
     {"plan-model", &Options::plan_model, "after the warm-up, print what the planned sweep of that step's system allows each --threads count, on a model (no step is timed; shared/driver/plan_table.hpp), and stop", driver::Kind::Free, driver::kImplicit},
     driver::solve_profile_option<Options>()});

bool parse(int argc, char** argv, Options& o) {
  if (!kOptions.parse(argc, argv, o)) return false;
  if (o.copies < 1 || o.copies > 10000) throw driver::InputError("--copies must lie in [1, 10000], got " + std::to_string(o.copies));
  if (o.seams != "walls" && o.seams != "plain" && o.seams != "mirrored")
    throw driver::InputError("--seams must be walls, plain or mirrored, got '" + o.seams + "'");
  if (o.order != "copies" && o.order != "rows") throw driver::InputError("--order must be copies or rows, got '" + o.order + "'");
  if (o.warmup < 0) throw driver::InputError("--warmup must be >= 0, got " + std::to_string(o.warmup));
  if (o.turn < 1 || o.turn > 1000) throw driver::InputError("--turn must lie in [1, 1000], got " + std::to_string(o.turn));
  if (o.steps < 1 || o.steps > 100000) throw driver::InputError("--steps must lie in [1, 100000], got " + std::to_string(o.steps));
  if (o.nlgs_order != "fixed" && !driver::is_colored_order(o.nlgs_order))
    throw driver::InputError("--nlgs-order must be fixed, colored, colored-rows or colored-cells, got '" + o.nlgs_order + "'");
  o.thread_counts = driver::parse_thread_list(o.threads, "--threads");
  for (int t : o.thread_counts)
    if (t > 1 && o.nlgs_order == "fixed")
      throw driver::InputError("--threads " + o.threads + " needs --nlgs-order colored, colored-rows or colored-cells (the fixed order sweeps on one thread)");
  if (o.plan_model && o.nlgs_order == "fixed")
    throw driver::InputError("--plan-model needs --nlgs-order colored, colored-rows or colored-cells (the fixed order is not planned)");
  if (o.plan_model && !o.csv.empty()) throw driver::InputError("--plan-model times no step: it writes no --csv row");
  for (char ch : o.machine)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_' || ch == '.'))
      throw driver::InputError("--machine may hold letters, digits, '-', '_' and '.' only, got '" + o.machine + "'");
  if (o.label.find_first_of(",\n\"") != std::string::npos) throw driver::InputError("--label may not hold a comma, a quote or a newline");
  return true;
}

struct Result {
  int threads = 1;
  std::size_t grains = 0;
  double contacts = 0, sweeps = 0, mean_sweeps = 0;
  double step_s = 0, detect_s = 0, solve_s = 0, rest_s = 0;  ///< CPU time of the thread, or wall time (`wall_parts`)
  double begin_s = 0, prepare_s = 0, end_s = 0;                ///< the rest's parts
  double wall_s = 0;                                           ///< wall time of the step
  double ns_per_grain_sweep = 0, ns_per_update = 0;
  double speedup = 0;        ///< median wall time of the first count's steps / this count's
  double round_speedup = 0;  ///< median over the rounds (the j-th timed step of each count) of the same ratio
  int unconverged = 0;
  int steps = 0;
  SolveParts parts;         ///< --solve-profile: the timed steps' solves, summed
  double solve_total = 0;   ///< the timed steps' solve time, summed
};

/// The timed steps of one thread count, before the medians.
struct Samples {
  std::vector<double> step, detect, solve, rest, begin, prepare, end, wall, sweeps, contacts;
  double solve_sum = 0, sweep_grain_sum = 0, updates = 0, sweep_sum = 0;
  int unconverged = 0;
  SolveParts parts;
};

/// Several thread counts: the parts are timed in wall time (a thread's CPU time misses the
/// others'); one count of 1: in the thread's CPU time, as the CSV's older rows.
bool wall_parts(const Options& o) { return o.thread_counts.size() > 1 || o.thread_counts.front() > 1; }

StepperOptions scaling_stepper_options(const Options& o) {
  StepperOptions so;  // the deposit driver's defaults (deposit_study.hpp)
  so.nlgs.policy = ConvergencePolicy::QM16;
  so.nlgs.tol = 1.666e-4;
  so.nlgs.check_every = 10;
  so.nlgs.max_sweeps = 1000;
  so.nlgs.order = parse_sweep_order(o.nlgs_order);
  so.nlgs.threads = o.thread_counts.front();
  so.threads = so.nlgs.threads;  // the rest of the step's too
  // a row measures its count: the solve on it, not on a count chosen by measure
  so.solve_threads = is_colored(so.nlgs.order) ? so.nlgs.threads : 0;
  so.nlgs.profile = o.solve_profile;
  so.warm_start = true;
  so.residual_check_every = 0;  // timing only
  so.projection.enabled = o.projection;
  return so;
}

/// A step of the plan that is not timed.
constexpr std::size_t kUntimed = ~std::size_t{0};

/// The thread count of each step (its index in --threads; kUntimed: not timed). The counts take
/// turns: one step untimed (the switch: the data move to the other cores' caches, the threads
/// wake up), then `turn` timed steps. The numbers do not depend on the count (theory §9.5), so
/// every count runs the same trajectory, and its turns fall in the same phases of a shared
/// machine as the others'. One count: --steps timed steps.
std::vector<std::size_t> turn_plan(const Options& o, std::size_t counts) {
  std::vector<std::size_t> plan;
  if (counts == 1) {
    plan.assign(static_cast<std::size_t>(o.steps), 0);
    return plan;
  }
  for (int done = 0; done < o.steps; done += o.turn)
    for (std::size_t k = 0; k < counts; ++k) {
      plan.push_back(kUntimed);  // switching to count k (plan tells which below)
      plan.push_back(k);
      for (int j = 1; j < std::min(o.turn, o.steps - done); ++j) plan.push_back(k);
    }
  return plan;
}

/// The clock of the parts (see wall_parts): wall time, or the thread's CPU time.
double part_clock(bool wall) {
  if (wall) return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  return thread_cpu_seconds();
}

/// One timed step, call by call, each part timed apart (see wall_parts): on a shared machine a
/// wall-clock step longer than a scheduler slice also counts the other jobs' turns.
void timed_step(MoreauJean& mj, bool wall, std::size_t grains, Samples& m) {
  const auto w0 = std::chrono::steady_clock::now();
  const double c0 = part_clock(wall);
  mj.begin_step();
  const double c1 = part_clock(wall);
  mj.detect();
  const double c2 = part_clock(wall);
  mj.prepare();
  const double c3 = part_clock(wall);
  mj.solve();
  const double c4 = part_clock(wall);
  mj.end_step();
  const double c5 = part_clock(wall);
  m.wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count());
  const StepReport& rep = mj.report();
  m.step.push_back(c5 - c0);
  m.detect.push_back(c2 - c1);
  m.solve.push_back(c4 - c3);
  m.rest.push_back((c1 - c0) + (c3 - c2) + (c5 - c4));
  m.begin.push_back(c1 - c0);
  m.prepare.push_back(c3 - c2);
  m.end.push_back(c5 - c4);
  m.sweeps.push_back(rep.sweeps);
  m.contacts.push_back(static_cast<double>(rep.contacts));
  m.solve_sum += c4 - c3;
  m.sweep_sum += rep.sweeps;
  m.sweep_grain_sum += static_cast<double>(rep.sweeps) * static_cast<double>(grains);
  m.updates += static_cast<double>(rep.sweeps) * static_cast<double>(rep.contacts);
  m.unconverged += rep.converged ? 0 : 1;
  m.parts += rep.solve_parts;
}

/// The medians of each thread count's samples, and its speedups against the first count.
std::vector<Result> medians(const Options& o, const std::vector<Samples>& per, std::size_t grains) {
  std::vector<Result> out(per.size());
  for (std::size_t k = 0; k < per.size(); ++k) {
    const Samples& m = per[k];
    Result& r = out[k];
    r.threads = o.thread_counts[k];
    r.grains = grains;
    r.steps = static_cast<int>(m.step.size());
    r.wall_s = median(m.wall);
    r.step_s = median(m.step);
    r.detect_s = median(m.detect);
    r.solve_s = median(m.solve);
    r.rest_s = median(m.rest);
    r.begin_s = median(m.begin);
    r.prepare_s = median(m.prepare);
    r.end_s = median(m.end);
    r.sweeps = median(m.sweeps);
    r.mean_sweeps = r.steps > 0 ? m.sweep_sum / r.steps : 0.0;
    r.contacts = median(m.contacts);
    r.ns_per_grain_sweep = m.sweep_grain_sum > 0 ? 1e9 * m.solve_sum / m.sweep_grain_sum : 0.0;
    r.ns_per_update = m.updates > 0 ? 1e9 * m.solve_sum / m.updates : 0.0;
    r.unconverged = m.unconverged;
    r.parts = m.parts;
    r.solve_total = m.solve_sum;
    // against the first count: the ratio of the medians, and the median of the rounds' ratios
    // (a round: the j-th timed step of each count's turns; the VM's slow phases hit a round
    // as a whole rather than one count's steps)
    r.speedup = r.step_s > 0 ? out[0].step_s / r.step_s : 0.0;
    std::vector<double> ratios;
    for (std::size_t j = 0; j < m.step.size() && j < per[0].step.size(); ++j)
      if (m.step[j] > 0) ratios.push_back(per[0].step[j] / m.step[j]);
    r.round_speedup = median(ratios);
  }
  return out;
}

std::vector<Result> measure(const Options& o, Checkpoint& cp) {
  scenes::Scene s = scenes::tile_scene(cp.reg, o.copies,
                                       o.seams == "walls"   ? scenes::Seams::Walls
                                       : o.seams == "plain" ? scenes::Seams::Plain
                                                            : scenes::Seams::Mirrored,
                                       o.order == "rows" ? scenes::TileOrder::Rows : scenes::TileOrder::Copies);
  StepperOptions so = scaling_stepper_options(o);
  MoreauJean mj(s.reg, so);
  for (int i = 0; i < o.warmup; ++i) mj.step();
  if (o.plan_model) {  // the next step's system, as the solve would find it
    driver::print_next_step_plan(mj, o.thread_counts);
    return {};
  }
  const bool wall = wall_parts(o);
  const std::size_t counts = o.thread_counts.size();
  std::vector<Samples> per(counts);
  const std::vector<std::size_t> plan = turn_plan(o, counts);
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const bool timed = plan[i] != kUntimed;
    const std::size_t k = timed ? plan[i] : plan[i + 1];
    if (so.nlgs.threads != o.thread_counts[k]) {
      so.nlgs.threads = o.thread_counts[k];
      so.threads = so.nlgs.threads;
      so.solve_threads = is_colored(so.nlgs.order) ? so.nlgs.threads : 0;
      mj.set_options(so);
    }
    if (timed)
      timed_step(mj, wall, s.grains.size(), per[k]);
    else
      mj.step();
  }
  return medians(o, per, s.grains.size());
}

const char* kCsvHeader =
    "machine,label,grains,copies,warmup,steps,contacts_per_grain,median_sweeps,mean_sweeps,unconverged_steps,"
    "step_ms,detect_ms,solve_ms,rest_ms,step_us_per_grain,detect_us_per_grain,solve_us_per_grain,rest_us_per_grain,"
    "solve_ns_per_grain_sweep,solve_ns_per_update,wall_step_ms,nlgs_order,threads,clock";

/// A CSV to append to must have this version's header: refused before the measurement, so that
/// minutes of measuring are not lost on a file that cannot take the row.
void check_csv(const std::string& path) {
  if (path.empty() || !std::filesystem::exists(path) || std::filesystem::file_size(path) == 0) return;
  std::ifstream f(path);
  std::string header;
  std::getline(f, header);
  if (header != kCsvHeader)
    throw driver::InputError("--csv " + path + " has another header than this version of scaling writes (" +
                             "its columns end in 'nlgs_order,threads,clock'); give a new file");
}

void write_csv(const Options& o, const std::vector<Result>& rows) {
  const bool fresh = !std::filesystem::exists(o.csv) || std::filesystem::file_size(o.csv) == 0;
  if (const auto dir = std::filesystem::path(o.csv).parent_path(); !dir.empty()) std::filesystem::create_directories(dir);
  std::ofstream f(o.csv, std::ios::app);
  if (fresh) f << kCsvHeader << "\n";
  for (const Result& r : rows) {
    const double n = static_cast<double>(r.grains);
    char line[640];
    std::snprintf(line, sizeof line,
                  "%s,%s,%zu,%zu,%d,%d,%.4f,%.1f,%.2f,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.3f,%.3f,%.4f,%s,%d,%s\n",
                  o.machine.c_str(), o.label.c_str(), r.grains, o.copies, o.warmup, r.steps, r.contacts / n, r.sweeps,
                  r.mean_sweeps, r.unconverged, 1e3 * r.step_s, 1e3 * r.detect_s, 1e3 * r.solve_s, 1e3 * r.rest_s,
                  1e6 * r.step_s / n, 1e6 * r.detect_s / n, 1e6 * r.solve_s / n, 1e6 * r.rest_s / n, r.ns_per_grain_sweep,
                  r.ns_per_update, 1e3 * r.wall_s, o.nlgs_order.c_str(), r.threads, wall_parts(o) ? "wall" : "cpu");
    f << line;
  }
  if (!f) throw std::runtime_error("cannot write " + o.csv);
}


int run(const Options& o) {
  Checkpoint cp = load_checkpoint(o.sample);  // a sample that cannot be read is bad input (exit 2)
  check_csv(o.csv);
  driver::input_accepted();
  const std::vector<Result> rows = measure(o, cp);
  if (rows.empty()) return 0;  // (--plan-model: printed)
  const Result& r0 = rows.front();
  const double n = static_cast<double>(r0.grains);
  std::printf(
      "scaling: %zu grains (%zu copies of %s), %d warm-up + %d timed steps, NLGS order %s%s; medians over the timed steps\n",
      r0.grains, static_cast<std::size_t>(o.copies), o.sample.c_str(), o.warmup, o.steps, o.nlgs_order.c_str(),
      o.projection ? "" : ", no overlap projection");
  if (rows.size() > 1)
    std::printf("  the thread counts %s take turns of %d timed steps (after an untimed one), on one trajectory\n", o.threads.c_str(),
                o.turn);
  for (const Result& r : rows) {
    std::printf("  threads %d (%d steps): contacts/grain %.3f  sweeps %.0f (mean %.1f, %d unconverged)\n", r.threads, r.steps,
                r.contacts / n, r.sweeps, r.mean_sweeps, r.unconverged);
    std::printf("  %s of the step and its parts (medians; wall time of the step %.3f ms):\n",
                wall_parts(o) ? "wall time" : "CPU time", 1e3 * r.wall_s);
    std::printf("  %-8s %12s %14s\n", "part", "ms/step", "us/step/grain");
    const std::pair<const char*, double> parts[] = {{"step", r.step_s}, {"detect", r.detect_s}, {"solve", r.solve_s}, {"rest", r.rest_s},
                                                    {" begin", r.begin_s}, {" prepare", r.prepare_s}, {" end", r.end_s}};
    for (const auto& [name, v] : parts) std::printf("  %-8s %12.3f %14.4f\n", name, 1e3 * v, 1e6 * v / n);
    std::printf("  NLGS: %.2f ns per grain per sweep, %.2f ns per contact update\n", r.ns_per_grain_sweep, r.ns_per_update);
    std::fputs(scenes::solve_profile_table(r.parts, r.solve_total).c_str(), stdout);
    if (&r != &r0)
      std::printf("  speed-up against %d thread(s): %.3fx (medians), %.3fx (median of the rounds)\n", r0.threads, r.speedup,
                  r.round_speedup);
  }
  if (!o.csv.empty()) {
    write_csv(o, rows);
    std::printf("  %zu row%s appended to %s\n", rows.size(), rows.size() == 1 ? "" : "s", o.csv.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return driver::run_main("scaling", argc, argv, Options{}, parse, run); }
