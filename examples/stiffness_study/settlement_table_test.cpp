// examples/stiffness_study/settlement_table_test.cpp — tests of the stiffness study's
// reduction (settlement_table.cpp): CSV reading by column name, mean and sample standard
// deviation per cycle against hand-computed values, the settlement_by_k.csv layout, the trend.
#include "settlement_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;
using namespace stiffness;

namespace {

fs::path temp_file(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "nscd_stiffness_study_test";
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

std::string read_all(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Series series(std::vector<int> c, std::vector<double> s) { return Series{std::move(c), std::move(s)}; }

}  // namespace

TEST(SettlementTable, ReadsColumnsByNameWhateverTheirOrder) {
  // settlement_min_load is the 3rd column here (in ballast it is the 3rd too, but the reader
  // must not count on it): rows 1 and 2 give 0.5e-3 and 1.25e-3.
  const fs::path f = temp_file("cycles_a.csv", "time,cycle,settlement_min_load,x\n0.05,1,0.5e-3,9\n0.10,2,1.25e-3,9\n");
  const Series s = read_cycles_csv(f);
  ASSERT_EQ(s.cycle.size(), 2u);
  EXPECT_EQ(s.cycle[0], 1);
  EXPECT_EQ(s.cycle[1], 2);
  EXPECT_DOUBLE_EQ(s.settlement[0], 0.5e-3);
  EXPECT_DOUBLE_EQ(s.settlement[1], 1.25e-3);
  // Another column by name: x = 9 on both rows.
  EXPECT_DOUBLE_EQ(read_cycles_csv(f, "x").settlement[1], 9.0);
}

TEST(SettlementTable, ReportsMissingFileColumnAndBadNumbers) {
  EXPECT_THROW(read_cycles_csv("/nonexistent/cycles.csv"), std::runtime_error);
  EXPECT_THROW(read_cycles_csv(temp_file("no_col.csv", "cycle,time\n1,0.05\n")), std::runtime_error);
  EXPECT_THROW(read_cycles_csv(temp_file("bad_num.csv", "cycle,settlement_min_load\n1,abc\n")), std::runtime_error);
  EXPECT_THROW(read_cycles_csv(temp_file("short_row.csv", "cycle,time,settlement_min_load\n1,0.05\n")), std::runtime_error);
  try {
    read_cycles_csv(temp_file("bad_num2.csv", "cycle,settlement_min_load\n1,0.1\n2,1x\n"));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad_num2.csv:3"), std::string::npos) << e.what();  // file and line named
  }
}

TEST(SettlementTable, MeanAndSampleStandardDeviationPerCycle) {
  // Two runs, settlements (1, 2, 4) and (3, 2, 0):
  //   cycle 1: mean (1+3)/2 = 2, variance ((1−2)² + (3−2)²)/(2−1) = 2, std √2
  //   cycle 2: mean 2, std 0
  //   cycle 3: mean (4+0)/2 = 2, variance (2² + 2²)/1 = 8, std √8 = 2√2
  const KStats k = aggregate(100.0, {series({1, 2, 3}, {1, 2, 4}), series({1, 2, 3}, {3, 2, 0})});
  EXPECT_EQ(k.samples, 2);
  EXPECT_DOUBLE_EQ(k.k_factor, 100.0);
  ASSERT_EQ(k.mean.size(), 3u);
  for (double m : k.mean) EXPECT_DOUBLE_EQ(m, 2.0);
  EXPECT_DOUBLE_EQ(k.stddev[0], std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(k.stddev[1], 0.0);
  EXPECT_DOUBLE_EQ(k.stddev[2], 2.0 * std::sqrt(2.0));
}

TEST(SettlementTable, ThreeRunsAndTheShortestSetsTheLength) {
  // Runs (0.3, 0.6), (0.6, 0.9), (0.9): only cycle 1 is common. Mean (0.3+0.6+0.9)/3 = 0.6,
  // variance (0.09 + 0 + 0.09)/2 = 0.09, std 0.3.
  const KStats k = aggregate(1.0, {series({1, 2}, {0.3, 0.6}), series({1, 2}, {0.6, 0.9}), series({1}, {0.9})});
  ASSERT_EQ(k.cycle.size(), 1u);
  EXPECT_NEAR(k.mean[0], 0.6, 1e-15);
  EXPECT_NEAR(k.stddev[0], 0.3, 1e-15);
  // A single run: its own curve, spread 0.
  const KStats one = aggregate(1.0, {series({1, 2}, {0.3, 0.6})});
  EXPECT_DOUBLE_EQ(one.mean[1], 0.6);
  EXPECT_DOUBLE_EQ(one.stddev[1], 0.0);
  // No run at all: empty, not a crash.
  EXPECT_TRUE(aggregate(1.0, {}).mean.empty());
}

TEST(SettlementTable, RunsThatDisagreeOnCyclesAreAnError) {
  EXPECT_THROW(aggregate(1.0, {series({1, 2}, {0, 0}), series({1, 3}, {0, 0})}), std::runtime_error);
}

TEST(SettlementTable, WritesOneMeanAndStdColumnPerKFactor) {
  KStats a = aggregate(1.0, {series({1, 2}, {1.5, 2.5})});
  KStats b = aggregate(1000.0, {series({1}, {0.25}), series({1}, {0.75})});  // mean 0.5, std √((0.0625·2)/1) = √0.125
  const fs::path f = fs::temp_directory_path() / "nscd_stiffness_study_test" / "by_k.csv";
  write_settlement_by_k(f, {a, b});
  std::stringstream expected;
  expected.precision(10);
  expected << "cycle,mean_k1,std_k1,mean_k1000,std_k1000\n"
           << "1,1.5,0,0.5," << std::sqrt(0.125) << "\n"
           << "2,2.5,0,,\n";  // k × 1000 has one cycle only: empty cells after it
  EXPECT_EQ(read_all(f), expected.str());
}

TEST(SettlementTable, TrendIsAStrictDecreaseOfTheFinalMeanAsKGrows) {
  const auto k = [](double f, double final_settlement) { return aggregate(f, {series({1}, {final_settlement})}); };
  EXPECT_TRUE(decreases_with_k({k(1, 3e-3), k(100, 2e-3), k(1000, 1e-3)}));
  EXPECT_TRUE(decreases_with_k({k(1000, 1e-3), k(1, 3e-3), k(100, 2e-3)}));  // order of the list does not matter
  EXPECT_FALSE(decreases_with_k({k(1, 3e-3), k(100, 3.5e-3), k(1000, 1e-3)}));
  EXPECT_FALSE(decreases_with_k({k(1, 2e-3), k(100, 2e-3)}));  // equal is not a decrease
  EXPECT_FALSE(decreases_with_k({k(1, 2e-3)}));                // one k factor: no trend
  EXPECT_TRUE(decreases_with_k({k(1, 2e-3), aggregate(10, {}), k(100, 1e-3)}));  // a k factor without runs is ignored
}

TEST(SettlementTable, NumberTextIsShortest) {
  EXPECT_EQ(number_text(1.0), "1");
  EXPECT_EQ(number_text(100.0), "100");
  EXPECT_EQ(number_text(0.5), "0.5");
}
