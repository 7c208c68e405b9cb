// tests/unit/test_progress.cpp — the ETA of the drivers' progress lines (shared/progress.hpp,
// issue #11) on synthetic step costs, no clock involved: the estimate follows the cost per
// step of the current phase, not the mean over the whole run.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "nscd/shared/progress.hpp"

namespace {

using nscd::scenes::StepCostEta;

// Feeds `n` steps of `cost` seconds each, from step `*step` and wall time `*wall`.
void feed(StepCostEta& e, std::int64_t* step, double* wall, int n, double cost) {
  for (int i = 0; i < n; ++i) {
    ++*step;
    *wall += cost;
    e.observe(*step, *wall);
  }
}

TEST(StepCostEta, UnknownBeforeTwoMarks) {
  StepCostEta e(5.0);
  EXPECT_TRUE(std::isnan(e.seconds_per_step()));
  EXPECT_TRUE(std::isnan(e.eta(100)));
  e.observe(0, 0.0);
  EXPECT_TRUE(std::isnan(e.eta(100)));
  e.observe(0, 1.0);  // no step between the marks
  EXPECT_TRUE(std::isnan(e.eta(100)));
  e.observe(10, 2.0);
  EXPECT_NEAR(e.seconds_per_step(), 2.0 / 10.0, 1e-12);  // from the first mark: (2 - 0) / 10
}

TEST(StepCostEta, FollowsTheCurrentPhaseNotTheRunMean) {
  // A deposit: 2000 free-fall steps at 1 ms, then impact steps at 50 ms. After 200 impact
  // steps (10 s of wall time), 8000 steps left to the time limit.
  StepCostEta e(5.0);
  std::int64_t step = 0;
  double wall = 0.0;
  e.observe(step, wall);
  feed(e, &step, &wall, 2000, 1e-3);
  EXPECT_NEAR(e.seconds_per_step(), 1e-3, 1e-12);
  feed(e, &step, &wall, 200, 50e-3);
  const double run_mean = wall / double(step);  // the old estimate: elapsed / steps done
  EXPECT_NEAR(e.seconds_per_step(), 50e-3, 1e-3);
  EXPECT_NEAR(e.eta(8000), 8000 * 50e-3, 8000 * 1e-3);
  EXPECT_GT(e.eta(8000) / (8000 * run_mean), 8.0);  // the old estimate was ~9x too low here
  // and back to cheap steps (the grains at rest): the estimate comes down within a window
  feed(e, &step, &wall, 10000, 2e-3);
  EXPECT_NEAR(e.seconds_per_step(), 2e-3, 1e-9);
}

TEST(StepCostEta, WindowIsTheLastWindowSecondsOfWallTime) {
  // The estimate averages from the last mark at or before (now - window): with a 5 s window,
  // 20 steps of 1 s then 3 of 2 s average exactly the 3 slow steps (marks 20 s to 26 s).
  StepCostEta e(5.0);
  std::int64_t step = 0;
  double wall = 0.0;
  e.observe(step, wall);
  feed(e, &step, &wall, 20, 1.0);
  EXPECT_NEAR(e.seconds_per_step(), 1.0, 1e-12);
  feed(e, &step, &wall, 3, 2.0);
  EXPECT_NEAR(e.seconds_per_step(), 2.0, 1e-12);
  EXPECT_NEAR(e.eta(10), 20.0, 1e-9);
  // one step longer than the window: it alone is the current cost
  feed(e, &step, &wall, 1, 7.0);
  EXPECT_NEAR(e.seconds_per_step(), 7.0, 1e-12);
  EXPECT_EQ(e.eta(0), 0.0);
  EXPECT_EQ(e.eta(-3), 0.0);
}

}  // namespace
