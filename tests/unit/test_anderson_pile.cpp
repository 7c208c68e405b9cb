// tests/unit/test_anderson_pile.cpp — Anderson mixing of the NLGS sweeps (src/solvers/anderson.hpp)
// in a scene:
//   - a pile (pentagons under gravity, colored-rows): after every solve the bodies'
//     velocities are those of the impulses (u_free + M⁻¹ H r), lanes and threads give the same
//     bits, and a deep pile needs fewer sweeps, with no more capped steps and a natural-map
//     residual below MoreauJean's flag; a body no contact touches is left out of the mixing and
//     keeps its velocity bit for bit;
//   - options: mixing needs a colored order, not the skip rule, and a depth of 0 … 8.
// The mixer alone: test_anderson.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "nscd/core/error.hpp"
#include "nscd/shared/samples.hpp"
#include "nscd/solvers/anderson.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "nscd/solvers/local_problem.hpp"
#include "nscd/solvers/nlgs.hpp"
#include "nscd/solvers/nlgs_colored.hpp"
#include "nscd/solvers/nlgs_mixing.hpp"
#include "threads.hpp"

namespace {

using namespace nscd;

// x ← G(x) = x + (b − A x) / 2.2 for the 1D Laplacian A = tridiag(−1, 2, −1) of size n: a
// A pile: 300 pentagons of bench_nlgs's field, every grain moving toward the centre, under
// gravity.
scenes::Scene pile() {
  scenes::Scene s = scenes::pentagon_field(300, 0.01, 0.009);
  scenes::converge_to_centroid(s.reg, 0.1);
  s.reg.params.gravity = {0.0, -9.81};
  return s;
}

// A deep one: 300 grains of the paper's grading packed in a box (pitch 0.8 d_max, neighbours
// overlapping a little), the layer as deep as the paper's, under gravity.
scenes::Scene deep_pile() {
  scenes::SampleOptions o;
  o.grains = 300;
  o.box_width = scenes::scaled_box_width(o.grains);
  o.pitch_factor = scenes::kPackedPitchFactor;
  return scenes::paper_sample(o);
}

NlgsOptions mixed_rows(int depth) {  // as recommended for the LMGC90 case: depth 5
  NlgsOptions o;
  o.order = SweepOrder::ColoredRows;
  o.relaxation = 1.3;
  o.anderson = depth;
  return o;
}

/// Steps the pile with `nlgs` and checks after each solve that the bodies' velocities are
/// those of the contacts' impulses; returns the mixings done.
int expect_velocities_of_the_impulses(const NlgsOptions& nlgs) {
  scenes::Scene s = pile();
  StepperOptions o;
  o.nlgs = nlgs;
  MoreauJean mj(s.reg, o);
  int mixes = 0;
  for (int k = 0; k < 25; ++k) {
    mj.begin_step();
    mj.detect();
    mj.prepare();
    mj.solve();
    mixes += mj.report().mixes;
    // u_f from the impulses alone: u_free + M⁻¹ H r
    ContactSystem again = mj.system();
    again.set_impulses(mj.impulses(), false);
    const ContactSystem& sys = mj.system();
    double vmax = 0.0, wmax = 0.0;
    for (const SolverBody& b : sys.bodies) {
      vmax = std::max({vmax, std::abs(b.vx), std::abs(b.vy)});
      wmax = std::max(wmax, std::abs(b.w));
    }
    for (std::size_t i = 0; i < sys.bodies.size(); ++i) {
      EXPECT_NEAR(sys.bodies[i].vx, again.bodies[i].vx, 1e-10 * vmax) << "step " << k << " body " << i;
      EXPECT_NEAR(sys.bodies[i].vy, again.bodies[i].vy, 1e-10 * vmax) << "step " << k << " body " << i;
      EXPECT_NEAR(sys.bodies[i].w, again.bodies[i].w, 1e-10 * wmax) << "step " << k << " body " << i;
    }
    mj.end_step();
  }
  return mixes;
}

TEST(AndersonMixing, TheVelocitiesStayThoseOfTheImpulses) { EXPECT_GT(expect_velocities_of_the_impulses(mixed_rows(3)), 0); }

// the sequential orders mix through the same NlgsMixing (nlgs_mixing.hpp)
TEST(AndersonMixing, ASequentialOrderMixesToo) {
  for (SweepOrder order : {SweepOrder::Fixed, SweepOrder::Shuffled}) {
    NlgsOptions o = mixed_rows(3);
    o.order = order;
    o.lanes = 0;
    EXPECT_GT(expect_velocities_of_the_impulses(o), 0) << name_of(order);
  }
}

struct PileRun {
  std::vector<double> rn, rt, vx, vy, spin;
  int sweeps = 0, mixes = 0, capped = 0, mix_returns = 0;
  double worst_residual = 0.0;  ///< largest natural-map residual / ‖q‖ over the steps
};

PileRun run_pile(const NlgsOptions& nlgs, int steps, bool deep = false) {
  scenes::Scene s = deep ? deep_pile() : pile();
  StepperOptions o;
  o.projection.enabled = false;  // the mixing on the paper's scheme, as these figures were measured
  o.nlgs = nlgs;
  o.solve_threads = nlgs.threads;  // every step on the count asked (ThreadChoice would lead with one)
  MoreauJean mj(s.reg, o);
  PileRun out;
  for (int k = 0; k < steps; ++k) {
    mj.begin_step();
    mj.detect();
    mj.prepare();
    mj.solve();
    out.sweeps += mj.report().sweeps;
    out.mixes += mj.report().mixes;
    out.mix_returns += mj.report().mix_returns;
    out.capped += !mj.report().converged;
    if (!mj.system().contacts.empty())
      out.worst_residual = std::max(out.worst_residual, natural_map_error(mj.local_problem(), mj.impulses()).relative_q);
    mj.end_step();
  }
  out.rn = s.reg.contacts.rn;
  out.rt = s.reg.contacts.rt;
  out.vx = s.reg.bodies.vx;
  out.vy = s.reg.bodies.vy;
  out.spin = s.reg.bodies.spin;
  return out;
}

TEST(AndersonMixing, LanesAndThreadsGiveTheSameBits) {
  NlgsOptions o = mixed_rows(3);
  o.lanes = 0;
  const PileRun scalar = run_pile(o, 20);
  ASSERT_GT(scalar.mixes, 0);
  for (const auto& [lanes, threads] : {std::pair{4, 1}, std::pair{2, 1}, std::pair{4, 2}, std::pair{0, 3}}) {
    if (threads > 1 && !testing_support::threads_run_in_parallel()) continue;  // (skipped below)
    o.lanes = lanes;
    o.threads = threads;
    const PileRun other = run_pile(o, 20);
    EXPECT_EQ(other.sweeps, scalar.sweeps) << lanes << " lanes, " << threads << " threads";
    EXPECT_EQ(other.mixes, scalar.mixes) << lanes << " lanes, " << threads << " threads";
    EXPECT_EQ(other.mix_returns, scalar.mix_returns) << lanes << " lanes, " << threads << " threads";
    // bitwise
    EXPECT_EQ(other.rn, scalar.rn) << lanes << " lanes, " << threads << " threads";
    EXPECT_EQ(other.rt, scalar.rt) << lanes << " lanes, " << threads << " threads";
    EXPECT_EQ(other.vx, scalar.vx) << lanes << " lanes, " << threads << " threads";
    EXPECT_EQ(other.vy, scalar.vy) << lanes << " lanes, " << threads << " threads";
    EXPECT_EQ(other.spin, scalar.spin) << lanes << " lanes, " << threads << " threads";
  }
  NSCD_SKIP_WITHOUT_THREADS();  // the lanes were compared; say that the threads were not
}

TEST(AndersonMixing, APileNeedsFewerSweepsForTheSameResidual) {
  const int steps = 600;
  const PileRun plain = run_pile(mixed_rows(0), steps, true);
  const PileRun mixed = run_pile(mixed_rows(5), steps, true);
  EXPECT_EQ(plain.mixes, 0);
  EXPECT_GT(mixed.mixes, 0);
  std::printf("pile, %d steps: sweeps %d plain, %d mixed (%d mixings, %d returns to mixing); capped %d / %d; worst natural-map residual %.3g / %.3g\n",
              steps, plain.sweeps, mixed.sweeps, mixed.mixes, mixed.mix_returns, plain.capped, mixed.capped,
              plain.worst_residual, mixed.worst_residual);
  EXPECT_EQ(plain.mix_returns, 0);
  EXPECT_GT(mixed.mix_returns, 0);  // some solves stall in their relaxed sweeps and mix again
  // measured: 57,360 sweeps plain, 33,170 mixed (depth 5; 31,550 before the mixing could resume
  // after relaxed sweeps stalled); 3 and 3 steps at the cap (3 and 0 before)
  EXPECT_LT(mixed.sweeps, 3 * plain.sweeps / 4);
  EXPECT_LE(mixed.capped, plain.capped);
  EXPECT_LT(mixed.worst_residual, 1e-3);  // the flag of MoreauJean's independent check
}

TEST(AndersonMixing, ASequentialPileNeedsFewerSweeps) {
  const int steps = 600;
  NlgsOptions o = mixed_rows(0);
  o.order = SweepOrder::Fixed;
  o.lanes = 0;
  const PileRun plain = run_pile(o, steps, true);
  o.anderson = 5;
  const PileRun mixed = run_pile(o, steps, true);
  std::printf("pile, fixed order, %d steps: sweeps %d plain, %d mixed (%d mixings, %d returns to mixing); capped %d / %d; worst natural-map residual %.3g / %.3g\n",
              steps, plain.sweeps, mixed.sweeps, mixed.mixes, mixed.mix_returns, plain.capped, mixed.capped,
              plain.worst_residual, mixed.worst_residual);
  EXPECT_GT(mixed.mixes, 0);
  // measured: 58,960 sweeps plain, 31,130 mixed (depth 5); 4 and 2 steps at the cap
  EXPECT_LT(mixed.sweeps, 3 * plain.sweeps / 4);
  EXPECT_LE(mixed.capped, plain.capped);
  EXPECT_LT(mixed.worst_residual, 1e-3);
}

// A body no contact or link touches keeps its velocity through a solve, a fixed point of the
// mixing: the mixer leaves it out (its list holds exactly the touched bodies), and its velocity
// comes out bit for bit as it went in, a −0.0 included, in the colored order on one thread or
// two and in a sequential order.
TEST(AndersonMixing, LeavesOutTheBodiesNoContactTouches) {
  scenes::Scene s = pile();
  s.reg.bodies.y[0] += 1.0;  // a grain a metre above the pile, out of contact
  StepperOptions so;
  so.nlgs = mixed_rows(3);
  MoreauJean mj(s.reg, so);
  for (int k = 0; k < 8; ++k) mj.step();
  mj.begin_step();
  mj.detect();
  mj.prepare();
  ContactSystem base = mj.system();
  std::vector<std::uint8_t> touched(base.bodies.size(), 0);
  for (const SolverContact& c : base.contacts) touched[c.cd] = touched[c.an] = 1;
  std::vector<std::uint32_t> expect;
  for (std::uint32_t i = 0; i < touched.size(); ++i)
    if (touched[i]) expect.push_back(i);
  ASSERT_GT(base.contacts.size(), 50u);
  ASSERT_LT(expect.size(), base.bodies.size()) << "the pile must keep a grain out of contact";
  const auto free_body = static_cast<std::size_t>(std::find(touched.begin(), touched.end(), 0) - touched.begin());
  base.bodies[free_body].vx = -0.0;
  auto check = [&](const ContactSystem& sys, const NlgsMixingBuffers& mb, const NlgsResult& r, const char* how) {
    EXPECT_GT(r.mixes, 0) << how;
    std::vector<std::uint32_t> listed = mb.bodies;
    std::size_t in_runs = 0;  // the runs the velocities are copied by: every listed body at its slot
    for (const BodyRun& run : mb.runs)
      for (std::uint32_t i = 0; i < run.count; ++i, ++in_runs) EXPECT_EQ(listed.at(run.slot + i), run.first + i) << how;
    EXPECT_EQ(in_runs, listed.size()) << how;
    std::sort(listed.begin(), listed.end());
    EXPECT_EQ(listed, expect) << how;
    for (std::size_t i = 0; i < sys.bodies.size(); ++i) {
      if (touched[i]) continue;
      const SolverBody &a = sys.bodies[i], &b = base.bodies[i];
      EXPECT_EQ(std::memcmp(&a.vx, &b.vx, sizeof(double)), 0) << how << ", body " << i;
      EXPECT_EQ(std::memcmp(&a.vy, &b.vy, sizeof(double)), 0) << how << ", body " << i;
      EXPECT_EQ(std::memcmp(&a.w, &b.w, sizeof(double)), 0) << how << ", body " << i;
    }
  };
  for (int threads : {1, 2}) {
    ContactSystem sys = base;
    NlgsColoredWorkspace ws;
    NlgsOptions o = mixed_rows(3);
    o.threads = threads;
    const NlgsResult r = nlgs_iterate_colored(sys, o, ws);
    check(sys, ws.mixing, r, threads == 1 ? "colored, one thread" : "colored, two threads");
  }
  ContactSystem sys = base;
  NlgsWorkspace ws;
  NlgsMixingBuffers buf;
  NlgsOptions o = mixed_rows(3);
  o.order = SweepOrder::Fixed;
  o.lanes = 0;
  const NlgsResult r = nlgs_iterate_mixed(sys, o, ws, buf);
  check(sys, buf, r, "fixed order");
}

// A list of bodies as runs of consecutive numbers, each at the slot of its first body; a run
// ends where the numbers jump, and a list appended in parts starts a run at each part.
TEST(AndersonMixing, ListsTheBodiesAsRunsOfConsecutiveNumbers) {
  const std::vector<std::uint32_t> ids = {3, 4, 5, 9, 10, 2, 11, 12};
  std::vector<BodyRun> runs;
  NlgsMixing::list_runs(ids.data(), 0, ids.size(), runs);
  auto as_tuples = [](const std::vector<BodyRun>& v) {
    std::vector<std::array<std::uint32_t, 3>> t;
    for (const BodyRun& r : v) t.push_back({r.first, r.slot, r.count});
    return t;
  };
  using T = std::vector<std::array<std::uint32_t, 3>>;
  EXPECT_EQ(as_tuples(runs), (T{{3, 0, 3}, {9, 3, 2}, {2, 5, 1}, {11, 6, 2}}));
  runs.clear();
  NlgsMixing::list_runs(ids.data(), 0, 4, runs);  // (two shares: 3 4 5 9 | 10 2 11 12)
  NlgsMixing::list_runs(ids.data(), 4, ids.size(), runs);
  EXPECT_EQ(as_tuples(runs), (T{{3, 0, 3}, {9, 3, 1}, {10, 4, 1}, {2, 5, 1}, {11, 6, 2}}));
}

TEST(AndersonMixing, NeedsASceneNoSkipRuleAndADepthUpToEight) {
  NlgsOptions o = mixed_rows(3);
  EXPECT_NO_THROW(validate(o));
  o.order = SweepOrder::Fixed;  // a scene's sequential sweeps mix too, a stand-alone problem's do not
  EXPECT_NO_THROW(validate(o));
  FrictionProblem2D p;
  std::vector<double> r;
  EXPECT_THROW(nlgs_solve(p, r, o), Error);
  o = mixed_rows(3);
  o.skip_zero = true;
  EXPECT_THROW(validate(o), Error);
  o = mixed_rows(AndersonMixer::kMaxDepth + 1);
  EXPECT_THROW(validate(o), Error);
  o = mixed_rows(-1);
  EXPECT_THROW(validate(o), Error);
}

}  // namespace
