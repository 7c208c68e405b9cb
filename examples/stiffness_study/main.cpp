// examples/stiffness_study/main.cpp — `stiffness_study`: the influence of the sublayer
// stiffness on the ballast settlement (Saussine et al. 2006, §4.2, Fig. 11), as a batch of
// `ballast` processes.
//
// What it shows
//   Eight samples that differ only by the grain dispositions before the deposit (seeds
//   s0 … s0+7), each loaded for N cycles on a sublayer whose springs are k_N = 4100 N/m × 1,
//   × 100 and × 1000. The mean settlement over the samples, cycle by cycle, for each stiffness:
//   the paper finds that the stiffer the sublayer, the smaller the settlement. Also how a study
//   of many independent runs is spread over the machine's cores, one process per run.
//
// Build
//   cmake -S . -B build && cmake --build build --target stiffness_study ballast
// Run
//   build/examples/stiffness_study/stiffness_study --samples 2 --cycles 10 --grading-fraction 0.25
//       --box-width 0.5 --pads 25 --sleeper-width 0.1        (one command line; a few minutes)
//   build/examples/stiffness_study/stiffness_study      (the paper: 8 samples × 3 k × 3000 cycles; days)
//   build/examples/stiffness_study/stiffness_study --help
// Outputs under --output DIR (default out/stiffness_study)
//   sample_S/            the prepared sample of seed S (sample.nscd) and its log.txt
//   k<F>_s<S>/           the run of sample S with stiffness × F: ballast's cycles.csv,
//                        steps.csv, summary.txt, checkpoint.nscd, and log.txt (its stdout+stderr)
//   commands.txt         every ballast command of the study, one a line
//   settlement_by_k.csv  cycle, then mean_k<F>, std_k<F> (m) for each k factor: the settlement
//                        at the smallest load, mean and standard deviation over the samples
//   summary.txt          key = value: final_mean_settlement_k<F>, final_std_k<F> (m),
//                        settlement_decreases_with_k (1/0), tasks_failed, wall_time (s), ...
//
// Steps
//   1. find the ballast executable (next to this one, or --ballast)
//   2. list the tasks: prepare each sample once (`ballast --prepare-only true --seed S ...`),
//      then one run per (sample, k factor) (`ballast --sample ... --k-factor F --cycles N ...`)
//   3. run them as separate processes, --jobs at a time (process_pool.cpp): progress, ETA, a
//      failed run reported with its log and the study going on
//   4. read every cycles.csv, write settlement_by_k.csv and summary.txt, print the table of the
//      final mean settlement per k factor and whether it decreases as k grows (Fig. 11)
#include <boost/program_options.hpp>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "process_pool.hpp"
#include "settlement_table.hpp"

namespace fs = std::filesystem;
namespace po = boost::program_options;
using namespace stiffness;

namespace {

struct Config {
  int samples = 8;
  std::uint64_t seed = 2006;
  std::string k_factors = "1,100,1000";
  int cycles = 3000;
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::string ballast;
  std::string output = "out/stiffness_study";
  int vtk_every = 0;
  double progress_every = 30.0;
  bool reuse = false, dry_run = false;
  std::vector<std::string> prepare_args;  ///< the sample size options given, as ballast arguments
  std::vector<std::string> extra_args;    ///< --ballast-option KEY=VALUE, for every ballast command
  std::vector<double> k;                  ///< parsed k_factors
};

// Returns false after --help; throws std::invalid_argument on bad input.
bool parse(int argc, char** argv, Config& c) {
  po::options_description desc("Options");
  std::vector<std::string> ballast_options;
  desc.add_options()("help,h", "print this help")
      ("samples", po::value(&c.samples)->default_value(c.samples), "number of samples M (the paper: 8)")
      ("seed", po::value(&c.seed)->default_value(c.seed), "seed of the first sample; the others are seed+1 ... seed+M-1")
      ("k-factors", po::value(&c.k_factors)->default_value(c.k_factors), "sublayer stiffness factors, comma-separated (paper 4.2: 1,100,1000)")
      ("cycles", po::value(&c.cycles)->default_value(c.cycles), "loading cycles per run (the paper: 3000)")
      ("jobs,j", po::value(&c.jobs)->default_value(c.jobs), "ballast processes at a time (default: the machine's cores)")
      ("ballast", po::value(&c.ballast), "the ballast executable (default: found next to this one)")
      ("output", po::value(&c.output)->default_value(c.output), "study directory")
      ("grading-fraction", po::value<std::string>(), "passed to the sample preparation (smaller sample, e.g. 0.25)")
      ("box-width", po::value<std::string>(), "passed to the sample preparation (m)")
      ("pads", po::value<std::string>(), "passed to the sample preparation")
      ("sleeper-width", po::value<std::string>(), "passed to the sample preparation (m)")
      ("ballast-option", po::value(&ballast_options)->composing(),
       "KEY=VALUE given to every ballast command as --KEY VALUE (repeatable), e.g. load-amplitude=-400")
      ("vtk-every", po::value(&c.vtk_every)->default_value(c.vtk_every), "steps between VTK frames of each run (0: none)")
      ("progress-every", po::value(&c.progress_every)->default_value(c.progress_every), "wall seconds between progress lines")
      ("reuse", po::bool_switch(&c.reuse), "keep the samples and the finished runs (summary.txt with --cycles cycles) found in --output")
      ("dry-run", po::bool_switch(&c.dry_run), "print the ballast commands and stop");
  po::variables_map vm;
  try {
    po::store(po::parse_command_line(argc, argv, desc), vm);
    if (vm.count("help")) {
      std::cout << "stiffness_study — the ballast settlement for several sublayer stiffnesses, mean over samples\n"
                   "(Saussine et al. 2006, 4.2, Fig. 11); one ballast process per (sample, k factor).\n\n"
                << desc << "\n";
      return false;
    }
    po::notify(vm);
  } catch (const po::error& e) {
    throw std::invalid_argument(e.what());
  }
  if (c.samples < 1 || c.cycles < 1 || c.jobs < 1) throw std::invalid_argument("--samples, --cycles and --jobs must be >= 1");
  if (c.vtk_every < 0 || !(c.progress_every > 0)) throw std::invalid_argument("--vtk-every must be >= 0 and --progress-every > 0");
  std::stringstream ks(c.k_factors);
  for (std::string item; std::getline(ks, item, ',');) {
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || item.find_first_not_of(' ', used) != std::string::npos || !(v > 0) || !std::isfinite(v))
      throw std::invalid_argument("--k-factors: '" + item + "' is not a positive number");
    for (double k : c.k)
      if (k == v) throw std::invalid_argument("--k-factors: " + item + " is given twice");
    c.k.push_back(v);
  }
  if (c.k.empty()) throw std::invalid_argument("--k-factors is empty");
  for (const char* name : {"grading-fraction", "box-width", "pads", "sleeper-width"})
    if (vm.count(name)) c.prepare_args.insert(c.prepare_args.end(), {std::string("--") + name, vm[name].as<std::string>()});
  for (std::string& a : stiffness::ballast_option_args(ballast_options)) c.extra_args.push_back(std::move(a));
  return true;
}


// True if the file has a line "key = value" exactly.
bool has_line(const fs::path& file, const std::string& line) {
  std::ifstream in(file);
  for (std::string l; std::getline(in, l);)
    if (l == line) return true;
  return false;
}

// Step 2. The tasks: the samples first (index s), then run (s, k) waiting for sample s.
std::vector<Task> make_tasks(const Config& c, const fs::path& ballast) {
  const fs::path dir(c.output);
  std::vector<Task> tasks;
  for (int i = 0; i < c.samples; ++i) {
    const std::string s = std::to_string(c.seed + std::uint64_t(i));
    Task t;
    t.kind = Task::Kind::prepare;
    t.name = "sample_" + s;
    // --overwrite: a task that runs (not reused) replaces whatever an earlier study left in its folder
    t.argv = {ballast.string(), "--prepare-only", "true", "--seed", s, "--output", (dir / t.name).string(), "--progress-every", "10",
              "--overwrite"};
    t.argv.insert(t.argv.end(), c.prepare_args.begin(), c.prepare_args.end());
    t.argv.insert(t.argv.end(), c.extra_args.begin(), c.extra_args.end());
    t.log = dir / t.name / "log.txt";
    t.reuse = c.reuse && fs::exists(dir / t.name / "sample.nscd");
    tasks.push_back(std::move(t));
  }
  for (int i = 0; i < c.samples; ++i)
    for (double k : c.k) {
      const std::string s = std::to_string(c.seed + std::uint64_t(i));
      Task t;
      t.name = "k" + number_text(k) + "_s" + s;
      t.argv = {ballast.string(), "--sample", (dir / ("sample_" + s) / "sample.nscd").string(), "--seed", s, "--k-factor",
                number_text(k), "--cycles", std::to_string(c.cycles), "--vtk-every", std::to_string(c.vtk_every),
                "--output", (dir / t.name).string(), "--progress-every", "10", "--overwrite"};
      t.argv.insert(t.argv.end(), c.extra_args.begin(), c.extra_args.end());
      t.log = dir / t.name / "log.txt";
      t.after = i;
      t.reuse = c.reuse && has_line(dir / t.name / "summary.txt", "cycles = " + std::to_string(c.cycles));
      tasks.push_back(std::move(t));
    }
  return tasks;
}

std::string command_line(const Task& t) {
  std::string s;
  for (const std::string& a : t.argv) s += (s.empty() ? "" : " ") + a;
  return s + " > " + t.log.string() + " 2>&1";
}

// Step 4. Reduce the runs that succeeded, write the files, print the table.
bool report(const Config& c, const std::vector<Task>& tasks, const std::vector<Outcome>& out, double wall) {
  const fs::path dir(c.output);
  std::vector<KStats> stats;
  bool read_ok = true;
  for (std::size_t ki = 0; ki < c.k.size(); ++ki) {
    std::vector<Series> runs;
    for (int s = 0; s < c.samples; ++s) {
      const std::size_t i = std::size_t(c.samples) + std::size_t(s) * c.k.size() + ki;  // make_tasks' order
      if (!out[i].ok) continue;
      try {
        runs.push_back(read_cycles_csv(dir / tasks[i].name / "cycles.csv"));
      } catch (const std::exception& e) {
        std::printf("skipping %s: %s\n", tasks[i].name.c_str(), e.what());
        read_ok = false;
      }
    }
    stats.push_back(aggregate(c.k[ki], runs));
  }
  write_settlement_by_k(dir / "settlement_by_k.csv", stats);
  const bool decreasing = decreases_with_k(stats);
  int failed = 0;
  for (std::size_t i = 0; i < tasks.size(); ++i)
    if (!out[i].ok) {
      if (failed++ == 0) std::printf("\nfailed:\n");
      std::printf("  %-16s %s; log: %s\n", tasks[i].name.c_str(), out[i].why.c_str(), tasks[i].log.string().c_str());
    }

  std::ofstream sum(dir / "summary.txt");
  sum.precision(10);
  sum << "samples = " << c.samples << "\ncycles = " << c.cycles << "\nk_factors = " << stats.size() << "\ntasks = " << tasks.size()
      << "\ntasks_failed = " << failed << "\nwall_time = " << wall << "\n";
  std::printf("\nfinal settlement at the smallest load, mean over the samples (%s):\n", (dir / "settlement_by_k.csv").string().c_str());
  std::printf("  %10s  %7s  %6s  %14s  %12s\n", "k factor", "samples", "cycle", "mean (mm)", "std (mm)");
  for (const KStats& k : stats) {
    const std::string f = number_text(k.k_factor);
    if (k.mean.empty()) {
      std::printf("  %10s  %7d  no successful run\n", f.c_str(), k.samples);
      continue;
    }
    std::printf("  %10s  %7d  %6d  %14.5f  %12.5f\n", f.c_str(), k.samples, k.cycle.back(), 1e3 * k.mean.back(), 1e3 * k.stddev.back());
    sum << "final_mean_settlement_k" << f << " = " << k.mean.back() << "\nfinal_std_k" << f << " = " << k.stddev.back()
        << "\nsamples_k" << f << " = " << k.samples << "\n";
  }
  sum << "settlement_decreases_with_k = " << (decreasing ? 1 : 0) << "\n";
  if (!sum) throw std::runtime_error("cannot write " + (dir / "summary.txt").string());
  int with_runs = 0;
  for (const KStats& k : stats) with_runs += k.mean.empty() ? 0 : 1;
  if (with_runs < 2)
    std::printf("no trend to tell: fewer than two k factors have a successful run\n");
  else
    std::printf("the final mean settlement %s as k grows (the paper's Fig. 11: the stiffer the sublayer, the smaller\n"
                "the settlement)%s\n",
                decreasing ? "decreases" : "does NOT decrease",
                c.samples < 8 || c.cycles < 1000 ? "; few samples or cycles: the trend may be lost in the spread" : "");
  std::printf("%d of %zu tasks failed; %s (plot it: contrib/plots/plot_settlement.py %s)\n", failed, tasks.size(),
              (dir / "summary.txt").string().c_str(), (dir / "settlement_by_k.csv").string().c_str());
  return read_ok;
}

}  // namespace

int main(int argc, char** argv) {
  Config c;
  fs::path ballast;
  try {
    if (!parse(argc, argv, c)) return 0;
    ballast = stiffness::find_ballast(c.ballast);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stiffness_study: %s (see --help)\n", e.what());
    return 2;
  }
  try {
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<Task> tasks = make_tasks(c, ballast);
    if (c.dry_run) {
      for (const Task& t : tasks) std::printf("%s\n", command_line(t).c_str());
      return 0;
    }
    fs::create_directories(c.output);
    std::ofstream cmds(fs::path(c.output) / "commands.txt");
    for (const Task& t : tasks) cmds << command_line(t) << '\n';
    std::printf("stiffness_study: %d samples x %zu k factors, %d cycles each: %zu tasks, %d at a time; ballast: %s; output %s\n",
                c.samples, c.k.size(), c.cycles, tasks.size(), c.jobs, ballast.c_str(), c.output.c_str());
    std::fflush(stdout);
    const std::vector<Outcome> out = run_all(tasks, PoolOptions{c.jobs, c.progress_every});
    if (interrupted()) return 130;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const bool read_ok = report(c, tasks, out, wall);
    for (const Outcome& o : out)
      if (!o.ok) return 1;
    return read_ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stiffness_study: error: %s\n", e.what());
    return 1;
  }
}
