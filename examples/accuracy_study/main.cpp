// examples/accuracy_study/main.cpp — `accuracy_study`: speed against accuracy, measured
// (Saussine et al. 2006, §3.2 and §3.3; issue #10), as a plan of `ballast` runs that GNU
// parallel runs here, or a Slurm job array / several hosts run (--plan-only, then --gather).
//
// What it shows
//   criterion  study 1 (§3.2): one prepared sample under the paper's load (20 Hz, dt 2e-4), for
//              each convergence setting: the energy criterion 1.66e-3/-4/-5, strict Gauss–Seidel
//              1e-4/-5, non-strict 1e-5/-6/-7, the reference (ballast's default, non-strict
//              1.666e-4), the same with at least 100 sweeps a step, NEWTON_AC 1e-6/-8 (the
//              hybrid: 300 NLGS sweeps to Quad 1e-4 first, --newton-presweeps 0 for pure
//              Newton); and the reference on other samples for the spread between samples
//   step       study 2 (§3.3): ten step lengths 1e-4 … 1e-3 s, load vertical and inclined 5°,
//              reference setting: overlaps against time, settlement, the mean-overlap ratio
//              between the longest and the shortest step, the largest step within the spread
//   trade      study 3: both lists, and the cost per cycle against the error in one figure
//
// Build
//   cmake --build build --target accuracy_study ballast
// Run
//   build/examples/accuracy_study/accuracy_study --study criterion --output out/accuracy/criterion
//       --runs out/accuracy/runs        (the full study: days on 2 cores; see docs/studies.md §4)
//   build/examples/accuracy_study/accuracy_study --study trade --quick --output out/acc_quick
//       (every setting on a tiny sample for 2 cycles: under a minute)
//   ... --plan-only: write the plan (and Slurm scripts) only; ... --gather: the table only
//   ... --rank-against OTHER: compare this study's ranking of the settings with OTHER's (a study
//       of the same kind at another size): ranking.csv and a section of report.md
// Outputs under --output DIR
//   table.csv   one row per setting: setting,solver,policy,tol,dt,inclination,wall_seconds,
//               mean_iterations,unconverged_steps,mean_overlap,max_overlap,cumulated_overlap,
//               settlement (SI units; nan where a run failed)
//   trade.csv   the same settings: processor and wall time per cycle, overlap, settlement error
//               against the tightest setting of its family, within the sample spread (1/0)
//   runs.csv    setting,role,run: the ballast folder of each row (for the plots)
//   report.md   the table in Markdown, the spread, the findings; PNG plots (needs matplotlib:
//               contrib/plots/plot_accuracy.py; a warning, not a failure, without)
//   prepare.txt, commands.txt, manifest.csv, slurm*.sbatch, submit_slurm.sh: the plan of the
//               tasks not done yet (study_common/plan.hpp); joblog*.txt: GNU parallel's
// Runs under --runs (default DIR/runs): sample_<seed>/ (sample.nscd), one folder per setting
//   (ballast's summary.txt, cycles.csv, steps.csv, log.txt) and <folder>.args, the command
//   planned for it. A run whose .args file holds the same command and whose summary.txt says it
//   finished its cycles is not planned again: studies sharing --runs share their runs (trade
//   after criterion and step runs nothing new); a folder whose .args differs is emptied when
//   planned; one with the same .args, unfinished, is resumed (ballast --continue).
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <thread>

#include "../study_common/ballast_args.hpp"
#include "../study_common/local_run.hpp"
#include "../study_common/plan.hpp"
#include "../study_common/slurm.hpp"
#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/run_main.hpp"
#include "settings.hpp"
#include "ranking.hpp"
#include "table.hpp"

namespace fs = std::filesystem;
namespace driver = nscd::driver;
using namespace accuracy;

namespace {

struct Config {
  std::string study;
  Study which{};  ///< study, parsed
  std::string solvers = "NLGS,NEWTON_AC";
  std::vector<std::string> solver_list;  ///< solvers, parsed
  std::string output, runs, ballast;
  std::string rank_against;  ///< another finished study of the same kind, to compare rankings with
  bool quick = false, no_plot = false, dry_run = false, plan_only = false, gather = false;
  int cycles = 100, samples = 3;
  int newton_presweeps = kNewtonPresweeps;
  double newton_presweep_tol = kNewtonPresweepTol;
  std::uint64_t seed = 2006;
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  int threads = 1;
  std::vector<std::string> thread_args;  ///< --threads N for every ballast command, kept out of the runs' keys
  std::string grading_fraction_arg, box_width, pads, sleeper_width, pad_height;  ///< passed through when given
  std::vector<std::string> ballast_options;                          ///< --ballast-option KEY=VALUE, as given
  std::vector<std::string> sample_args, extra_args;
  double grading_fraction = 1.0;
};

using driver::Kind;
constexpr unsigned kSwitch = driver::kSwitch, kNoDefault = driver::kNoDefault;

const driver::OptionTable<Config> kOptions(
    "accuracy_study",
    "speed against accuracy (Saussine et al. 2006, 3.2-3.3): ballast runs for each\n"
    "convergence setting or step length, one table, a report and plots.",
    {{"study", &Config::study, "criterion (paper 3.2), step (3.3) or trade (both, cost against error)", Kind::Free, kNoDefault},
     {"output", &Config::output, "study directory: table.csv, trade.csv, report.md, PNGs", Kind::Free, kNoDefault},
     {"runs", &Config::runs, "folder of the samples and ballast runs (default OUTPUT/runs); share it between studies", Kind::Free,
      kNoDefault},
     {"quick", &Config::quick, "CI size: every setting on a tiny sample (36 grains, load / 10) for 2 cycles, 2 samples", Kind::Free,
      kSwitch},
     {"cycles", &Config::cycles, "loading cycles per run (default 100; --quick: 2)", Kind::Free, kNoDefault},
     {"samples", &Config::samples, "samples at the reference setting, for the spread (default 3; --quick: 2)", Kind::Free, kNoDefault},
     {"seed", &Config::seed, "seed of the reference sample; the others are seed+1 ..."},
     {"solvers", &Config::solvers, "the solvers whose settings the study holds: NLGS, NEWTON_AC or both, comma-separated (NEWTON_AC's rows, the hybrid, cost about 4x and 7x the reference's)"},
     {"newton-presweeps", &Config::newton_presweeps, "NEWTON_AC rows: NLGS sweeps before Newton, at most (the hybrid; 0: pure Newton)"},
     {"newton-presweep-tol", &Config::newton_presweep_tol, "NEWTON_AC rows: the NLGS sweeps stop at this Quad criterion"},
     {"jobs", &Config::jobs, "ballast processes at a time (default: the machine's cores / --threads)", Kind::Free, 0, nullptr, 'j'},
     {"threads", &Config::threads,
      "threads of each ballast run (its --threads); --jobs defaults to the cores / --threads, and jobs x threads may not pass the cores; not part of a run's key (the results do not depend on it)"},
     {"ballast", &Config::ballast, "the ballast executable (default: found next to this one)", Kind::Free, kNoDefault},
     {"grading-fraction", &Config::grading_fraction_arg, "sample preparation: scales the grain counts (e.g. 0.25)", Kind::Free,
      kNoDefault},
     {"box-width", &Config::box_width, "sample preparation (m)", Kind::Free, kNoDefault},
     {"pads", &Config::pads, "sample preparation", Kind::Free, kNoDefault},
     {"sleeper-width", &Config::sleeper_width, "sample preparation (m)", Kind::Free, kNoDefault},
     {"pad-height", &Config::pad_height, "sample preparation (m)", Kind::Free, kNoDefault},
     {"ballast-option", &Config::ballast_options, "KEY=VALUE given to every ballast command as --KEY VALUE (repeatable)"},
     {"plan-only", &Config::plan_only, "write the plan (commands, manifest, Slurm scripts) and run nothing", Kind::Free, kSwitch},
     {"gather", &Config::gather, "run nothing: make the table, report and plots from the runs there (same options as the plan)",
      Kind::Free, kSwitch},
     {"rank-against", &Config::rank_against,
      "a finished study's folder (same --study, another size): compare how both rank the settings (ranking.csv, report.md)",
      Kind::Free, kNoDefault},
     {"no-plot", &Config::no_plot, "do not draw the PNGs", Kind::Free, kSwitch},
     {"dry-run", &Config::dry_run, "print the ballast commands and stop", Kind::Free, kSwitch}});

using driver::require;

bool parse(int argc, char** argv, Config& c) {
  std::set<std::string> given;
  if (!kOptions.parse(argc, argv, c, &given)) return false;  // --help printed
  require(!c.study.empty(), "--study is required (criterion, step or trade)");
  c.which = parse_study(c.study);
  try {
    c.solver_list = parse_solvers(c.solvers);
  } catch (const std::invalid_argument& e) {
    throw driver::InputError(e.what());
  }
  require(!c.output.empty(), "--output DIR is required");
  if (c.runs.empty()) c.runs = (fs::path(c.output) / "runs").string();
  if (c.quick) {
    if (!given.count("cycles")) c.cycles = 2;
    if (!given.count("samples")) c.samples = 2;
    c.sample_args = {"--grading-fraction", "0.05", "--box-width", "0.2", "--pads", "10", "--sleeper-width", "0.06"};
    c.extra_args = {"--load-mean", "-100", "--load-amplitude", "-50"};
  }
  require(c.cycles >= 1 && c.jobs >= 1, "--cycles and --jobs must be >= 1");
  require(c.newton_presweeps >= 0 && c.newton_presweep_tol > 0,
          "--newton-presweeps must be >= 0 and --newton-presweep-tol > 0");
  require(c.samples >= 2, "--samples must be >= 2 (the spread between samples needs two)");
  require(!(c.plan_only && (c.gather || c.dry_run)), "--plan-only cannot go with --gather or --dry-run");
  if (!c.rank_against.empty()) {
    require(!c.plan_only && !c.dry_run, "--rank-against needs the study's results: not with --plan-only or --dry-run");
    for (const char* f : {"table.csv", "trade.csv"})
      require(fs::is_regular_file(fs::path(c.rank_against) / f),
              "--rank-against: " + (fs::path(c.rank_against) / f).string() + " not found (the folder of a finished study)");
  }
  if (c.quick) c.grading_fraction = 0.05;
  if (given.count("grading-fraction")) c.grading_fraction = std::atof(c.grading_fraction_arg.c_str());
  for (const char* name : study::kSampleSizeOptions)
    if (given.count(name)) {
      require(!c.quick, std::string("--") + name + " cannot go with --quick (which sets the sample)");
      c.sample_args.insert(c.sample_args.end(), {std::string("--") + name, kOptions.value_text(c, *kOptions.find(name))});
    }
  for (std::string& a : study::ballast_option_args(c.ballast_options)) c.extra_args.push_back(std::move(a));
  try {
    for (std::size_t i = 0; i < c.extra_args.size(); i += 2)
      require(c.extra_args[i] != "--threads", "give the runs' threads as --threads N, not as --ballast-option threads=N");
    study::split_machine(c.jobs, given.count("jobs") > 0, c.threads, !c.plan_only && !c.dry_run && !c.gather, c.thread_args);
  } catch (const std::invalid_argument& e) {
    throw driver::InputError(e.what());
  }
  return true;
}


std::string joined(const std::vector<std::string>& v, std::size_t from = 0) {
  std::string s;
  for (std::size_t i = from; i < v.size(); ++i) s += (s.empty() ? "" : " ") + v[i];
  return s;
}

std::string file_text(const fs::path& f) {
  std::ifstream in(f);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

bool has_line(const fs::path& file, const std::string& line) {
  std::ifstream in(file);
  for (std::string l; std::getline(in, l);)
    if (l == line) return true;
  return false;
}

// The plan: one preparation per sample, then one run per setting (needing its sample), each
// with its .args file: the command planned for its folder (a run's includes its sample's).
// A task whose .args holds the same command and whose result is there is done: left out of the
// plan. A folder whose .args differs holds another run: emptied, so that --continue never
// resumes it.
struct Planned {
  study::Plan plan;
  std::size_t tasks = 0, done = 0;
};

// The plan while it is made: the options, where the runs go, and each sample's command (part of
// its runs' keys) and whether it is prepared.
struct Planner {
  const Config& c;
  fs::path ballast, runs;
  Planned out;
  std::map<std::uint64_t, std::string> sample_args;
  std::map<std::uint64_t, bool> sample_done;

  bool claim(const study::Job& j, const std::string& args, bool finished);
  void add_samples(const std::vector<Setting>& settings);
  void add_runs(const std::vector<Setting>& order);
};

// Counts the task; true when it is done (same .args, finished), else (unless --dry-run or
// --gather) writes its .args, first emptying a folder whose .args differs.
bool Planner::claim(const study::Job& j, const std::string& args, bool finished) {
  ++out.tasks;
  const fs::path args_file = runs / (j.name + ".args");
  const bool same = file_text(args_file) == args;
  if (same && finished) {
    ++out.done;
    return true;
  }
  if (!c.dry_run && !c.gather) {
    if (!same) {
      std::error_code ec;
      fs::remove_all(j.folder, ec);
    }
    fs::create_directories(runs);
    std::ofstream(args_file) << args;
  }
  return false;
}

// One preparation per seed, in the settings' order.
void Planner::add_samples(const std::vector<Setting>& settings) {
  for (const Setting& s : settings) {
    if (sample_args.count(s.seed)) continue;
    study::Job j;
    j.name = "sample_" + std::to_string(s.seed);
    j.folder = runs / j.name;
    j.argv = {ballast.string(), "--prepare-only", "true", "--seed", std::to_string(s.seed), "--output", j.folder.string(),
              "--progress-every", "10", "--overwrite"};
    j.argv.insert(j.argv.end(), c.sample_args.begin(), c.sample_args.end());
    j.argv.insert(j.argv.end(), c.extra_args.begin(), c.extra_args.end());
    j.values = {j.name, std::to_string(s.seed)};
    sample_args[s.seed] = joined(j.argv, 1) + "\n";
    sample_done[s.seed] = claim(j, sample_args[s.seed], fs::exists(j.folder / "sample.nscd"));
    j.argv.insert(j.argv.end(), c.thread_args.begin(), c.thread_args.end());  // after the key: the same sample
    if (!sample_done[s.seed]) out.plan.prepare.push_back(std::move(j));
  }
}

// One run per folder, in `order`; a run is finished when its sample is and its summary says it
// ran the cycles to a valid result.
void Planner::add_runs(const std::vector<Setting>& order) {
  std::set<std::string> seen;
  for (const Setting& s : order) {
    study::Job j;
    j.name = run_name(s);
    if (!seen.insert(j.name).second) continue;  // two rows, one run
    j.folder = runs / j.name;
    j.needs = "sample_" + std::to_string(s.seed);
    j.cycles = c.cycles;
    j.append_log = true;
    j.argv = {ballast.string(), "--sample", (runs / j.needs / "sample.nscd").string()};
    for (const std::string& a : run_arguments(s)) j.argv.push_back(a);
    j.argv.insert(j.argv.end(), {"--cycles", std::to_string(c.cycles), "--vtk-every", "0", "--checkpoint-every", "0", "--output",
                                 j.folder.string(), "--progress-every", "10", "--continue"});
    j.argv.insert(j.argv.end(), c.extra_args.begin(), c.extra_args.end());
    j.values = {j.name, std::to_string(s.seed)};
    const fs::path summary = j.folder / "summary.txt";
    const bool finished = sample_done.at(s.seed) && has_line(summary, "cycles = " + std::to_string(c.cycles)) &&
                          has_line(summary, "result = valid");
    const bool done = claim(j, joined(j.argv, 1) + "\nsample: " + sample_args.at(s.seed), finished);
    j.argv.insert(j.argv.end(), c.thread_args.begin(), c.thread_args.end());  // after the key: the same run
    if (!done) out.plan.runs.push_back(std::move(j));
  }
}

// The spread runs first (cheap, and every comparison needs them), then the NEWTON_AC runs
// (each costs 10-100 NLGS runs: started early, they do not finish alone at the end while the
// other cores idle), then the list's order.
std::vector<Setting> run_order(const std::vector<Setting>& settings) {
  std::vector<Setting> order;
  for (const Setting& s : settings)
    if (s.role == Role::spread) order.push_back(s);
  for (const Setting& s : settings)
    if (s.role != Role::spread && s.solver == "NEWTON_AC") order.push_back(s);
  for (const Setting& s : settings)
    if (s.role != Role::spread && s.solver != "NEWTON_AC") order.push_back(s);
  return order;
}

Planned make_plan(const Config& c, const fs::path& ballast, const std::vector<Setting>& settings) {
  Planner planner{c, ballast, fs::absolute(c.runs).lexically_normal(), {}, {}, {}};
  study::Plan& p = planner.out.plan;
  p.dir = fs::absolute(c.output).lexically_normal();
  p.threads = c.threads;
  p.study = "accuracy_study";
  p.columns = {"setting_folder", "seed"};
  for (int n : {361, 242, 121})
    p.grains += std::max(1, static_cast<int>(std::lround(c.grading_fraction * n)));  // shared/ballast.cpp
  planner.add_samples(settings);
  planner.add_runs(run_order(settings));
  return std::move(planner.out);
}

// The PNGs: contrib/plots/plot_accuracy.py by the first python3 that has matplotlib.
std::string plot(const Config& c) {
  const fs::path script = fs::path(NSCD_SOURCE_DIR) / "contrib/plots/plot_accuracy.py";
  std::string python;
  for (const char* candidate : {"/usr/bin/python3", "python3"})
    if (std::system((std::string(candidate) + " -c 'import matplotlib' >/dev/null 2>&1").c_str()) == 0) {
      python = candidate;
      break;
    }
  const std::string by_hand = script.string() + " " + c.output;
  if (python.empty()) {
    std::printf("WARNING: no python3 with matplotlib: no PNG drawn (Debian: apt-get install python3-matplotlib; then run %s)\n",
                by_hand.c_str());
    return "No PNG: no python3 with matplotlib when the study ran (draw them with `" + by_hand + "`).";
  }
  std::fflush(stdout);
  if (std::system((python + " '" + script.string() + "' '" + c.output + "' --study " + c.study).c_str()) != 0) {
    std::printf("WARNING: %s failed: no PNG\n", script.string().c_str());
    return "No PNG: the plot script failed.";
  }
  return "Plots: the PNG files next to this report (contrib/plots/plot_accuracy.py).";
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, cc;
  in >> a >> b >> cc;
  return a.empty() ? "unknown" : a + " " + b + " " + cc;
}

// The settings of the study and solvers asked for, NEWTON_AC's with the hybrid's options.
std::vector<Setting> study_settings(const Config& c) {
  std::vector<Setting> settings = keep_solvers(settings_of(c.which, c.seed, c.samples), c.solver_list);
  for (Setting& s : settings)
    if (s.solver == "NEWTON_AC") {
      s.newton_presweeps = c.newton_presweeps;
      s.newton_presweep_tol = c.newton_presweep_tol;
    }
  return settings;
}

// Writes the plan and the Slurm scripts, then runs it with GNU parallel (not with --plan-only):
// the exit status when the study stops here, nullopt when the table is to be made.
std::optional<int> carry_out(const Config& c, const Planned& planned, std::size_t settings) {
  const study::Plan& plan = planned.plan;
  study::write_plan(plan);
  study::write_slurm(plan, study::measured_cost_model());
  std::printf(
      "accuracy_study: study %s, %zu settings, %d cycles each: %zu tasks (%d already done), %d at a time; runs in %s\n",
      c.study.c_str(), settings, c.cycles, planned.tasks, static_cast<int>(planned.done), c.jobs, c.runs.c_str());
  if (c.plan_only) {
    std::printf(
        "plan: %s/prepare.txt then commands.txt (manifest.csv); on Slurm: %s/submit_slurm.sh;\n"
        "then the same accuracy_study command with --gather instead of --plan-only\n",
        plan.dir.c_str(), plan.dir.c_str());
    return driver::kExitOk;
  }
  if (study::run_with_parallel(plan.dir, c.jobs) == study::LocalResult::interrupted) {
    std::printf("accuracy_study: interrupted; run the same command again to go on\n");
    return driver::kExitInterrupted;
  }
  return std::nullopt;
}

// The rows from the runs' summaries, written as table.csv, trade.csv and runs.csv.
std::vector<Row> write_tables(const Config& c, const std::vector<Setting>& settings, const fs::path& dir) {
  std::vector<Row> rows;
  for (const Setting& s : settings)
    rows.push_back(read_row(s, fs::path(c.runs) / run_name(s) / "summary.txt", c.cycles));
  fs::create_directories(dir);  // --gather into a new folder
  write_table(dir / "table.csv", rows);
  write_trade(dir / "trade.csv", rows, sample_spread(rows));
  std::ofstream runs_csv(dir / "runs.csv");
  runs_csv << "setting,role,run\n";
  for (const Setting& s : settings)
    runs_csv << s.label << ',' << role_name(s.role) << ',' << fs::absolute(fs::path(c.runs) / run_name(s)).string()
             << '\n';
  return rows;
}

// The report's run size: grains (from the first run that finished), cycles, samples, options, and
// the machine it ran on (cores, load, wall time).
std::string run_size(const Config& c, const std::vector<Row>& rows, const std::string& load0, double wall,
                     std::size_t reused) {
  std::string grains = "?";
  for (const Row& r : rows)
    if (r.ok) {
      grains = read_summary(fs::path(c.runs) / run_name(r.setting) / "summary.txt")["grains"];
      break;
    }
  return std::string("**Run size:** ") + (c.quick ? "--quick (CI size, not a result): " : "") + grains + " grains, " +
         std::to_string(c.cycles) + " cycles per run, " + std::to_string(c.samples) +
         " samples for the spread; solvers: " + c.solvers +
         "; sample options: " + (c.sample_args.empty() ? "the paper's" : joined(c.sample_args)) +
         (c.extra_args.empty() ? "" : "; ballast options: " + joined(c.extra_args)) + ". **Machine:** " +
         std::to_string(std::thread::hardware_concurrency()) + " cores, " + std::to_string(c.jobs) +
         " runs at a time, load average " + load0 + " at the start and " + load_average() +
         " at the end; this study's wall time " + std::to_string(int(wall)) + " s (" + std::to_string(reused) +
         " tasks reused).";
}

// --rank-against: ranking.csv, a section of report.md, and a line on how far the rankings agree.
void rank_against(const Config& c, const std::vector<Setting>& settings, const fs::path& dir) {
  const RankComparison cmp = compare_rankings(settings, read_study(dir), read_study(c.rank_against));
  write_ranking(dir / "ranking.csv", cmp);
  std::ofstream(dir / "report.md", std::ios::app) << "\n" << ranking_section(cmp, "`" + c.rank_against + "`");
  double worst = std::nan("");  // the lowest finite correlation (NaN: none defined)
  for (const RankAgreement& a : cmp.agreements)
    if (std::isfinite(a.spearman) && !(worst <= a.spearman)) worst = a.spearman;
  std::printf(
      "accuracy_study: ranking against %s: %zu group x measure comparisons, lowest Spearman %.3f; %d of %zu "
      "within-spread verdicts the same; %s\n",
      c.rank_against.c_str(), cmp.agreements.size(), worst, cmp.verdicts_same(), cmp.verdicts.size(),
      (dir / "ranking.csv").string().c_str());
}

// Names each missing row and sums up; the exit status: a run error when a row is missing.
int report_rows(const std::vector<Row>& rows, const fs::path& dir) {
  int failed = 0;
  for (const Row& r : rows)
    if (!r.ok) {
      std::printf("missing row: %s: %s\n", r.setting.label.c_str(), r.why.c_str());
      ++failed;
    }
  std::printf("accuracy_study: %zu rows, %d missing; %s, %s\n", rows.size(), failed, (dir / "table.csv").string().c_str(),
              (dir / "report.md").string().c_str());
  return failed == 0 ? driver::kExitOk : driver::kExitRunError;
}

// The study: find ballast (bad input while it is not found), plan the runs not done yet, run
// them with GNU parallel (unless --plan-only, --gather or --dry-run), then the table and report.
int run(const Config& c) {
  const fs::path ballast = study::find_ballast(c.ballast);
  driver::input_accepted();  // from here an error is the run's (exit 1)
  const auto t0 = std::chrono::steady_clock::now();
  const std::string load0 = load_average();
  const std::vector<Setting> settings = study_settings(c);
  const Planned planned = make_plan(c, ballast, settings);
  const study::Plan& plan = planned.plan;
  if (c.dry_run) {
    for (const auto* phase : {&plan.prepare, &plan.runs})
      for (const study::Job& j : *phase) std::printf("%s\n", study::command_line(j).c_str());
    std::printf("(%zu tasks already done: not listed)\n", planned.done);
    return driver::kExitOk;
  }
  if (!c.gather)
    if (const std::optional<int> status = carry_out(c, planned, settings.size())) return *status;
  if (fs::exists(plan.dir / "manifest.csv"))
    study::report_tasks(study::check_tasks(plan.dir, study::read_manifest(plan.dir)));
  const fs::path dir(c.output);
  const std::vector<Row> rows = write_tables(c, settings, dir);
  const std::string note = c.no_plot ? "" : plot(c);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_report(dir / "report.md", c.which, rows, run_size(c, rows, load0, wall, planned.done), note);
  if (!c.rank_against.empty()) rank_against(c, settings, dir);
  return report_rows(rows, dir);
}

}  // namespace

int main(int argc, char** argv) { return driver::run_main("accuracy_study", argc, argv, Config{}, parse, run); }
