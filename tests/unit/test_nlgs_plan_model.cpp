// tests/unit/test_nlgs_plan_model.cpp — what a planned sweep allows its threads, on a model
// (src/solvers/nlgs_plan_model.hpp), and the plan it models (plan_colored):
//   - hand-made plans: a bundle costs a unit, half where lanes 4–7 idle; two shares that do not
//     meet sweep in the busier one's time, a share that waits for the other's last bundle
//     sweeps after it, a wait's latency counts only where the wait is not met, and two shares
//     that wait for each other are refused;
//   - plan_colored gives the plan a solve on threads sweeps by, and its model lies between
//     the busiest share's work and every share's.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "nscd/core/error.hpp"
#include "nscd/solvers/nlgs_colored.hpp"
#include "nscd/solvers/nlgs_plan_model.hpp"
#include "squeezed_system.hpp"
#include "threads.hpp"

namespace {

using namespace nscd;

/// A share whose lane `lane` sweeps one block of `length` contacts from time 0.
SharePlan one_block(int lane, std::uint32_t length, bool shared) {
  SharePlan s;
  s.runs[lane].push_back({0, 0, length});
  s.span = s.bundles = length;
  if (shared) {  // (several shares: each time's bundles before it)
    s.bundle_at.resize(length + 1);
    for (std::uint32_t t = 0; t <= length; ++t) s.bundle_at[t] = t;
  }
  return s;
}

TEST(NlgsPlanModel, ABundleCostsAUnitAndHalfWhereItsUpperLanesIdle) {
  SharePlan s = one_block(0, 6, false);
  s.runs[5].push_back({1, 2, 4});  // lane 5 busy at times 2 and 3
  s.runs[1].push_back({2, 8, 10});  // a gap at 6 and 7: no bundle
  s.span = 10;
  s.bundles = 8;
  EXPECT_EQ(bundle_costs(s), (std::vector<double>{0.0, 0.5, 1.0, 2.0, 3.0, 3.5, 4.0, 4.5, 5.0}));
  LanePlan plan;
  plan.shares = {s};
  const PlanModel m = model_plan(plan, 0.25);
  EXPECT_DOUBLE_EQ(m.total, 5.25);  // its bundles and its tail
  EXPECT_DOUBLE_EQ(m.sweep, 5.25);
  EXPECT_EQ(m.waits, 0.0);
}

TEST(NlgsPlanModel, SharesSweepInTheBusierOnesTimeOrAfterWhatTheyWaitFor) {
  LanePlan plan;
  plan.shares = {one_block(4, 10, true), one_block(4, 6, true)};
  PlanModel m = model_plan(plan);
  EXPECT_DOUBLE_EQ(m.total, 16.0);
  EXPECT_DOUBLE_EQ(m.sweep, 10.0);  // apart: the busier share's 10 units
  EXPECT_EQ(m.waits, 0.0);
  // share 1 starts once share 0 has swept its 10 bundles, in every sweep; share 0 publishes them
  plan.shares[0].stops.push_back({10, ShareStop::kPublish, 0});
  plan.shares[1].stops.push_back({0, 0, 10});
  m = model_plan(plan, 0.0, 8);
  EXPECT_DOUBLE_EQ(m.sweep, 10.0);  // share 0 sweeps on; share 1 follows it a sweep behind
  EXPECT_DOUBLE_EQ(m.waits, 1.0);
  EXPECT_DOUBLE_EQ(m.idle, 4.0);  // 10 − 6 a sweep
  // share 0 now also waits, at its start, for share 1's last sweep: one after the other
  plan.shares[1].stops.push_back({6, ShareStop::kPublish, 0});
  std::sort(plan.shares[1].stops.begin(), plan.shares[1].stops.end(),
            [](const ShareStop& a, const ShareStop& b) { return a.at < b.at; });
  plan.shares[0].stops.insert(plan.shares[0].stops.begin(), ShareStop{0, 1, 6 - 7});
  m = model_plan(plan, 0.0, 8);
  EXPECT_DOUBLE_EQ(m.sweep, 16.0);
  EXPECT_DOUBLE_EQ(model_plan(plan, 0.0, 8, 3.0).sweep, 22.0);  // each of the two waits 3 units late
}

TEST(NlgsPlanModel, SharesThatWaitForEachOtherAreRefused) {
  LanePlan plan;
  plan.shares = {one_block(0, 4, true), one_block(0, 4, true)};
  plan.shares[0].stops = {{0, 1, 2}, {2, ShareStop::kPublish, 0}};
  plan.shares[1].stops = {{0, 0, 2}, {2, ShareStop::kPublish, 0}};
  EXPECT_THROW(model_plan(plan), Error);
  EXPECT_THROW(model_plan(plan, 0.0, 1), Error);  // at least two sweeps
}

TEST(NlgsPlanModel, ColoredCellsSweepTheRowsAtOnceOnManyThreads) {
  // The same grid of cells: in colored-rows each row ends where the next begins, so on eight
  // threads the rows follow one another; in colored-cells (from the top, each cell upward) they
  // start at once. One thread's plan is about as long in both.
  const ContactSystem field = testing_support::squeezed_system(700, SweepOrder::ColoredRows);
  double sweep[2][2] = {};  // [order][1 or 8 threads]
  std::size_t colours = 0;  // (over the four plans)
  for (const SweepOrder order : {SweepOrder::ColoredRows, SweepOrder::ColoredCells})
    for (const int T : {1, 8}) {
      NlgsOptions opt;
      opt.order = order;
      opt.threads = T;
      ContactSystem sys = field;
      NlgsColoredWorkspace ws;
      const LanePlan* plan = plan_colored(sys, opt, ws);
      if (plan == nullptr) GTEST_SKIP() << "no SIMD lanes here: the sweeps are not planned";
      ASSERT_TRUE(ws.cells);
      for (std::size_t k = 0; k + 2 < ws.color_start.size(); ++k)  // the parallel colours used
        colours += ws.color_start[k + 1] > ws.color_start[k];
      sweep[order == SweepOrder::ColoredCells][T == 8] = model_plan(*plan).sweep;
    }
  ASSERT_GE(colours, 4 * 6u);  // three rows at least, two colours a row
  EXPECT_NEAR(sweep[1][0], sweep[0][0], 0.05 * sweep[0][0]);
  EXPECT_LT(sweep[1][1], 0.8 * sweep[0][1])
      << "8 threads: colored-cells " << sweep[1][1] << " units a sweep, colored-rows " << sweep[0][1];
  EXPECT_GT(sweep[1][0] / sweep[1][1], 4.0);
}

TEST(NlgsPlanModel, PlanColoredIsThePlanTheThreadsSweepBy) {
  NSCD_SKIP_WITHOUT_THREADS();
  const ContactSystem base = testing_support::squeezed_system(300, SweepOrder::Colored);
  for (const int T : {2, 3}) {
    SCOPED_TRACE(testing::Message() << T << " threads, " << base.contacts.size() << " contacts");
    NlgsOptions opt;
    opt.order = SweepOrder::Colored;
    opt.threads = T;
    opt.max_sweeps = 2;
    ContactSystem planned = base, solved = base;
    NlgsColoredWorkspace pw, sw;
    const LanePlan* plan = plan_colored(planned, opt, pw);
    ASSERT_NE(plan, nullptr);
    nlgs_iterate_colored(solved, opt, sw);
    ASSERT_EQ(plan->shares.size(), static_cast<std::size_t>(T));
    ASSERT_EQ(sw.plan.shares.size(), plan->shares.size());
    std::size_t waits = 0;
    for (std::size_t u = 0; u < plan->shares.size(); ++u) {
      const SharePlan &a = plan->shares[u], &b = sw.plan.shares[u];
      EXPECT_EQ(a.bundles, b.bundles);
      EXPECT_EQ(a.bundle_at, b.bundle_at);
      ASSERT_EQ(a.stops.size(), b.stops.size());
      for (std::size_t i = 0; i < a.stops.size(); ++i) {
        EXPECT_TRUE(a.stops[i].at == b.stops[i].at && a.stops[i].share == b.stops[i].share &&
                    a.stops[i].need == b.stops[i].need);
        waits += a.stops[i].share != ShareStop::kPublish;
      }
    }
    EXPECT_GT(waits, 0u);
    const PlanModel m = model_plan(*plan);
    const double busiest = *std::max_element(m.work.begin(), m.work.end());
    EXPECT_GE(m.sweep, busiest);
    EXPECT_LE(m.sweep, m.total);
  }
  NlgsOptions one;
  one.order = SweepOrder::Colored;
  one.lanes = 0;  // the scalar sweep is not planned
  ContactSystem sys = base;
  NlgsColoredWorkspace ws;
  one.threads = 2;
  EXPECT_EQ(plan_colored(sys, one, ws), nullptr);
}

}  // namespace
