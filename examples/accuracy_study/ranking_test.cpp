// examples/accuracy_study/ranking_test.cpp — comparing two studies' rankings: Spearman's rank
// correlation against hand-computed values (ties included), the pair order, the groups, and two
// studies written as table.csv/trade.csv and read back.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "ranking.hpp"
#include "settings.hpp"
#include "table.hpp"

using namespace accuracy;
namespace fs = std::filesystem;

TEST(Spearman, SameOrderIsOneReversedIsMinusOne) {
  EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {10, 20, 30, 400}), 1.0);  // ranks, not values
  EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {4, 3, 2, 1}), -1.0);
}

TEST(Spearman, HandComputedWithoutAndWithTies) {
  // ranks (1,2,3,4,5) against (2,1,4,3,5): sum d^2 = 4, rho = 1 - 6*4/(5*24) = 0.8
  EXPECT_NEAR(spearman({1, 2, 3, 4, 5}, {2, 1, 4, 3, 5}), 0.8, 1e-12);
  // ties: b's ranks (1.5, 1.5, 3, 4); the Pearson correlation of (1,2,3,4) with them
  // = 4.5 / sqrt(5 * 4.5) = 0.948683...
  EXPECT_NEAR(spearman({1, 2, 3, 4}, {7, 7, 8, 9}), 4.5 / std::sqrt(5.0 * 4.5), 1e-12);
}

TEST(Spearman, UndefinedCasesAreNaN) {
  EXPECT_TRUE(std::isnan(spearman({1, 2}, {1, 2})));           // too few
  EXPECT_TRUE(std::isnan(spearman({1, 2, 3}, {5, 5, 5})));     // constant
  EXPECT_TRUE(std::isnan(spearman({1, 2, 3}, {1, 2})));        // unequal lengths
}

TEST(PairOrder, CountsPairsInTheSameOrderAndSkipsTies) {
  const PairOrder p = pair_order({1, 2, 3, 4}, {1, 3, 2, 3});
  // pairs: (1,2) same, (1,3) same, (1,4) same, (2,3) reversed, (2,4) tie in b, (3,4) same
  EXPECT_EQ(p.comparable, 5);
  EXPECT_EQ(p.same, 4);
}

namespace {

Row made_row(const Setting& s, double scale, double settlement) {
  Row r;
  r.setting = s;
  r.ok = true;
  r.cycles = 2;
  r.wall_seconds = 1.0;
  r.cpu_per_cycle = s.solver == "NEWTON_AC" ? 20.0 * scale : scale / s.tol * 1e-4;
  r.mean_iterations = 1.0 / s.tol;
  r.max_iterations = 2.0 / s.tol;
  r.unconverged_steps = 0.5 / s.tol;
  r.mean_overlap = s.dt * s.tol * scale;
  r.max_overlap = 10.0 * r.mean_overlap;
  r.cumulated_overlap = 100.0 * r.mean_overlap;
  r.settlement = settlement;
  return r;
}

// A study's table.csv and trade.csv for the criterion list, measures made from the setting (so
// two studies with another scale rank alike), settlements given.
fs::path write_study(const std::string& name, double scale, double settlement_of_energy) {
  const fs::path dir = fs::temp_directory_path() / ("nscd_ranking_" + std::to_string(getpid()) + "_" + name);
  fs::create_directories(dir);
  std::vector<Row> rows;
  for (const Setting& s : settings_of(Study::criterion, 2006, 3))
    rows.push_back(made_row(s, scale,
                            s.policy == "Energy" ? settlement_of_energy
                            : s.role == Role::reference || s.role == Role::spread ? 0.030 + 1e-4 * double(s.seed - 2006)  // spread 0.2 mm
                                                                                  : 0.030));
  write_table(dir / "table.csv", rows);
  write_trade(dir / "trade.csv", rows, sample_spread(rows));
  return dir;
}

}  // namespace

TEST(CompareRankings, TwoStudiesOfOneOrderAgreeAndAChangedVerdictIsNamed) {
  const fs::path a = write_study("a", 1.0, 0.030), b = write_study("b", 3.0, 0.050);
  const StudyMeasures ma = read_study(a), mb = read_study(b);
  const std::vector<Setting> settings = settings_of(Study::criterion, 2006, 3);
  ASSERT_EQ(ma.size(), settings.size());
  EXPECT_NEAR(ma.at("Energy 1.66e-3").value.at("mean_overlap"), 2e-4 * 1.66e-3, 1e-15);
  const RankComparison c = compare_rankings(settings, ma, mb);
  ASSERT_EQ(c.agreements.size(), ranked_measures().size());  // one group: study 1
  for (const RankAgreement& g : c.agreements) {
    EXPECT_EQ(g.group, "study 1 (criterion)");
    EXPECT_EQ(g.settings, 12) << g.measure;  // 9 NLGS and 2 NEWTON_AC criterion rows, the reference; not the spread rows
    if (g.measure == "settlement_error") continue;
    EXPECT_NEAR(g.spearman, 1.0, 1e-12) << g.measure;
    EXPECT_EQ(g.pairs.same, g.pairs.comparable) << g.measure;
  }
  // the energy rows settle 20 mm away in b: outside its spread (0.2 mm), within in a
  EXPECT_EQ(c.verdicts.size(), 12u);
  EXPECT_EQ(c.verdicts_same(), 9);
  const std::string section = ranking_section(c, "b");
  EXPECT_NE(section.find("the same verdict for 9 of 12"), std::string::npos) << section;
  EXPECT_NE(section.find("Energy 1.66e-3 (within here)"), std::string::npos) << section;
  write_ranking(a / "ranking.csv", c);
  std::ifstream in(a / "ranking.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "group,measure,settings,spearman,pairs_same,pairs_comparable");
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(CompareRankings, StepStudyGroupsByInclinationWithTheReferenceAsVertical) {
  const std::vector<Setting> settings = settings_of(Study::step, 2006, 2);
  StudyMeasures m;
  for (const Setting& s : settings)
    for (const std::string& name : ranked_measures()) m[s.label].value[name] = s.dt + s.inclination;
  const RankComparison c = compare_rankings(settings, m, m);
  int vertical = 0, inclined = 0;
  for (const RankAgreement& g : c.agreements) {
    EXPECT_NE(g.group, "study 1 (criterion)");
    if (g.group == "study 2, vertical") vertical = g.settings;
    if (g.group == "study 2, inclined 5°") inclined = g.settings;
  }
  EXPECT_EQ(vertical, 10);  // nine steps and the reference (dt 2e-4)
  EXPECT_EQ(inclined, 10);
}

TEST(ReadStudy, AMissingFileIsNamed) {
  try {
    read_study("/nonexistent_nscd_study");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_nscd_study/table.csv"), std::string::npos) << e.what();
  }
}
