// The threads of a step's loops around the solve, chosen step by step (LoopThreadChoice,
// StepperOptions::loop_threads): the schedule of the rounds, the choice by median cost, and the
// same bits whatever the choice.
#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <set>
#include <vector>

#include "nscd/core/error.hpp"
#include "nscd/shared/samples.hpp"
#include "nscd/solvers/loop_choice.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "nscd/solvers/thread_range.hpp"
#include "threads.hpp"

namespace {

using namespace nscd;

// Runs one epoch's rounds with cost(count, step) and returns the counts they ran on, in order.
std::vector<int> explore(LoopThreadChoice& c, const std::function<double(int, int)>& cost) {
  std::vector<int> ran;
  const int steps = c.candidates() * LoopThreadChoice::kBlock * LoopThreadChoice::kRounds;
  for (int s = 0; s < steps; ++s) {
    ran.push_back(c.next());
    EXPECT_EQ(c.next(), ran.back()) << "next() must not move before record()";
    c.record(cost(ran.back(), s));
  }
  return ran;
}

TEST(LoopThreadChoice, TriesEveryCountInBlocksThenKeepsTheCheapest) {
  LoopThreadChoice c;
  c.reset(2);
  ASSERT_EQ(c.candidates(), 2);
  // the rounds: 2 then 1, then 1 then 2 (kBlock steps each)
  const std::vector<int> ran = explore(c, [](int count, int) { return count == 2 ? 0.5 : 1.0; });
  const int b = LoopThreadChoice::kBlock;
  for (int s = 0; s < 4 * b; ++s) EXPECT_EQ(ran[s], (s < b || s >= 3 * b) ? 2 : 1) << "step " << s;
  EXPECT_EQ(c.chosen(), 2);
  for (int s = 4 * b; s < LoopThreadChoice::kEpoch; ++s) {
    ASSERT_EQ(c.next(), 2);
    c.record(100.0);  // (the rest of an epoch does not choose again)
  }
  // the next epoch measures again: now one thread is cheaper
  explore(c, [](int count, int) { return count == 1 ? 0.2 : 0.3; });
  EXPECT_EQ(c.chosen(), 1);
}

TEST(LoopThreadChoice, AMedianIsNotMovedByAFewSlowSteps) {
  LoopThreadChoice c;
  c.reset(2);
  // two threads cheaper, but every fourth of their steps (a rebuild of the broad phase) 20 times dearer
  explore(c, [](int count, int s) { return count == 1 ? 1.0 : (s % 4 == 0 ? 16.0 : 0.8); });
  EXPECT_EQ(c.chosen(), 2);
}

TEST(LoopThreadChoice, ManyCoresChooseAmongThePowersOfTwo) {
  LoopThreadChoice c;
  c.reset(12);
  ASSERT_EQ(c.candidates(), 5);  // 1, 2, 4, 8 and 12
  const std::vector<int> ran = explore(c, [](int count, int) { return count == 4 ? 1.0 : 2.0 + count; });
  EXPECT_EQ(std::set<int>(ran.begin(), ran.end()), (std::set<int>{1, 2, 4, 8, 12}));
  EXPECT_EQ(c.chosen(), 4);
  // a tie goes to the fewer threads
  c.reset(4);
  explore(c, [](int, int) { return 1.0; });
  EXPECT_EQ(c.chosen(), 1);
  // one thread: nothing to choose, no rounds
  c.reset(1);
  EXPECT_EQ(c.candidates(), 1);
  EXPECT_EQ(c.next(), 1);
}

TEST(LoopThreadChoice, TheStepperRefusesACountAboveItsThreads) {
  Registry reg;
  StepperOptions o;
  o.threads = 2;
  o.loop_threads = 3;
  EXPECT_THROW(MoreauJean(reg, o), Error);
  o.loop_threads = -1;
  EXPECT_THROW(MoreauJean(reg, o), Error);
  o.loop_threads = 2;
  EXPECT_NO_THROW(MoreauJean(reg, o));
}

TEST(LoopThreadChoice, AnyChoiceGivesTheSameBits) {
  NSCD_SKIP_WITHOUT_THREADS();
  // The paper's sample size: the loops around the solve on one thread, on two, and chosen step
  // by step (both, as the rounds try them), over warm-started steps to convergence.
  scenes::Scene s = scenes::pentagon_field(700, 0.01, 0.009);
  scenes::converge_to_centroid(s.reg, 0.1);
  s.reg.params.gravity = {0.0, -9.81};
  const int steps = 2 * 2 * LoopThreadChoice::kBlock + 4;
  std::vector<double> runs[3];
  std::set<int> counts;
  for (int loops : {1, 2, 0}) {
    Registry reg = s.reg;
    StepperOptions o;
    o.nlgs.order = SweepOrder::Colored;
    o.nlgs.anderson = 3;
    o.nlgs.threads = o.threads = 2;
    o.loop_threads = loops;
    MoreauJean mj(reg, o);
    std::vector<double>& out = runs[loops];
    for (int k = 0; k < steps; ++k) {
      const StepReport r = mj.step();
      if (loops == 0)
        counts.insert(r.loop_threads);
      else
        EXPECT_EQ(r.loop_threads, loops);
      out.insert(out.end(), {double(r.sweeps), r.max_overlap, r.contact_dissipation, double(r.warm_started)});
    }
    ASSERT_GE(reg.contacts.size(), kLoopParallelMin);  // (the loops do go on the threads)
    for (const auto* v : {&reg.bodies.x, &reg.bodies.y, &reg.bodies.angle, &reg.bodies.vx, &reg.contacts.rn})
      out.insert(out.end(), v->begin(), v->end());
  }
  EXPECT_EQ(counts, (std::set<int>{1, 2}));
  EXPECT_GT(runs[1][0], 10.0);  // real sweeps
  ASSERT_EQ(runs[0].size(), runs[1].size());
  ASSERT_EQ(runs[0].size(), runs[2].size());
  for (std::size_t i = 0; i < runs[0].size(); ++i) {
    ASSERT_EQ(runs[1][i], runs[2][i]) << "entry " << i;
    ASSERT_EQ(runs[0][i], runs[2][i]) << "entry " << i;
  }
}

}  // namespace
