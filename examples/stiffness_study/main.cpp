// examples/stiffness_study/main.cpp — `stiffness_study`: the influence of the sublayer
// stiffness on the ballast settlement (Saussine et al. 2006, §4.2, Fig. 11), as a batch of
// `ballast` runs that GNU parallel or a Slurm job array runs (issue #11).
//
// What it shows
//   Eight samples that differ only by the grain dispositions before the deposit (seeds
//   s0 … s0+7), each loaded for N cycles on a sublayer whose springs are k_N = 4100 N/m × 1,
//   × 100 and × 1000. The mean settlement over the samples, cycle by cycle, for each stiffness:
//   the paper finds that the stiffer the sublayer, the smaller the settlement.
//
// Build
//   cmake -S . -B build && cmake --build build --target stiffness_study ballast
// Run (docs/studies.md §2)
//   build/examples/stiffness_study/stiffness_study --samples 2 --cycles 10 --grading-fraction 0.25
//       --box-width 0.5 --pads 25 --sleeper-width 0.1 --jobs 2     (here, with GNU parallel)
//   build/examples/stiffness_study/stiffness_study --plan-only --output DIR   (plan only: for
//       Slurm (DIR/submit_slurm.sh), GNU parallel on several hosts, or by hand)
//   build/examples/stiffness_study/stiffness_study --gather DIR   (the table, once the runs ended)
// Outputs under --output DIR (default out/stiffness_study)
//   prepare.txt, commands.txt, manifest.csv   the plan (study_common/plan.hpp)
//   slurm_prepare.sbatch, slurm.sbatch, submit_slurm.sh, slurm/   the Slurm job arrays
//   joblog_prepare.txt, joblog.txt   GNU parallel's joblogs (local runs)
//   sample_S/            the prepared sample of seed S (sample.nscd) and its log.txt
//   k<F>_s<S>/           the run of sample S with stiffness × F: ballast's files and log.txt
//   settlement_by_k.csv  cycle, then mean_k<F>, std_k<F> (m) for each k factor
//   summary.txt          key = value: final_mean_settlement_k<F>, final_std_k<F> (m), ...
//
// Steps
//   1. the plan: prepare each sample once (`ballast --prepare-only true --seed S ...`), then one
//      run per (sample, k factor) (`ballast --sample ... --k-factor F --cycles N --continue ...`)
//   2. unless --plan-only: GNU parallel runs prepare.txt, then commands.txt (local_run.hpp)
//   3. gather (gather.cpp): every task's state from its files, the table, the trend
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "../study_common/ballast_args.hpp"
#include "../study_common/local_run.hpp"
#include "../study_common/slurm.hpp"
#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/run_main.hpp"
#include "settlement_table.hpp"
#include "study_config.hpp"

namespace fs = std::filesystem;
namespace driver = nscd::driver;

namespace stiffness {

namespace {
using driver::Kind;
constexpr unsigned kSwitch = driver::kSwitch, kNoDefault = driver::kNoDefault;

const driver::OptionTable<Config> kOptions(
    "stiffness_study",
    "the ballast settlement for several sublayer stiffnesses, mean over samples\n"
    "(Saussine et al. 2006, 4.2, Fig. 11); one ballast run per (sample, k factor), run by GNU parallel\n"
    "here, or planned for Slurm / several hosts with --plan-only, then gathered (docs/studies.md 2).",
    {{"samples", &Config::samples, "number of samples M (the paper: 8)"},
     {"seed", &Config::seed, "seed of the first sample; the others are seed+1 ... seed+M-1"},
     {"k-factors", &Config::k_factors, "sublayer stiffness factors, comma-separated (paper 4.2: 1,100,1000)"},
     {"cycles", &Config::cycles, "loading cycles per run (the paper: 3000)"},
     {"jobs", &Config::jobs, "ballast processes at a time (GNU parallel -j; default: the machine's cores / --threads)", Kind::Free, 0, nullptr, 'j'},
     {"threads", &Config::threads,
      "threads of each ballast run (its --threads); --jobs defaults to the cores / --threads, and jobs x threads may not pass the cores"},
     {"ballast", &Config::ballast, "the ballast executable (default: found next to this one)", Kind::Free, kNoDefault},
     {"output", &Config::output, "study directory (the plan, the runs, the table)"},
     {"plan-only", &Config::plan_only, "write the plan (commands, manifest, Slurm scripts) and run nothing", Kind::Free, kSwitch},
     {"gather", &Config::gather, "only gather the runs of the plan in this study directory into the table", Kind::Free, kNoDefault},
     {"allow-missing", &Config::allow_missing, "gather: average over the runs that finished when some did not (said in summary.txt)",
      Kind::Free, kSwitch},
     {"fresh", &Config::fresh, "delete the joblogs and the runs of the plan found in --output first (start the study again)", Kind::Free,
      kSwitch},
     {"grading-fraction", &Config::grading_fraction_arg, "passed to the sample preparation (smaller sample, e.g. 0.25)", Kind::Free,
      kNoDefault},
     {"box-width", &Config::box_width, "passed to the sample preparation (m)", Kind::Free, kNoDefault},
     {"pads", &Config::pads, "passed to the sample preparation", Kind::Free, kNoDefault},
     {"sleeper-width", &Config::sleeper_width, "passed to the sample preparation (m)", Kind::Free, kNoDefault},
     {"pad-height", &Config::pad_height, "passed to the sample preparation (m)", Kind::Free, kNoDefault},
     {"ballast-option", &Config::ballast_options,
      "KEY=VALUE given to every ballast command as --KEY VALUE (repeatable), e.g. load-amplitude=-400"},
     {"vtk-every", &Config::vtk_every, "steps between VTK frames of each run (0: none)"},
     {"dry-run", &Config::dry_run, "print the plan's commands and stop (writes nothing)", Kind::Free, kSwitch}});

using driver::require;
}  // namespace

bool parse(int argc, char** argv, Config& c) {
  std::set<std::string> given;
  if (!kOptions.parse(argc, argv, c, &given)) return false;  // --help printed
  require(c.gather.empty() || !(c.plan_only || c.dry_run || c.fresh),
          "--gather DIR reads a finished plan: it cannot go with --plan-only, --dry-run or --fresh");
  require(!(c.allow_missing && c.plan_only), "--allow-missing is for the gathering, not --plan-only");
  require(c.samples >= 1 && c.cycles >= 1 && c.jobs >= 1, "--samples, --cycles and --jobs must be >= 1");
  require(c.vtk_every >= 0, "--vtk-every must be >= 0");
  std::stringstream ks(c.k_factors);
  for (std::string item; std::getline(ks, item, ',');) {
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    require(used != 0 && item.find_first_not_of(' ', used) == std::string::npos && v > 0 && std::isfinite(v),
            "--k-factors: '" + item + "' is not a positive number");
    for (double k : c.k) require(k != v, "--k-factors: " + item + " is given twice");
    c.k.push_back(v);
  }
  require(!c.k.empty(), "--k-factors is empty");
  for (const char* name : study::kSampleSizeOptions)
    if (given.count(name))
      c.prepare_args.insert(c.prepare_args.end(), {std::string("--") + name, kOptions.value_text(c, *kOptions.find(name))});
  if (given.count("grading-fraction")) c.grading_fraction = std::atof(c.grading_fraction_arg.c_str());
  c.extra_args = study::ballast_option_args(c.ballast_options);
  study::split_machine(c.jobs, given.count("jobs") > 0, c.threads, !c.plan_only && !c.dry_run && c.gather.empty(), c.extra_args);
  // the steps per cycle for the cost model (ballast checks the values themselves)
  double dt = 2e-4, f = 20.0;
  for (std::size_t i = 0; i + 1 < c.extra_args.size(); i += 2) {
    if (c.extra_args[i] == "--dt") dt = std::atof(c.extra_args[i + 1].c_str());
    if (c.extra_args[i] == "--frequency") f = std::atof(c.extra_args[i + 1].c_str());
  }
  if (dt > 0 && f > 0) c.steps_per_cycle = std::max(1, static_cast<int>(std::lround(1.0 / (f * dt))));
  return true;
}

study::Plan make_plan(const Config& c, const fs::path& ballast) {
  study::Plan p;
  p.dir = fs::absolute(c.output).lexically_normal();
  p.threads = c.threads;
  p.study = "stiffness_study";
  p.columns = {"seed", "k_factor", "settings"};  // settings: the sample and ballast options given
  const auto joined = [](const std::vector<std::string>& a, const std::vector<std::string>& b) {
    std::string s;
    for (const auto* v : {&a, &b})
      for (const std::string& x : *v) s += (s.empty() ? "" : " ") + x;
    return s;
  };
  p.steps_per_cycle = c.steps_per_cycle;
  for (int n : {361, 242, 121}) p.grains += std::max(1, static_cast<int>(std::lround(c.grading_fraction * n)));  // shared/ballast.cpp
  for (int i = 0; i < c.samples; ++i) {
    const std::string s = std::to_string(c.seed + std::uint64_t(i));
    study::Job j;
    j.name = "sample_" + s;
    j.folder = p.dir / j.name;
    // --overwrite: a preparation that runs replaces whatever an earlier attempt left in its folder
    j.argv = {ballast.string(), "--prepare-only", "true", "--seed", s, "--output", j.folder.string(), "--progress-every", "10", "--overwrite"};
    j.argv.insert(j.argv.end(), c.prepare_args.begin(), c.prepare_args.end());
    j.argv.insert(j.argv.end(), c.extra_args.begin(), c.extra_args.end());
    j.values = {s, "", joined(c.prepare_args, c.extra_args)};
    p.prepare.push_back(std::move(j));
  }
  for (int i = 0; i < c.samples; ++i)
    for (double k : c.k) {
      const std::string s = std::to_string(c.seed + std::uint64_t(i));
      study::Job j;
      j.name = "k" + number_text(k) + "_s" + s;
      j.folder = p.dir / j.name;
      j.needs = "sample_" + s;
      j.cycles = c.cycles;
      j.append_log = true;
      // --continue: a run rerun (GNU parallel --resume-failed, a requeued Slurm task) resumes
      // from its checkpoint, and one already finished returns at once
      j.argv = {ballast.string(), "--sample", (p.dir / j.needs / "sample.nscd").string(), "--seed", s, "--k-factor", number_text(k),
                "--cycles", std::to_string(c.cycles), "--vtk-every", std::to_string(c.vtk_every), "--output", j.folder.string(),
                "--progress-every", "10", "--continue"};
      j.argv.insert(j.argv.end(), c.extra_args.begin(), c.extra_args.end());
      j.values = {s, number_text(k), joined({}, c.extra_args)};
      p.runs.push_back(std::move(j));
    }
  return p;
}

}  // namespace stiffness

namespace {

using namespace stiffness;

std::string file_text(const fs::path& f) {
  std::ifstream in(f);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A study directory holds one plan: a different one there is refused (its joblogs would skip
// tasks by position and its runs would be resumed), unless --fresh deletes what it ran.
void claim_study_dir(const Config& c, const study::Plan& p) {
  std::string planned;
  for (const study::Job& j : p.prepare) planned += study::command_line(j) + "\n";
  std::string planned_runs;
  for (const study::Job& j : p.runs) planned_runs += study::command_line(j) + "\n";
  const bool other = (fs::exists(p.dir / "prepare.txt") && file_text(p.dir / "prepare.txt") != planned) ||
                     (fs::exists(p.dir / "commands.txt") && file_text(p.dir / "commands.txt") != planned_runs);
  if (c.fresh) {
    std::error_code ec;
    for (const char* f : {"joblog_prepare.txt", "joblog.txt", "settlement_by_k.csv", "summary.txt"}) fs::remove(p.dir / f, ec);
    for (const auto* phase : {&p.prepare, &p.runs})
      for (const study::Job& j : *phase) fs::remove_all(j.folder, ec);
  } else if (other) {
    throw std::invalid_argument("the study folder " + p.dir.string() + " holds another plan (its prepare.txt or commands.txt differs): "
                                "give another --output, or --fresh to delete its runs and start again");
  }
}

// The study: find ballast (bad input while it is not found), then gather only, print the
// plan (--dry-run), or write it, run it with GNU parallel (unless --plan-only) and gather.
int run(const Config& c) {
  const fs::path ballast = c.gather.empty() ? study::find_ballast(c.ballast) : fs::path();
  driver::input_accepted();  // from here an error is the run's (exit 1)
  if (!c.gather.empty()) return gather(fs::absolute(c.gather).lexically_normal(), c.allow_missing, -1.0);
  const auto t0 = std::chrono::steady_clock::now();
  const study::Plan plan = make_plan(c, ballast);
  if (c.dry_run) {
    for (const auto* phase : {&plan.prepare, &plan.runs})
      for (const study::Job& j : *phase) std::printf("%s\n", study::command_line(j).c_str());
    return driver::kExitOk;
  }
  try {
    claim_study_dir(c, plan);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "stiffness_study: %s\n", e.what());
    return driver::kExitBadInput;
  }
  study::write_plan(plan);
  study::write_slurm(plan, study::measured_cost_model());
  const std::string d = plan.dir.string();
  std::printf("stiffness_study: %d samples x %zu k factors, %d cycles each: %zu preparations, %zu runs; ballast: %s\n"
              "plan: %s/prepare.txt, commands.txt, manifest.csv, slurm.sbatch\n",
              c.samples, c.k.size(), c.cycles, plan.prepare.size(), plan.runs.size(), ballast.c_str(), d.c_str());
  if (c.plan_only) {
    std::printf("run it here:  parallel --joblog %s/joblog_prepare.txt --resume-failed -j %d :::: %s/prepare.txt &&\n"
                "              parallel --joblog %s/joblog.txt --resume-failed -j %d :::: %s/commands.txt\n"
                "on Slurm:     %s/submit_slurm.sh\n"
                "then:         stiffness_study --gather %s\n",
                d.c_str(), c.jobs, d.c_str(), d.c_str(), c.jobs, d.c_str(), d.c_str(), d.c_str());
    return driver::kExitOk;
  }
  if (study::run_with_parallel(plan.dir, c.jobs) == study::LocalResult::interrupted) {
    std::printf("stiffness_study: interrupted; the running ballast runs were stopped with a checkpoint at the end of their cycle.\n"
                "Run the same command again to go on (GNU parallel --resume-failed, ballast --continue).\n");
    return driver::kExitInterrupted;
  }
  return gather(plan.dir, c.allow_missing, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

}  // namespace

int main(int argc, char** argv) {
  Config c;
  c.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));  // the default shown by --help
  return driver::run_main("stiffness_study", argc, argv, c, stiffness::parse, run);
}
