// tests/unit/test_solve_profile.cpp — NlgsOptions::profile (solve_profile.hpp): a colored
// solve's region part by part, on one thread and on two, with the numbers unchanged.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "nscd/solvers/moreau_jean.hpp"
#include "compressed_field.hpp"
#include "threads.hpp"

namespace {

using namespace nscd;

using testing_support::compressed_field;

struct Solved {
  std::vector<double> rn, vx, w;
  SolveParts parts;  ///< summed over the steps
  double solve_seconds = 0.0;
  int sweeps = 0;
};

// `steps` steps in colored-cells (planned sweeps, Anderson's mixing) on `threads` threads
Solved run(const Registry& start, int threads, bool profile, int steps = 3) {
  Registry reg = start;
  StepperOptions o;
  o.nlgs.order = SweepOrder::ColoredCells;
  o.nlgs.anderson = 3;
  o.nlgs.relaxation = 1.3;
  o.nlgs.threads = o.threads = o.solve_threads = o.loop_threads = threads;
  o.nlgs.profile = profile;
  MoreauJean mj(reg, o);
  Solved r;
  for (int k = 0; k < steps; ++k) {
    mj.step();
    r.parts += mj.report().solve_parts;
    r.solve_seconds += mj.report().solve_seconds;
    r.sweeps += mj.report().sweeps;
  }
  r.rn = reg.contacts.rn;
  r.vx = reg.bodies.vx;
  r.w = reg.bodies.spin;
  return r;
}

void expect_same_numbers(const Solved& a, const Solved& b) {
  EXPECT_EQ(a.sweeps, b.sweeps);
  ASSERT_EQ(a.rn.size(), b.rn.size());
  for (std::size_t i = 0; i < a.rn.size(); ++i) ASSERT_EQ(a.rn[i], b.rn[i]) << "contact " << i;
  for (std::size_t i = 0; i < a.vx.size(); ++i) {
    ASSERT_EQ(a.vx[i], b.vx[i]) << "body " << i;
    ASSERT_EQ(a.w[i], b.w[i]) << "body " << i;
  }
}

// Each thread's laps lie inside the region, so the parts never pass region × threads, and
// the region lies inside the solve.
void expect_parts_inside(const SolveParts& p, double solve_seconds) {
  EXPECT_GT(p.region, 0.0);
  EXPECT_LE(p.region, solve_seconds);
  EXPECT_LE(p.parts(), p.thread_seconds);
  EXPECT_GT(p.parts(), 0.25 * p.thread_seconds);  // the clocks read most of the region
  for (double v : {p.sweeping, p.waiting, p.mixing, p.serial, p.setup}) EXPECT_GE(v, 0.0);
}

TEST(SolveProfile, OneThreadSweepsMixesAndNeverWaits) {
  const scenes::Scene s = compressed_field(600);
  const Solved off = run(s.reg, 1, false), on = run(s.reg, 1, true);
  expect_same_numbers(off, on);
  ASSERT_GT(on.sweeps, 60);
  EXPECT_EQ(off.parts.region, 0.0);  // not asked: nothing measured
  EXPECT_EQ(off.parts.parts(), 0.0);
  expect_parts_inside(on.parts, on.solve_seconds);
  EXPECT_EQ(on.parts.thread_seconds, on.parts.region);
  EXPECT_EQ(on.parts.waiting, 0.0);
  EXPECT_GT(on.parts.sweeping, 0.0);
  EXPECT_GT(on.parts.mixing, 0.0);
  EXPECT_GT(on.parts.serial, 0.0);  // the convergence checks
}

TEST(SolveProfile, TwoThreadsShareTheRegionAndKeepTheNumbers) {
  NSCD_SKIP_WITHOUT_THREADS();
  const scenes::Scene s = compressed_field(600);
  const Solved one = run(s.reg, 1, false), off = run(s.reg, 2, false), on = run(s.reg, 2, true);
  expect_same_numbers(one, off);
  expect_same_numbers(one, on);
  expect_parts_inside(on.parts, on.solve_seconds);
  EXPECT_DOUBLE_EQ(on.parts.thread_seconds, 2.0 * on.parts.region);
  EXPECT_GT(on.parts.sweeping, 0.0);
  EXPECT_GT(on.parts.mixing, 0.0);
  EXPECT_GT(on.parts.serial, 0.0);  // thread 0's γ and checks
  EXPECT_GT(on.parts.waiting, 0.0);  // the other thread, at least, waits for them
}

}  // namespace
