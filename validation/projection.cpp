// validation/projection.cpp — the overlap projection (docs/theory.md §8.4).
//
// 1. A block pressed into the floor by 50 µm (beyond the slop s = 1e-3 × alert) at rest: one
//    step with the projection leaves the overlap at s (to the projection's tolerance), and the
//    velocities are bit for bit those of the same step without it (the projection moves
//    positions only, so it puts no kinetic energy into the scene). Without the projection
//    IQS_CLB keeps the 50 µm for good.
// 2. A block within the slop is not moved at all (positions bit for bit those without it).
// 3. A column of 30 blocks (10 cm × 1 cm) resting on the floor, stepped 10⁵ times at the ballast
//    driver's default solver settings (NLGS NonStrict 1.666e-4, colored, ω = 1.3, Anderson
//    depth 3, h = 2e-4 s): its top block sinks by at most 1 µm after the first 1,000 steps.
//
// 4. A block 110 µm into the floor leaving it at 0.5 m/s, clear at the next detection but still
//    overlapping at the end of the step: that overlap is brought to end_slops × s.
//
// Suite: Projection (also run with NEWTON_AC: validation/CMakeLists.txt).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "validation_support.hpp"

namespace {

using namespace nscd;
using nscd::validation::kG;
using nscd::validation::add_block;
using nscd::validation::add_floor;


struct Pressed {
  Registry reg;
  BodyId block;
};

// A 0.2 × 0.1 m block whose bottom face lies `overlap` below the floor's top face.
Pressed pressed_block(double overlap) {
  Pressed p;
  p.reg.params.dt = 2e-4;
  p.reg.params.gravity = {0.0, -kG};
  const MaterialId m = add_material(p.reg, "concrete", 2000.0);
  set_default_contact_law(p.reg, LawSpec{LawKind::IQS_CLB, 0.5});
  add_floor(p.reg, m);
  p.block = add_block(p.reg, m, 0.2, 0.1, 0.0, -overlap);
  return p;
}

// The default NLGS, or NEWTON_AC in the NEWTON_AC build of the validation (validation_support.hpp).
StepperOptions with_projection(bool on) {
  StepperOptions o;
#ifdef NSCD_VALIDATION_NEWTON
  o = nscd::validation::tight_options();
#endif
  o.projection.enabled = on;
  return o;
}

TEST(Projection, AnOverlapBeyondTheSlopIsRemovedWithoutAVelocity) {
  constexpr double kOverlap = 5e-5;
  Pressed on = pressed_block(kOverlap), off = pressed_block(kOverlap);
  MoreauJean mj_on(on.reg, with_projection(true)), mj_off(off.reg, with_projection(false));
  const StepReport r_on = mj_on.step(), r_off = mj_off.step();
  const double s = StepperOptions{}.projection.slop * on.reg.params.alert;
  const std::size_t i = on.block.index();
  EXPECT_EQ(on.reg.bodies.vx[i], off.reg.bodies.vx[i]);
  EXPECT_EQ(on.reg.bodies.vy[i], off.reg.bodies.vy[i]);
  EXPECT_EQ(on.reg.bodies.spin[i], off.reg.bodies.spin[i]);
  EXPECT_GT(r_on.projection_sweeps, 0);
  EXPECT_EQ(r_on.projected, 2u);  // the two ends of the face
  EXPECT_NEAR(r_on.projection_excess, kOverlap - s, 1e-9);
  // the overlap left: s, to the tolerance (and the O(h²) fall within the step)
  EXPECT_LE(r_on.max_overlap, s * (1.0 + StepperOptions{}.projection.tol) + kG * 2e-4 * 2e-4);
  EXPECT_GE(r_on.max_overlap, 0.9 * s);
  EXPECT_GT(r_off.max_overlap, 0.99 * kOverlap);
  EXPECT_NEAR(on.reg.bodies.y[i] - off.reg.bodies.y[i], kOverlap - s, 0.05 * s);
  EXPECT_NEAR(on.reg.bodies.x[i], off.reg.bodies.x[i], 1e-5 * kOverlap);  // along the normal (to the friction solve's rounding)
  // the next steps keep it there: the block rests at the slop
  for (int n = 0; n < 100; ++n) mj_on.step();
  EXPECT_LE(mj_on.report().max_overlap, s * (1.0 + StepperOptions{}.projection.tol) + 1e-9);
}

TEST(Projection, AnOverlapWithinTheSlopIsLeftAlone) {
  const double s = StepperOptions{}.projection.slop * Parameters{}.alert;
  Pressed on = pressed_block(0.5 * s), off = pressed_block(0.5 * s);
  MoreauJean mj_on(on.reg, with_projection(true)), mj_off(off.reg, with_projection(false));
  for (int n = 0; n < 50; ++n) {
    const StepReport r = mj_on.step();
    mj_off.step();
    ASSERT_EQ(r.projection_sweeps, 0) << "step " << n;
  }
  const std::size_t i = on.block.index();
  EXPECT_EQ(on.reg.bodies.y[i], off.reg.bodies.y[i]);
  EXPECT_EQ(on.reg.bodies.vy[i], off.reg.bodies.vy[i]);
}

TEST(Projection, AColumnOfThirtyBlocksDoesNotCreep) {
  Registry reg;
  reg.params.dt = 2e-4;
  reg.params.gravity = {0.0, -kG};
  const MaterialId m = add_material(reg, "concrete", 2367.0);
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.5});
  add_floor(reg, m);
  constexpr int kBlocks = 30;
  constexpr double kW = 0.1, kH = 0.01;  // 1 cm thick, as the paper's smallest grains
  std::vector<BodyId> blocks;
  for (int k = 0; k < kBlocks; ++k) blocks.push_back(add_block(reg, m, kW, kH, 0.0, k * kH, "block " + std::to_string(k)));
  StepperOptions o;  // the ballast driver's default solver settings (examples/ballast/ballast_study.hpp)
  o.nlgs.order = SweepOrder::Colored;
  o.nlgs.relaxation = 1.3;
  o.nlgs.anderson = 3;
  o.nlgs.policy = ConvergencePolicy::NonStrict;
  o.nlgs.tol = 1.666e-4;
  o.nlgs.check_every = 10;
  o.nlgs.max_sweeps = 1000;
#ifdef NSCD_VALIDATION_NEWTON
  o.solver = SolverKind::NEWTON_AC;  // at its default tolerance
#endif
  MoreauJean mj(reg, o);
  constexpr int kSettle = 1000, kSteps = 100000;
  const std::size_t top = blocks.back().index();
  double y_settled = 0.0, worst = 0.0, worst_overlap = 0.0;
  std::int64_t projected = 0;
  for (int n = 1; n <= kSteps; ++n) {
    const StepReport r = mj.step();
    projected += r.projection_sweeps > 0;
    worst_overlap = std::max(worst_overlap, r.max_overlap);
    if (n == kSettle) y_settled = reg.bodies.y[top];
    if (n > kSettle) worst = std::max(worst, std::abs(reg.bodies.y[top] - y_settled));
  }
  std::printf("[ measured ] 30-block column: top block drift %.3e m over steps %d-%d (%.3e m from the start), sideways %.3e m, "
              "largest overlap %.3e m, projected steps %lld\n",
              worst, kSettle, kSteps, (kBlocks - 0.5) * kH - reg.bodies.y[top], reg.bodies.x[top], worst_overlap,
              static_cast<long long>(projected));
  EXPECT_LE(worst, 1e-6);
  // the loose NLGS tolerance lets the column lean a little with or without the projection
  // (docs/studies.md §5.9); it must not walk away
  EXPECT_LE(std::abs(reg.bodies.x[top]), 1e-4);
}

// A block leaving the floor fast after a hard step: 110 µm into it at 0.5 m/s upwards, so that
// with θ = 1/2 and h = 2e-4 s it is clear at the next detection (+40 µm) but still 10 µm in at
// the end of the step. The projection takes that overlap down to end_slops × s, velocities
// unchanged; without the end-of-step bound the 10 µm would be reported.
TEST(Projection, AFastSeparatingOverlapIsBoundedAtTheEndOfTheStep) {
  constexpr double kOverlap = 1.1e-4, kSpeed = 0.5;
  Pressed on = pressed_block(kOverlap), unbounded = pressed_block(kOverlap);
  const std::size_t i = on.block.index();
  on.reg.bodies.vy[i] = unbounded.reg.bodies.vy[i] = kSpeed;
  StepperOptions far = with_projection(true);
  far.projection.end_slops = 1e9;
  MoreauJean mj_on(on.reg, with_projection(true)), mj_far(unbounded.reg, far);
  const StepReport r_on = mj_on.step(), r_far = mj_far.step();
  const ProjectionOptions o{};
  const double s = o.slop * on.reg.params.alert;
  EXPECT_EQ(on.reg.bodies.vy[i], unbounded.reg.bodies.vy[i]);
  EXPECT_GT(r_far.max_overlap, 5e-6);  // about 10 µm
  EXPECT_EQ(r_far.projection_sweeps, 0);
  EXPECT_GT(r_on.projection_sweeps, 0);
  EXPECT_LE(r_on.max_overlap, o.end_slops * s + o.tol * s + 1e-9);
  EXPECT_GE(r_on.max_overlap, 0.9 * o.end_slops * s);
}

}  // namespace
