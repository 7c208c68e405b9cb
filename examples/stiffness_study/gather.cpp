// examples/stiffness_study/gather.cpp — step 3 of the stiffness study: the runs listed in the
// plan's manifest.csv, wherever they ran, reduced to the mean settlement per k factor
// (settlement_table.hpp); a task not done is reported by name and, without --allow-missing,
// nothing is averaged.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <stdexcept>

#include "settlement_table.hpp"
#include "study_config.hpp"

namespace fs = std::filesystem;

namespace stiffness {

namespace {

using TaskStates = std::vector<std::pair<std::string, study::TaskState>>;

// The k factors in the plan's order, the samples, the planned cycles.
struct PlanShape {
  std::vector<std::string> k_names;
  std::set<std::string> seeds;
  int cycles = 0;
};

PlanShape plan_shape(const std::vector<study::ManifestRow>& rows) {
  PlanShape plan;
  for (const study::ManifestRow& r : rows) {
    if (!r.is_run()) continue;
    bool seen = false;
    for (const std::string& k : plan.k_names) seen = seen || k == r.at("k_factor");
    if (!seen) plan.k_names.push_back(r.at("k_factor"));
    plan.seeds.insert(r.at("seed"));
    plan.cycles = std::max(plan.cycles, std::atoi(r.at("cycles").c_str()));
  }
  return plan;
}

// The finished runs of each k factor, cut to their planned cycles, averaged; a cycles.csv that
// cannot be read is skipped and clears read_ok.
std::vector<KStats> settlement_stats(const std::vector<study::ManifestRow>& rows, const TaskStates& states,
                                     const std::vector<std::string>& k_names, bool& read_ok) {
  std::vector<KStats> stats;
  for (const std::string& kn : k_names) {
    std::vector<Series> runs;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (!rows[i].is_run() || rows[i].at("k_factor") != kn || states[i].second.kind != study::TaskState::ok) continue;
      try {
        Series s = read_cycles_csv(fs::path(rows[i].at("output")) / "cycles.csv");
        const std::size_t planned = static_cast<std::size_t>(std::atoi(rows[i].at("cycles").c_str()));
        if (s.cycle.size() > planned) s.cycle.resize(planned), s.settlement.resize(planned);
        runs.push_back(std::move(s));
      } catch (const std::exception& e) {
        std::printf("skipping %s: %s\n", rows[i].at("name").c_str(), e.what());
        read_ok = false;
      }
    }
    stats.push_back(aggregate(std::strtod(kn.c_str(), nullptr), runs));
  }
  return stats;
}

// The final settlement per k factor: a table on stdout, the same numbers in summary.txt.
void report_settlement(const fs::path& dir, std::ofstream& sum, const std::vector<KStats>& stats) {
  std::printf("\nfinal settlement at the smallest load, mean over the samples (%s):\n", (dir / "settlement_by_k.csv").c_str());
  std::printf("  %10s  %7s  %6s  %14s  %12s\n", "k factor", "samples", "cycle", "mean (mm)", "std (mm)");
  for (const KStats& k : stats) {
    const std::string f = number_text(k.k_factor);
    sum << "samples_k" << f << " = " << k.samples << "\n";
    if (k.mean.empty()) {
      std::printf("  %10s  %7d  no finished run\n", f.c_str(), k.samples);
      continue;
    }
    std::printf("  %10s  %7d  %6d  %14.5f  %12.5f\n", f.c_str(), k.samples, k.cycle.back(), 1e3 * k.mean.back(), 1e3 * k.stddev.back());
    sum << "final_mean_settlement_k" << f << " = " << k.mean.back() << "\nfinal_std_k" << f << " = " << k.stddev.back() << "\n";
  }
}

// The trend over k needs a finished run for at least two k factors.
void print_trend(const std::vector<KStats>& stats, bool decreasing, const PlanShape& plan) {
  int with_runs = 0;
  for (const KStats& k : stats) with_runs += k.mean.empty() ? 0 : 1;
  if (with_runs < 2)
    std::printf("no trend to tell: fewer than two k factors have a finished run\n");
  else
    std::printf(
        "the final mean settlement %s as k grows (the paper's Fig. 11: the stiffer the sublayer, the smaller\n"
        "the settlement)%s\n",
        decreasing ? "decreases" : "does NOT decrease",
        plan.seeds.size() < 8 || plan.cycles < 1000 ? "; few samples or cycles: the trend may be lost in the spread"
                                                    : "");
}

}  // namespace

int gather(const fs::path& dir, bool allow_missing, double wall) {
  const std::vector<study::ManifestRow> rows = study::read_manifest(dir);
  const auto states = study::check_tasks(dir, rows);
  const int not_done = study::report_tasks(states);
  const PlanShape plan = plan_shape(rows);
  std::ofstream sum(dir / "summary.txt", std::ios::trunc);
  sum.precision(10);
  sum << "samples = " << plan.seeds.size() << "\ncycles = " << plan.cycles << "\nk_factors = " << plan.k_names.size()
      << "\ntasks = " << rows.size() << "\ntasks_failed = " << not_done << "\n";
  if (wall >= 0) sum << "wall_time = " << wall << "\n";
  if (not_done > 0 && !allow_missing) {
    fs::remove(dir / "settlement_by_k.csv");
    sum << "gathered = 0\n";
    std::printf(
        "\nnot gathered: %d tasks not done. Run the study again (it resumes), or gather what is there with\n"
        "  stiffness_study --gather %s --allow-missing\n",
        not_done, dir.c_str());
    return 1;
  }

  bool read_ok = true;
  const std::vector<KStats> stats = settlement_stats(rows, states, plan.k_names, read_ok);
  write_settlement_by_k(dir / "settlement_by_k.csv", stats);
  const bool decreasing = decreases_with_k(stats);
  sum << "gathered = 1\n";
  if (not_done > 0)
    sum << "allow_missing = 1\nnote = averaged over the runs that finished only: " << not_done << " tasks not done\n";
  report_settlement(dir, sum, stats);
  sum << "settlement_decreases_with_k = " << (decreasing ? 1 : 0) << "\n";
  if (!sum) throw std::runtime_error("cannot write " + (dir / "summary.txt").string());
  print_trend(stats, decreasing, plan);
  if (not_done > 0)
    std::printf("WARNING --allow-missing: averaged over the runs that finished only (%d tasks not done; summary.txt says so)\n", not_done);
  std::printf("%d of %zu tasks not done; %s (plot it: contrib/plots/plot_settlement.py %s)\n", not_done, rows.size(),
              (dir / "summary.txt").c_str(), (dir / "settlement_by_k.csv").c_str());
  return read_ok ? 0 : 1;
}

}  // namespace stiffness
