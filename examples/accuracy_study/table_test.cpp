// examples/accuracy_study/table_test.cpp — the accuracy study's settings and reduction on
// hand-made rows: the lists (every setting of the issue, one run per setting), reading a summary,
// the spread, the error reference, the overlap ratio and the largest step within the spread.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <unistd.h>

#include "settings.hpp"
#include "table.hpp"

using namespace accuracy;
namespace fs = std::filesystem;

namespace {

Row row(Setting s, double settlement, double mean_overlap = 1e-5, double cpu = 1.0) {
  Row r;
  r.setting = s;
  r.ok = true;
  r.cycles = 10;
  r.settlement = settlement;
  r.mean_overlap = mean_overlap;
  r.cpu_per_cycle = cpu;
  return r;
}

Setting step(double dt, double inclination) {
  Setting s = reference_setting(2006);
  s.role = Role::step;
  s.dt = dt;
  s.inclination = inclination;
  return s;
}

}  // namespace

TEST(AccuracySettings, StudiesHoldEverySettingOfTheIssueOnce) {
  const auto crit = settings_of(Study::criterion, 2006, 3);
  ASSERT_EQ(crit.size(), 14u);  // 3 energy, 2 strict, 3 non-strict, reference, minimum sweeps, 2 Newton, 2 samples
  std::set<std::string> labels, runs;
  int newton = 0, min_sweeps = 0, spread = 0;
  for (const Setting& s : crit) {
    labels.insert(s.label);
    runs.insert(run_name(s));
    newton += s.solver == "NEWTON_AC";
    min_sweeps += s.min_sweeps > 0;
    spread += s.role == Role::spread;
    EXPECT_EQ(s.dt, 2e-4);
    EXPECT_EQ(s.label.find(','), std::string::npos) << s.label;
  }
  EXPECT_EQ(labels.size(), crit.size());
  EXPECT_EQ(runs.size(), crit.size());
  EXPECT_EQ(newton, 2);
  EXPECT_EQ(min_sweeps, 1);
  EXPECT_EQ(spread, 2);
  EXPECT_TRUE(labels.count("Energy 1.66e-5") && labels.count("Strict 1e-4") && labels.count("NonStrict 1e-7"));

  const auto st = settings_of(Study::step, 2006, 3);
  ASSERT_EQ(st.size(), 22u);  // 10 steps x 2 inclinations, 2 samples
  // every step a whole number of steps per 20 Hz cycle, 1e-4 ... 1e-3
  ASSERT_EQ(step_lengths().size(), 10u);
  EXPECT_EQ(step_lengths().front(), 1e-4);
  EXPECT_EQ(step_lengths().back(), 1e-3);
  for (double dt : step_lengths()) {
    const double n = 1.0 / (20.0 * dt);
    EXPECT_NEAR(n, std::round(n), 1e-9 * n) << dt;
  }
  // trade: the union, study 2's dt 2e-4 vertical run being study 1's reference run
  const auto tr = settings_of(Study::trade, 2006, 3);
  EXPECT_EQ(tr.size(), 14u + 19u);
  std::set<std::string> trade_runs;
  for (const Setting& s : tr) EXPECT_TRUE(trade_runs.insert(run_name(s)).second) << run_name(s);
  EXPECT_THROW(settings_of(Study::criterion, 2006, 0), std::invalid_argument);
  EXPECT_THROW(parse_study("fast"), std::invalid_argument);
}

TEST(AccuracySettings, SolversKeepTheirRowsOnly) {
  EXPECT_EQ(parse_solvers("NLGS"), std::vector<std::string>{"NLGS"});
  EXPECT_EQ(parse_solvers("NEWTON_AC,NLGS"), (std::vector<std::string>{"NEWTON_AC", "NLGS"}));
  EXPECT_THROW(parse_solvers(""), std::invalid_argument);
  EXPECT_THROW(parse_solvers("NLGS,"), std::invalid_argument);
  EXPECT_THROW(parse_solvers("GS"), std::invalid_argument);
  EXPECT_THROW(parse_solvers("NLGS,NLGS"), std::invalid_argument);
  const auto all = settings_of(Study::criterion, 2006, 3);
  const auto nlgs_only = keep_solvers(all, parse_solvers("NLGS"));
  const auto newton_only = keep_solvers(all, parse_solvers("NEWTON_AC"));
  EXPECT_EQ(nlgs_only.size(), all.size() - 2u);  // NEWTON_AC 1e-6 and 1e-8 left out
  for (const Setting& s : nlgs_only) EXPECT_EQ(s.solver, "NLGS") << s.label;
  EXPECT_EQ(keep_solvers(all, parse_solvers("NLGS,NEWTON_AC")).size(), all.size());
  EXPECT_EQ(nlgs_only.front().label, all.front().label);  // the order kept
  // NEWTON_AC only: the reference and the spread rows stay (3 samples), and study 2 keeps all
  EXPECT_EQ(newton_only.size(), 2u + 3u);
  const auto step_rows = settings_of(Study::step, 2006, 3);
  EXPECT_EQ(keep_solvers(step_rows, parse_solvers("NEWTON_AC")).size(), step_rows.size());
}

TEST(AccuracySettings, BallastArgumentsFollowTheSolver) {
  Setting s = reference_setting(7);
  s.min_sweeps = 100;
  const auto a = run_arguments(s);
  const std::vector<std::string> want = {"--solver", "NLGS", "--dt", "0.0002", "--inclination", "0", "--policy", "NonStrict",
                                         "--tol", "0.0001666", "--min-sweeps", "100"};
  EXPECT_EQ(a, want);
  s.solver = "NEWTON_AC";
  s.tol = 1e-8;
  const auto b = run_arguments(s);
  EXPECT_EQ(b.back(), "1e-08");
  EXPECT_EQ(b[b.size() - 2], "--newton-tol");
  // the study's NEWTON_AC rows are the hybrid: NLGS sweeps first, named in the run's folder
  const auto crit = settings_of(Study::criterion, 7, 2);
  const auto row = std::find_if(crit.begin(), crit.end(), [](const Setting& x) { return x.solver == "NEWTON_AC"; });
  ASSERT_NE(row, crit.end());
  EXPECT_EQ(row->newton_presweeps, kNewtonPresweeps);
  const auto c = run_arguments(*row);
  const std::vector<std::string> tail = {"--newton-presweeps", std::to_string(kNewtonPresweeps), "--newton-presweep-tol",
                                         "0.0001"};
  EXPECT_TRUE(std::equal(tail.rbegin(), tail.rend(), c.rbegin()));
  EXPECT_NE(run_name(*row).find("_ps300_pt0.0001"), std::string::npos) << run_name(*row);
  Setting pure = *row;
  pure.newton_presweeps = 0;
  EXPECT_EQ(run_name(pure).find("_ps"), std::string::npos);
  EXPECT_EQ(run_arguments(pure).size(), c.size() - 4);
}

TEST(AccuracyTable, ReadsASummaryAndRefusesAnUnfinishedRun) {
  const fs::path dir = fs::temp_directory_path() / ("nscd_accuracy_table_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  {
    std::ofstream(dir / "summary.txt") << "result = valid\ncycles = 10\nfinal_settlement = 0.0125\nmean_sweeps = 42.5\n"
                                          "max_overlap = 2e-5\nmean_overlap = 1e-6\ncumulated_overlap = 3e-4\nunconverged_steps = 3\n"
                                          "time_per_cycle = 0.5\ncpu_time_per_cycle = 0.25\n";
  }
  const Row r = read_row(reference_setting(1), dir / "summary.txt", 10);
  ASSERT_TRUE(r.ok) << r.why;
  EXPECT_DOUBLE_EQ(r.wall_seconds, 5.0);
  EXPECT_DOUBLE_EQ(r.settlement, 0.0125);
  EXPECT_DOUBLE_EQ(r.cumulated_overlap, 3e-4);
  EXPECT_DOUBLE_EQ(r.unconverged_steps, 3.0);
  EXPECT_TRUE(std::isnan(r.max_iterations));  // a summary from before ballast recorded max_sweeps
  {
    std::ofstream(dir / "summary.txt", std::ios::app) << "max_sweeps = 1000\n";
  }
  EXPECT_DOUBLE_EQ(read_row(reference_setting(1), dir / "summary.txt", 10).max_iterations, 1000.0);
  EXPECT_TRUE(std::isnan(read_row(reference_setting(1), dir / "summary.txt", 10).mean_presweeps));  // not recorded
  {
    std::ofstream(dir / "summary.txt", std::ios::app) << "mean_presweeps = 120.5\n";
  }
  EXPECT_DOUBLE_EQ(read_row(reference_setting(1), dir / "summary.txt", 10).mean_presweeps, 120.5);
  const Row short_run = read_row(reference_setting(1), dir / "summary.txt", 20);  // asked for 20 cycles
  EXPECT_FALSE(short_run.ok);
  EXPECT_NE(short_run.why.find("10 cycles, not 20"), std::string::npos) << short_run.why;
  const Row none = read_row(reference_setting(1), dir / "missing.txt", 10);
  EXPECT_FALSE(none.ok);
  EXPECT_TRUE(std::isnan(none.settlement));

  write_table(dir / "table.csv", {r, none});
  std::ifstream in(dir / "table.csv");
  std::string header, first, second;
  std::getline(in, header);
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_EQ(header, kTableHeader);
  EXPECT_EQ(first, "NonStrict 1.666e-4 (reference),NLGS,NonStrict,0.0001666,0.0002,0,5,42.5,3,1e-06,2e-05,0.0003,0.0125");
  EXPECT_NE(second.find(",nan"), std::string::npos);
  fs::remove_all(dir);
}

TEST(AccuracyTable, SpreadRatioAndLargestStep) {
  Setting spread = reference_setting(2007);
  spread.role = Role::spread;
  std::vector<Row> rows = {row(reference_setting(2006), 0.010), row(spread, 0.013)};
  const Spread sp = sample_spread(rows);
  EXPECT_EQ(sp.samples, 2);
  EXPECT_NEAR(sp.range(), 0.003, 1e-15);
  EXPECT_NEAR(sp.mean, 0.0115, 1e-15);
  EXPECT_NEAR(sp.stddev, 0.003 / std::sqrt(2.0), 1e-15);
  // study 2's dt 2e-4 vertical row is the reference run: it counts; another step does not
  std::vector<Row> step_rows = {row(step(2e-4, 0.0), 0.010), row(step(1e-4, 0.0), 0.5), row(spread, 0.013)};
  EXPECT_EQ(sample_spread(step_rows).samples, 2);

  // the step series: settlement drifts away with dt; 1e-4 is the reference
  rows.push_back(row(step(1e-4, 0.0), 0.0100, 1e-6));
  rows.push_back(row(step(4e-4, 0.0), 0.0115, 2e-6));
  rows.push_back(row(step(5e-4, 0.0), 0.0140, 4e-6));  // out of the spread (0.004 > 0.003)
  rows.push_back(row(step(1e-3, 0.0), 0.0120, 8e-6));  // back within, but a shorter step was not
  EXPECT_DOUBLE_EQ(overlap_ratio(rows, 0.0), 8.0);
  EXPECT_DOUBLE_EQ(largest_step_within(rows, 0.0, sp.range()), 4e-4);  // the reference row (2e-4) counts too
  EXPECT_TRUE(std::isnan(overlap_ratio(rows, 5.0)));
  EXPECT_EQ(largest_step_within(rows, 5.0, sp.range()), 0.0);

  // study 1's error reference without a NEWTON_AC row: the tightest NonStrict NLGS row (not
  // the min-sweeps variant, not another policy)
  Setting ns5 = reference_setting(2006), ns7 = reference_setting(2006), st = reference_setting(2006), mn = reference_setting(2006);
  ns5.role = ns7.role = st.role = mn.role = Role::criterion;
  ns5.tol = 1e-5, ns7.tol = 1e-7, st.tol = 1e-9, mn.tol = 1e-8;
  st.policy = "Strict";
  mn.min_sweeps = 100;
  rows.push_back(row(ns5, 0.030));
  rows.push_back(row(ns7, 0.031));
  rows.push_back(row(st, 0.032));
  rows.push_back(row(mn, 0.033));
  const auto nlgs_ref = error_reference(rows, rows[0]);
  ASSERT_TRUE(nlgs_ref.has_value());
  EXPECT_EQ(nlgs_ref->setting.tol, 1e-7);
  EXPECT_EQ(nlgs_ref->settlement, 0.031);

  // NEWTON_AC rows that all failed count as absent: still the NLGS row
  Setting failed_newton = reference_setting(2006);
  failed_newton.role = Role::criterion;
  failed_newton.solver = "NEWTON_AC";
  failed_newton.tol = 1e-8;
  Row failed_row = row(failed_newton, 0.0);
  failed_row.ok = false;
  rows.push_back(failed_row);
  const auto after_failure = error_reference(rows, rows[0]);
  ASSERT_TRUE(after_failure.has_value());
  EXPECT_EQ(after_failure->setting.solver, "NLGS");
  rows.pop_back();

  // study 1's error reference: the tightest NEWTON_AC, when there is one
  Setting n6 = reference_setting(2006), n8 = reference_setting(2006);
  n6.role = n8.role = Role::criterion;
  n6.solver = n8.solver = "NEWTON_AC";
  n6.tol = 1e-6;
  n8.tol = 1e-8;
  rows.push_back(row(n6, 0.02));
  rows.push_back(row(n8, 0.011));
  const auto ref = error_reference(rows, rows[0]);
  ASSERT_TRUE(ref.has_value());
  EXPECT_EQ(ref->setting.tol, 1e-8);
  const auto step_ref = error_reference(rows, rows[4]);
  ASSERT_TRUE(step_ref.has_value());
  EXPECT_EQ(step_ref->setting.dt, 1e-4);
}
