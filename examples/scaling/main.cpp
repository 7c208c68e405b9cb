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
//         1000 sweeps, warm start, fixed order, one thread. The step and its parts are timed
//         in CPU time of the thread (CLOCK_THREAD_CPUTIME_ID), not wall time: on a loaded
//         machine a wall-clock step longer than a scheduler slice also counts other jobs' turns,
//         which grows the cost of big scenes only (the wall time is printed and written too).
// Output  a table on stdout; with --csv, one row appended (the header written when the file
//         is new): medians over the timed steps of CPU time per step and of its parts, per grain,
//         sweeps, contacts per grain, NLGS cost per grain per sweep and per contact update.
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
#include "nscd/shared/driver/run_main.hpp"
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
     {"label", &Options::label, "free label for the CSV row (e.g. 'tiled'; no comma)"}});

bool parse(int argc, char** argv, Options& o) {
  if (!kOptions.parse(argc, argv, o)) return false;
  if (o.copies < 1 || o.copies > 10000) throw driver::InputError("--copies must lie in [1, 10000], got " + std::to_string(o.copies));
  if (o.seams != "walls" && o.seams != "plain" && o.seams != "mirrored")
    throw driver::InputError("--seams must be walls, plain or mirrored, got '" + o.seams + "'");
  if (o.order != "copies" && o.order != "rows") throw driver::InputError("--order must be copies or rows, got '" + o.order + "'");
  if (o.warmup < 0) throw driver::InputError("--warmup must be >= 0, got " + std::to_string(o.warmup));
  if (o.steps < 1 || o.steps > 100000) throw driver::InputError("--steps must lie in [1, 100000], got " + std::to_string(o.steps));
  for (char ch : o.machine)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_' || ch == '.'))
      throw driver::InputError("--machine may hold letters, digits, '-', '_' and '.' only, got '" + o.machine + "'");
  if (o.label.find_first_of(",\n\"") != std::string::npos) throw driver::InputError("--label may not hold a comma, a quote or a newline");
  return true;
}

struct Result {
  std::size_t grains = 0;
  double contacts = 0, sweeps = 0, mean_sweeps = 0;
  double step_s = 0, detect_s = 0, solve_s = 0, rest_s = 0;  ///< CPU time of the thread
  double wall_s = 0;                                           ///< wall time of the step
  double ns_per_grain_sweep = 0, ns_per_update = 0;
  int unconverged = 0;
};

Result measure(const Options& o, Checkpoint& cp) {
  scenes::Scene s = scenes::tile_scene(cp.reg, o.copies,
                                          o.seams == "walls" ? scenes::Seams::Walls : o.seams == "plain" ? scenes::Seams::Plain : scenes::Seams::Mirrored,
                                          o.order == "rows" ? scenes::TileOrder::Rows : scenes::TileOrder::Copies);
  StepperOptions so;  // the deposit driver's defaults (deposit_study.hpp)
  so.nlgs.policy = ConvergencePolicy::QM16;
  so.nlgs.tol = 1.666e-4;
  so.nlgs.check_every = 10;
  so.nlgs.max_sweeps = 1000;
  so.warm_start = true;
  so.residual_check_every = 0;  // timing only
  MoreauJean mj(s.reg, so);
  for (int i = 0; i < o.warmup; ++i) mj.step();
  Result r;
  r.grains = s.grains.size();
  std::vector<double> step, detect, solve, rest, sweeps, contacts;
  double solve_sum = 0, sweep_grain_sum = 0, updates = 0, sweep_sum = 0;
  std::vector<double> wall;
  for (int i = 0; i < o.steps; ++i) {
    // the step call by call, each part timed in CPU time of this thread (one thread): on a shared
    // machine a wall-clock step longer than a scheduler slice also counts the other jobs' turns
    const auto w0 = std::chrono::steady_clock::now();
    const double c0 = thread_cpu_seconds();
    mj.begin_step();
    const double c1 = thread_cpu_seconds();
    mj.detect();
    const double c2 = thread_cpu_seconds();
    mj.prepare();
    const double c3 = thread_cpu_seconds();
    mj.solve();
    const double c4 = thread_cpu_seconds();
    mj.end_step();
    const double c5 = thread_cpu_seconds();
    wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count());
    const StepReport& rep = mj.report();
    step.push_back(c5 - c0);
    detect.push_back(c2 - c1);
    solve.push_back(c4 - c3);
    rest.push_back((c1 - c0) + (c3 - c2) + (c5 - c4));
    sweeps.push_back(rep.sweeps);
    contacts.push_back(static_cast<double>(rep.contacts));
    solve_sum += c4 - c3;
    sweep_sum += rep.sweeps;
    sweep_grain_sum += static_cast<double>(rep.sweeps) * static_cast<double>(r.grains);
    updates += static_cast<double>(rep.sweeps) * static_cast<double>(rep.contacts);
    r.unconverged += rep.converged ? 0 : 1;
  }
  r.wall_s = median(wall);
  r.step_s = median(step);
  r.detect_s = median(detect);
  r.solve_s = median(solve);
  r.rest_s = median(rest);
  r.sweeps = median(sweeps);
  r.mean_sweeps = sweep_sum / o.steps;
  r.contacts = median(contacts);
  r.ns_per_grain_sweep = sweep_grain_sum > 0 ? 1e9 * solve_sum / sweep_grain_sum : 0.0;
  r.ns_per_update = updates > 0 ? 1e9 * solve_sum / updates : 0.0;
  return r;
}

void write_csv(const Options& o, const Result& r) {
  const bool fresh = !std::filesystem::exists(o.csv) || std::filesystem::file_size(o.csv) == 0;
  if (const auto dir = std::filesystem::path(o.csv).parent_path(); !dir.empty()) std::filesystem::create_directories(dir);
  std::ofstream f(o.csv, std::ios::app);
  if (fresh)
    f << "machine,label,grains,copies,warmup,steps,contacts_per_grain,median_sweeps,mean_sweeps,unconverged_steps,"
         "step_ms,detect_ms,solve_ms,rest_ms,step_us_per_grain,detect_us_per_grain,solve_us_per_grain,rest_us_per_grain,"
         "solve_ns_per_grain_sweep,solve_ns_per_update,wall_step_ms\n";
  const double n = static_cast<double>(r.grains);
  char line[512];
  std::snprintf(line, sizeof line, "%s,%s,%zu,%zu,%d,%d,%.4f,%.1f,%.2f,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.3f,%.3f,%.4f\n",
                o.machine.c_str(), o.label.c_str(), r.grains, o.copies, o.warmup, o.steps, r.contacts / n, r.sweeps, r.mean_sweeps,
                r.unconverged, 1e3 * r.step_s, 1e3 * r.detect_s, 1e3 * r.solve_s, 1e3 * r.rest_s, 1e6 * r.step_s / n,
                1e6 * r.detect_s / n, 1e6 * r.solve_s / n, 1e6 * r.rest_s / n, r.ns_per_grain_sweep, r.ns_per_update, 1e3 * r.wall_s);
  f << line;
  if (!f) throw std::runtime_error("cannot write " + o.csv);
}


int run(const Options& o) {
  Checkpoint cp = load_checkpoint(o.sample);  // a sample that cannot be read is bad input (exit 2)
  driver::input_accepted();
  const Result r = measure(o, cp);
  const double n = static_cast<double>(r.grains);
  std::printf("scaling: %zu grains (%zu copies of %s), %d warm-up + %d timed steps; medians over the timed steps\n", r.grains,
              static_cast<std::size_t>(o.copies), o.sample.c_str(), o.warmup, o.steps);
  std::printf("  contacts/grain %.3f  sweeps %.0f (mean %.1f, %d unconverged)\n", r.contacts / n, r.sweeps, r.mean_sweeps, r.unconverged);
  std::printf("  CPU time of the step and its parts (medians; wall time of the step %.3f ms):\n", 1e3 * r.wall_s);
  std::printf("  %-8s %12s %14s\n", "part", "ms/step", "us/step/grain");
  const std::pair<const char*, double> parts[] = {{"step", r.step_s}, {"detect", r.detect_s}, {"solve", r.solve_s}, {"rest", r.rest_s}};
  for (const auto& [name, v] : parts) std::printf("  %-8s %12.3f %14.4f\n", name, 1e3 * v, 1e6 * v / n);
  std::printf("  NLGS: %.2f ns per grain per sweep, %.2f ns per contact update\n", r.ns_per_grain_sweep, r.ns_per_update);
  if (!o.csv.empty()) {
    write_csv(o, r);
    std::printf("  row appended to %s\n", o.csv.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return driver::run_main("scaling", argc, argv, Options{}, parse, run); }
