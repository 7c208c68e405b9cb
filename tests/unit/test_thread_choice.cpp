// The threads of a step's parts, chosen step by step (ThreadChoice, StepperOptions::solve_threads
// and loop_threads): the schedule of the rounds, the choice by median cost, the early end of the
// rounds and their restart on a drift, and the same bits whatever the choice.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <set>
#include <vector>

#include "nscd/core/error.hpp"
#include "nscd/shared/samples.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "nscd/solvers/thread_choice.hpp"
#include "nscd/solvers/thread_range.hpp"
#include "threads.hpp"

namespace {

using namespace nscd;

// Runs `steps` steps with cost(count, step) and returns the counts they ran on, in order.
std::vector<int> run(ThreadChoice& c, int steps, const std::function<double(int, int)>& cost) {
  std::vector<int> ran;
  for (int s = 0; s < steps; ++s) {
    ran.push_back(c.next());
    EXPECT_EQ(c.next(), ran.back()) << "next() must not move before record()";
    c.record(cost(ran.back(), s));
  }
  return ran;
}

// One epoch's full window of rounds.
std::vector<int> explore(ThreadChoice& c, const std::function<double(int, int)>& cost) {
  return run(c, c.exploring_steps(), cost);
}

TEST(ThreadChoice, TriesEveryCountInBlocksThenKeepsTheCheapest) {
  ThreadChoice c;
  c.reset(2);
  ASSERT_EQ(c.candidates(), 2);
  // close costs: both rounds, 1 then 2, then 2 then 1 (kBlock steps each)
  const std::vector<int> ran = explore(c, [](int count, int) { return count == 2 ? 0.9 : 1.0; });
  const int b = ThreadChoice::kBlock;
  for (int s = 0; s < 4 * b; ++s) EXPECT_EQ(ran[s], (s < b || s >= 3 * b) ? 1 : 2) << "step " << s;
  EXPECT_EQ(c.chosen(), 2);
  for (int s = 4 * b; s < ThreadChoice::kEpoch; ++s) {
    ASSERT_EQ(c.next(), 2);
    c.record(0.9);  // (the rest of an epoch does not choose again)
  }
  // the next epoch measures again: now one thread is cheaper
  explore(c, [](int count, int) { return count == 1 ? 0.27 : 0.3; });
  EXPECT_EQ(c.chosen(), 1);
}

TEST(ThreadChoice, AClearWinnerEndsTheRoundsAfterOne) {
  ThreadChoice c;
  c.reset(2);
  const int b = ThreadChoice::kBlock;
  // two threads a third dearer (a busy core): one round, then one thread to the epoch's end
  const std::vector<int> ran = run(c, 6 * b, [](int count, int) { return count == 2 ? 1.4 : 1.0; });
  for (int s = 0; s < 6 * b; ++s) EXPECT_EQ(ran[s], (s >= b && s < 2 * b) ? 2 : 1) << "step " << s;
  EXPECT_EQ(c.chosen(), 1);
}

TEST(ThreadChoice, ThePartThatFavoursTheThreadsAskedLeavesThemOnlyForAClearGain) {
  ThreadChoice c;
  c.reset(2, 0, ThreadChoice::kFavourAsked);  // (the solve's)
  explore(c, [](int count, int) { return count == 1 ? 0.9 : 1.0; });
  EXPECT_EQ(c.chosen(), 2);  // 10 % is within a noisy machine's drift
  c.reset(2, 0, ThreadChoice::kFavourAsked);
  explore(c, [](int count, int) { return count == 1 ? 1.0 : 3.0; });  // a busy core
  EXPECT_EQ(c.chosen(), 1);
  c.reset(16, 0, ThreadChoice::kFavourAsked);  // a small system on many cores: 8 is the best
  explore(c, [](int count, int) { return count == 8 ? 0.4 : count == 16 ? 1.0 : 2.0 / count; });
  EXPECT_EQ(c.chosen(), 8);
}

TEST(ThreadChoice, TheRoundsStartAtTheirStepAndOnOneThread) {
  ThreadChoice c;
  c.reset(2, 16);
  const std::vector<int> ran = run(c, 16 + c.exploring_steps(), [](int count, int) { return count == 1 ? 0.9 : 1.0; });
  for (int s = 0; s < 16 + ThreadChoice::kBlock; ++s) EXPECT_EQ(ran[s], 1) << "step " << s;
  EXPECT_EQ(ran[16 + ThreadChoice::kBlock], 2);
  EXPECT_EQ(c.chosen(), 1);
}

TEST(ThreadChoice, ADriftStartsTheRoundsAgain) {
  ThreadChoice c;
  c.reset(2);
  const int b = ThreadChoice::kBlock;
  run(c, 2 * b, [](int count, int) { return count == 2 ? 1.0 : 2.0; });  // two threads, clearly
  ASSERT_EQ(c.chosen(), 2);
  // a steady cost within kDrift: no new rounds
  EXPECT_EQ(run(c, 100, [](int, int) { return 1.5; }), std::vector<int>(100, 2));
  // slow steps in bursts shorter than the watch (rebuilds, another run's rounds): no new rounds
  const int w = ThreadChoice::kWatch;
  EXPECT_EQ(run(c, 4 * w, [](int, int s) { return s % b == 0 ? 5.0 : 1.0; }), std::vector<int>(4 * w, 2));
  EXPECT_EQ(run(c, 4 * w, [w](int, int s) { return s % (2 * w) < w / 2 ? 5.0 : 1.0; }), std::vector<int>(4 * w, 2));
  // another program takes a core: two threads 5 times dearer; after three quarters of the
  // watch's steps the rounds run again (a round of kBlock steps on each count) and choose one
  // thread, long before the epoch ends
  const std::vector<int> ran = run(c, 2 * w, [](int count, int) { return count == 2 ? 5.0 : 2.0; });
  const int first_one = static_cast<int>(std::find(ran.begin(), ran.end(), 1) - ran.begin());
  EXPECT_GE(first_one, 3 * w / 4 - 1 + b);
  EXPECT_LE(first_one, w + b);
  for (int s = first_one; s < 2 * w; ++s) EXPECT_EQ(ran[s], 1) << "step " << s;
  EXPECT_EQ(c.chosen(), 1);
}

TEST(ThreadChoice, ASystemThatDoubledChoosesAgain) {
  ThreadChoice c;
  c.reset(2);
  const int b = ThreadChoice::kBlock;
  for (int s = 0; s < 2 * b; ++s) c.record(c.next() == 1 ? 1.0 : 2.0, 100.0);  // a small system: one thread
  ASSERT_EQ(c.chosen(), 1);
  for (int s = 0; s < 50; ++s) {
    ASSERT_EQ(c.next(), 1) << "step " << s;
    c.record(1.0, 190.0);  // (grown, not doubled)
  }
  c.record(1.0, 210.0);  // doubled: a new epoch, its rounds led by the count chosen
  EXPECT_TRUE(c.restarted());
  const std::vector<int> ran = run(c, 2 * b, [](int, int) { return 1.0; });
  for (int s = 0; s < 2 * b; ++s) EXPECT_EQ(ran[s], s < b ? 1 : 2) << "step " << s;
}

TEST(ThreadChoice, ADearBlockEndsEarly) {
  const int b = ThreadChoice::kBlock;
  // the steps before the rounds on another part's count (one thread), which the rounds try first;
  // two threads forty times dearer (another run on the same cores): one step of them, not kBlock;
  // five times dearer: two steps
  for (const double dear : {40.0, 5.0}) {
    ThreadChoice c;
    c.reset(2, 8);
    std::vector<int> ran;
    for (int s = 0; s < 8 + 3 * b; ++s) {
      if (c.pending()) c.lead(1);
      ran.push_back(c.next());
      c.record(ran.back() == 2 ? dear : 1.0);
    }
    std::vector<int> expected(8 + 3 * b, 1);
    expected[8 + b] = 2;
    if (dear < ThreadChoice::kRejectAtOnce) expected[8 + b + 1] = 2;
    EXPECT_EQ(ran, expected) << dear;
    EXPECT_EQ(c.chosen(), 1);
  }
  // one dear step in a block (a rebuild of the broad phase) does not end it
  ThreadChoice c;
  c.reset(2, 1);
  c.lead(1);
  const std::vector<int> ran = run(c, 1 + 2 * b, [b](int count, int s) {
    return count == 2 && s == b + 2 ? 3.5 : count == 2 ? 0.5 : 1.0;
  });
  for (int s = b + 1; s < 1 + 2 * b; ++s) EXPECT_EQ(ran[s], 2) << "step " << s;
  EXPECT_EQ(c.chosen(), 2);
}

TEST(ThreadChoice, AnEpochLengthensWhileItsChoiceRepeats) {
  ThreadChoice c;
  c.reset(2);
  const int e = ThreadChoice::kEpoch;
  // two threads cheaper, always: the rounds at 0, e, 2e + e, 4e + 3e (the epoch doubles)
  std::vector<int> ones;  // the first steps of each run on one thread (the rounds' blocks)
  const auto cost = [](int count, int) { return count == 2 ? 1.0 : 2.0; };
  const std::vector<int> ran = run(c, 8 * e, cost);
  for (int s = 0; s < 8 * e; ++s)
    if (ran[s] == 1 && (s == 0 || ran[s - 1] == 2)) ones.push_back(s);
  EXPECT_EQ(ones, (std::vector<int>{0, e + ThreadChoice::kBlock, 3 * e + ThreadChoice::kBlock,
                                    7 * e + ThreadChoice::kBlock}));
  // a drift starts an epoch of kEpoch steps: a core taken, then given back
  run(c, 2 * ThreadChoice::kWatch, [](int count, int) { return count == 2 ? 5.0 : 2.0; });
  ASSERT_EQ(c.chosen(), 1);
  int s0 = 0;
  const std::vector<int> after = run(c, 2 * e, cost);
  while (after[s0] == 1) ++s0;  // (a fall of one thread's cost: no; two threads tried in the next epoch)
  EXPECT_LE(s0, e);
}

TEST(ThreadChoice, ARiseAtTheFewestThreadsDoesNotChooseAgain) {
  ThreadChoice c;
  c.reset(2);
  const int b = ThreadChoice::kBlock, w = ThreadChoice::kWatch;
  run(c, 2 * b, [](int count, int) { return count == 1 ? 1.0 : 2.0; });
  ASSERT_EQ(c.chosen(), 1);
  // another run's rounds slow this one's steps three times, for long: more threads would not help
  EXPECT_EQ(run(c, 4 * w, [](int, int) { return 3.0; }), std::vector<int>(4 * w, 1));
  // the machine got quieter: one thread's steps cost a third; new rounds, led by one thread
  const std::vector<int> ran = run(c, 2 * w, [](int count, int) { return count == 1 ? 0.3 : 0.2; });
  EXPECT_NE(std::find(ran.begin(), ran.end(), 2), ran.end());
  EXPECT_EQ(c.chosen(), 2);
}

TEST(ThreadChoice, AMedianIsNotMovedByAFewSlowSteps) {
  ThreadChoice c;
  c.reset(2);
  // two threads cheaper, but every fourth of their steps (a rebuild of the broad phase) 5 times dearer
  explore(c, [](int count, int s) { return count == 1 ? 1.0 : (s % 4 == 0 ? 4.0 : 0.8); });
  EXPECT_EQ(c.chosen(), 2);
}

TEST(ThreadChoice, StepsThatStallAreWeighedByTheirMean) {
  ThreadChoice c;
  c.reset(2);
  const int b = ThreadChoice::kBlock, w = ThreadChoice::kWatch;
  // another program on a core: most two-thread steps at full speed, one in four waits for time
  // slices (a hundred times dearer): their median is the cheaper, their mean is not
  const auto busy = [](int count, int s) { return count == 1 ? 1.0 : (s % 4 == 2 ? 100.0 : 0.6); };
  explore(c, busy);
  EXPECT_EQ(c.chosen(), 1);
  // two threads chosen on a quiet machine; then their steps stall: new rounds within the watch
  c.reset(2);
  run(c, 2 * b, [](int count, int) { return count == 1 ? 1.0 : 0.6; });
  ASSERT_EQ(c.chosen(), 2);
  const std::vector<int> ran = run(c, w + 4 * b, busy);  // (the new rounds led by two threads)
  EXPECT_NE(std::find(ran.begin(), ran.begin() + w + b + 1, 1), ran.begin() + w + b + 1);
  EXPECT_EQ(c.chosen(), 1);
}

TEST(ThreadChoice, ManyCoresChooseAmongThePowersOfTwo) {
  ThreadChoice c;
  c.reset(12);
  ASSERT_EQ(c.candidates(), 5);  // 1, 2, 4, 8 and 12
  const std::vector<int> ran = explore(c, [](int count, int) { return count == 4 ? 1.0 : 2.0 + count; });
  EXPECT_EQ(std::set<int>(ran.begin(), ran.end()), (std::set<int>{1, 2, 4, 8, 12}));
  EXPECT_EQ(c.chosen(), 4);
  // a tie goes to the fewer threads
  c.reset(4);
  explore(c, [](int, int) { return 1.0; });
  EXPECT_EQ(c.chosen(), 1);
  // one thread: nothing to choose, no rounds, no epoch for another part to follow
  c.reset(1);
  EXPECT_EQ(c.candidates(), 1);
  EXPECT_EQ(c.next(), 1);
  EXPECT_FALSE(c.began());
  c.restart();
  EXPECT_FALSE(c.began());
}

TEST(ThreadChoice, LoopsChooseWhereTheSolveIsFixed) {
  NSCD_SKIP_WITHOUT_THREADS();
  // The solve on a fixed count, the loops chosen: their rounds try every count (a fixed solve
  // once restarted the loops' epoch at every step, and they never left their lead).
  scenes::Scene s = scenes::pentagon_field(700, 0.01, 0.009);
  scenes::converge_to_centroid(s.reg, 0.1);
  s.reg.params.gravity = {0.0, -9.81};
  StepperOptions o;
  o.nlgs.order = SweepOrder::Colored;
  o.nlgs.threads = o.threads = 2;
  o.solve_threads = 2;
  MoreauJean mj(s.reg, o);
  std::set<int> loop_counts;
  for (int k = 0; k < 2 * ThreadChoice::kBlock * ThreadChoice::kRounds; ++k) {
    const StepReport r = mj.step();
    EXPECT_EQ(r.solve_threads, 2);
    loop_counts.insert(r.loop_threads);
  }
  EXPECT_EQ(loop_counts, (std::set<int>{1, 2}));
}

TEST(ThreadChoice, TheStepperRefusesACountAboveItsThreads) {
  Registry reg;
  StepperOptions o;
  o.threads = o.nlgs.threads = 2;
  o.nlgs.order = SweepOrder::Colored;
  for (int StepperOptions::*count : {&StepperOptions::loop_threads, &StepperOptions::solve_threads}) {
    for (int bad : {3, -1}) {
      StepperOptions x = o;
      x.*count = bad;
      EXPECT_THROW(MoreauJean(reg, x), Error) << bad;
    }
    StepperOptions x = o;
    x.*count = 2;
    EXPECT_NO_THROW(MoreauJean(reg, x));
  }
}

TEST(ThreadChoice, AnyChoiceGivesTheSameBits) {
  NSCD_SKIP_WITHOUT_THREADS();
  // The paper's sample size: the solve and the loops around it on one thread, on two, and chosen
  // step by step (both, as the rounds try them: the solve's first, then the loops'), over
  // warm-started steps to convergence.
  scenes::Scene s = scenes::pentagon_field(700, 0.01, 0.009);
  scenes::converge_to_centroid(s.reg, 0.1);
  s.reg.params.gravity = {0.0, -9.81};
  const int window = 2 * ThreadChoice::kBlock * ThreadChoice::kRounds;  // (two counts)
  const int steps = 2 * window + 4;
  std::vector<double> runs[3];
  std::set<int> loop_counts, solve_counts;
  for (int t : {1, 2, 0}) {
    Registry reg = s.reg;
    StepperOptions o;
    o.nlgs.order = SweepOrder::Colored;
    o.nlgs.anderson = 3;
    o.nlgs.threads = o.threads = 2;
    o.loop_threads = o.solve_threads = t;
    MoreauJean mj(reg, o);
    std::vector<double>& out = runs[t];
    for (int k = 0; k < steps; ++k) {
      const StepReport r = mj.step();
      if (t == 0) {
        solve_counts.insert(r.solve_threads);
        loop_counts.insert(r.loop_threads);
        if (k < window / ThreadChoice::kRounds) {  // (the solve's first round: the loops on its count)
          EXPECT_EQ(r.loop_threads, r.solve_threads) << "step " << k;
        }
      } else {
        EXPECT_EQ(r.loop_threads, t);
        EXPECT_EQ(r.solve_threads, t);
      }
      out.insert(out.end(), {double(r.sweeps), r.max_overlap, r.contact_dissipation, double(r.warm_started)});
    }
    ASSERT_GE(reg.contacts.size(), kLoopParallelMin);  // (the loops do go on the threads)
    for (const auto* v : {&reg.bodies.x, &reg.bodies.y, &reg.bodies.angle, &reg.bodies.vx, &reg.contacts.rn})
      out.insert(out.end(), v->begin(), v->end());
  }
  EXPECT_EQ(solve_counts, (std::set<int>{1, 2}));
  EXPECT_EQ(loop_counts, (std::set<int>{1, 2}));
  EXPECT_GT(runs[1][0], 10.0);  // real sweeps
  ASSERT_EQ(runs[0].size(), runs[1].size());
  ASSERT_EQ(runs[0].size(), runs[2].size());
  for (std::size_t i = 0; i < runs[0].size(); ++i) {
    ASSERT_EQ(runs[1][i], runs[2][i]) << "entry " << i;
    ASSERT_EQ(runs[0][i], runs[2][i]) << "entry " << i;
  }
}

}  // namespace
