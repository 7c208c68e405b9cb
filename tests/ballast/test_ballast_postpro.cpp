// tests/ballast/test_ballast_postpro.cpp — the POSTPRO time series of ballast's steps.csv and
// cycles.csv (issue #11, docs/output.md): appended after the columns of before, consistent with
// each other (status counts add up to the contacts, the strong and weak networks to the active
// points, the cumulative dissipation to the sum of the cycles'), with both solvers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "ballast_test_support.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/solvers/newton_ac.hpp"

using namespace ballast_test;

namespace {

const std::vector<std::string> kOldSteps = {"step", "time", "load", "settlement", "contacts", "active", "sweeps", "converged",
                                            "quad_dv", "maxm_dv", "mean_overlap", "max_overlap", "rms_grain_speed", "detect_s",
                                            "solve_s"};
const std::vector<std::string> kOldCycles = {"cycle", "time", "settlement_min_load", "settlement_max_load", "lateral_displacement",
                                             "mean_grain_speed", "mean_overlap", "max_overlap", "mean_sweeps", "unconverged_steps",
                                             "wall_time", "total_overlap"};

// The network columns of one row agree with each other and with the row's contacts / active.
void expect_consistent_network(const Csv& t, std::size_t i, const std::string& where) {
  const double open = t.value(i, "status_open"), stick = t.value(i, "status_stick");
  const double slip = t.value(i, "status_slip_forward") + t.value(i, "status_slip_backward");
  const double strong = t.value(i, "strong_contacts"), weak = t.value(i, "weak_contacts");
  const double active = stick + slip;
  if (std::find(t.columns.begin(), t.columns.end(), "contacts") != t.columns.end()) {  // steps.csv
    EXPECT_EQ(open + active, t.value(i, "contacts")) << where;
    EXPECT_EQ(active, t.value(i, "active")) << where;
  }
  EXPECT_EQ(strong + weak, active) << where;
  if (active > 0) {
    EXPECT_NEAR(t.value(i, "strong_force_share") + t.value(i, "weak_force_share"), 1.0, 1e-12) << where;
    EXPECT_GT(t.value(i, "strong_force_share"), 0.0) << where;
    EXPECT_DOUBLE_EQ(t.value(i, "sliding_share"), slip / active) << where;
    EXPECT_GT(t.value(i, "coordination_number"), 0.0) << where;
  }
  EXPECT_GE(t.value(i, "kinetic_energy"), 0.0) << where;
}

void check_run(const std::string& solver) {
  if (solver == "NEWTON_AC" && !nscd::newton_ac_available()) GTEST_SKIP() << "no SuiteSparse in this build";
  TempDir dir("postpro");
  ballast::Config c = tiny_config(dir.path(), 2);
  c.solver = solver;
  ASSERT_EQ(ballast::run(c), 0);

  const Csv st = read_csv(dir / "steps.csv");
  ASSERT_EQ(st.rows.size(), 500u);
  ASSERT_GT(st.columns.size(), kOldSteps.size());
  EXPECT_EQ(std::vector<std::string>(st.columns.begin(), st.columns.begin() + kOldSteps.size()), kOldSteps)
      << "the new columns come after the old ones";
  for (std::size_t i = 0; i < st.rows.size(); ++i) expect_consistent_network(st, i, solver + " steps.csv row " + std::to_string(i + 1));

  const Csv cy = read_csv(dir / "cycles.csv");
  ASSERT_EQ(cy.rows.size(), 2u);
  EXPECT_EQ(std::vector<std::string>(cy.columns.begin(), cy.columns.begin() + kOldCycles.size()), kOldCycles);
  double cumulative = 0.0, damper = 0.0;
  for (std::size_t i = 0; i < cy.rows.size(); ++i) {
    const std::string where = solver + " cycles.csv row " + std::to_string(i + 1);
    expect_consistent_network(cy, i, where);
    // the sleeper pushed into the layer under a cyclic load: its contacts and the sublayer's
    // dampers dissipate every cycle
    EXPECT_GT(cy.value(i, "contact_dissipation_cycle"), 0.0) << where;
    EXPECT_GT(cy.value(i, "damper_dissipation_cycle"), 0.0) << where;
    cumulative += cy.value(i, "contact_dissipation_cycle");
    damper += cy.value(i, "damper_dissipation_cycle");
    EXPECT_NEAR(cy.value(i, "contact_dissipation"), cumulative, 1e-12 * cumulative) << where;
    EXPECT_NEAR(cy.value(i, "damper_dissipation"), damper, 1e-12 * damper) << where;
  }
  // steps.csv (a row every step) ends where cycles.csv does: the same numbers, as text
  for (const char* col : {"kinetic_energy", "contact_dissipation", "damper_dissipation", "coordination_number", "sliding_share",
                          "strong_contacts", "strong_force_share", "status_open", "status_stick"})
    EXPECT_EQ(st.rows.back()[st.column(col)], cy.rows.back()[cy.column(col)]) << solver << " " << col;
}

TEST(BallastPostpro, SeriesAreAppendedAndConsistentNlgs) { check_run("NLGS"); }
TEST(BallastPostpro, SeriesAreAppendedAndConsistentNewton) { check_run("NEWTON_AC"); }

// The hybrid's NLGS sweeps before Newton (NEWTON_AC with --newton-presweeps), which `sweeps`
// (Newton iterations) leaves out: per step in steps.csv, per cycle in cycles.csv and over the
// run in summary.txt, the three agreeing; 0 for NLGS.
TEST(BallastPostpro, PresweepsOfTheHybridAreReported) {
  if (!nscd::newton_ac_available()) GTEST_SKIP() << "no SuiteSparse in this build";
  for (const std::string solver : {"NLGS", "NEWTON_AC"}) {
    TempDir dir("presweeps");
    ballast::Config c = tiny_config(dir.path(), 2);
    c.solver = solver;
    c.newton_presweeps = 40;
    c.newton_presweep_tol = 1e-5;
    ASSERT_EQ(ballast::run(c), 0) << solver;
    const Csv st = read_csv(dir / "steps.csv"), cy = read_csv(dir / "cycles.csv");
    ASSERT_EQ(st.rows.size(), 500u);
    ASSERT_EQ(cy.rows.size(), 2u);
    double sum = 0.0, most = 0.0;
    for (std::size_t i = 0; i < st.rows.size(); ++i) {
      const double p = st.value(i, "presweeps");
      EXPECT_GE(p, 0.0);
      EXPECT_LE(p, 40.0) << "at most --newton-presweeps";
      sum += p;
      most = std::max(most, p);
    }
    const double by_cycles = 0.5 * (cy.value(0, "mean_presweeps") + cy.value(1, "mean_presweeps"));
    EXPECT_NEAR(by_cycles, sum / 500.0, 1e-9) << solver;
    EXPECT_NEAR(std::stod(read_summary(dir / "summary.txt").at("mean_presweeps")), sum / 500.0, 1e-9) << solver;
    if (solver == "NLGS") EXPECT_EQ(most, 0.0) << "NLGS has no presweeps";
    else EXPECT_GT(most, 0.0) << "the hybrid swept before Newton";
  }
}

// Keeps the first n fields of every line of a CSV file (the file an earlier version wrote).
void keep_columns(const fs::path& file, std::size_t n) {
  std::ifstream in(file);
  std::string text, line;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split(line);
    for (std::size_t i = 0; i < n; ++i) text += (i ? "," : "") + f.at(i);
    text += '\n';
  }
  in.close();
  std::ofstream(file, std::ios::trunc) << text;
}

// A run started before the POSTPRO series existed: its checkpoint has no dissipation sums, its
// CSV files the old columns. Resumed, the files get the new header and "nan" in the new
// columns of the old rows; the cumulative dissipations are unknown (nan) but the per-cycle ones
// and the network are written; resumed once more, the "nan" stored in the checkpoint reads back.
TEST(BallastPostpro, RunFromBeforeTheSeriesResumes) {
  TempDir dir("postpro_old");
  ballast::Config c = tiny_config(dir.path(), 1);
  ASSERT_EQ(ballast::run(c), 0);
  const fs::path cp_file = dir / "checkpoint.nscd";
  nscd::Checkpoint cp = nscd::load_checkpoint(cp_file);
  ASSERT_EQ(cp.extra.erase("state.contact_dissipation"), 1u);
  ASSERT_EQ(cp.extra.erase("state.damper_dissipation"), 1u);
  ASSERT_EQ(cp.extra.erase("state.presweeps"), 1u);  // added later still
  nscd::save_checkpoint(cp_file, cp.reg, cp.warm_start, cp.extra);
  keep_columns(dir / "cycles.csv", kOldCycles.size());
  keep_columns(dir / "steps.csv", kOldSteps.size());

  for (int cycles : {2, 3}) {
    ballast::Config r;
    r.resume = dir.path().string();
    r.cycles = cycles;
    r.progress_every = 1e9;
    ASSERT_EQ(ballast::run(r), 0) << "resumed to " << cycles << " cycles";
  }
  const Csv cy = read_csv(dir / "cycles.csv");
  ASSERT_EQ(cy.rows.size(), 3u);
  EXPECT_GT(cy.columns.size(), kOldCycles.size());
  EXPECT_EQ(cy.rows[0][cy.column("kinetic_energy")], "nan") << "a row of the old run";
  EXPECT_EQ(cy.rows[0][cy.column("status_stick")], "nan");
  for (std::size_t i : {1u, 2u}) {
    EXPECT_EQ(cy.rows[i][cy.column("contact_dissipation")], "nan") << "unknown: the first cycle's is missing";
    EXPECT_GT(cy.value(i, "contact_dissipation_cycle"), 0.0);
    EXPECT_GT(cy.value(i, "damper_dissipation_cycle"), 0.0);
    EXPECT_GT(cy.value(i, "kinetic_energy"), 0.0);
    expect_consistent_network(cy, i, "cycles.csv row " + std::to_string(i + 1));
  }
  const Csv st = read_csv(dir / "steps.csv");  // every row has every column (read_csv checks)
  ASSERT_EQ(st.rows.size(), 750u);
  EXPECT_EQ(st.rows[0][st.column("coordination_number")], "nan");
  EXPECT_NE(st.rows[300][st.column("coordination_number")], "nan");
  EXPECT_EQ(st.rows[0][st.column("presweeps")], "nan");
  EXPECT_EQ(st.rows[300][st.column("presweeps")], "0");
  EXPECT_EQ(read_summary(dir / "summary.txt").at("mean_presweeps"), "nan") << "unknown over the whole run";
}

// A CSV file whose columns are not the first of this version's is refused, naming it.
TEST(BallastPostpro, ResumeRefusesForeignColumns) {
  TempDir dir("postpro_foreign");
  ballast::Config c = tiny_config(dir.path(), 1);
  ASSERT_EQ(ballast::run(c), 0);
  std::ofstream(dir / "cycles.csv", std::ios::trunc) << "cycle,something_else\n1,2\n";
  ballast::Config r;
  r.resume = dir.path().string();
  r.cycles = 2;
  r.progress_every = 1e9;
  try {
    ballast::run(r);
    ADD_FAILURE() << "a cycles.csv with foreign columns was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("cycles.csv"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("something_else"), std::string::npos) << e.what();
  }
}

}  // namespace
