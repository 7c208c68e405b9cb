// validation/incline.cpp — a block on an inclined plane with Coulomb friction (IQS_CLB).
//
// The incline is modelled by rotating gravity by α over a horizontal floor (exact, and the
// contact geometry stays axis-aligned): g = |g| (sin α, −cos α), so the "downhill" direction
// is +x. A rectangular block 0.2 m × 0.05 m rests on the floor with its bottom face exactly on
// y = 0 (gap 0); the floor is the antagonist, n = (0, 1), t = perp(n) = (−1, 0).
//
// Analytic answer (a rigid block, Coulomb's law with coefficient μ):
//   * tan α <= μ: the friction force balances the downhill weight, the block sticks,
//       Σ R_T = m |g| sin α  (along −x, uphill),  Σ R_N = m |g| cos α;
//   * tan α > μ: it slides with a = |g| (sin α − μ cos α), friction μ Σ R_N uphill.
// The θ-method keeps these exact in discrete time: with the normal impulse closing the
// contact each step (U_N = 0) the velocity update is u_{n+1} = u_n + h a, hence
// u_N = N h a (from rest) for every θ, and the travelled distance is
//   x_N − x_0 = Σ_{k<N} h ((1−θ) k h a + θ (k+1) h a) = a h² (N(N−1)/2 + θ N).
// The block does not tip: friction at the base makes a moment μ R_N (0.05/2) about the
// centre of mass, balanced by moving the normal force forward by μ · 0.025 m = 1.25 cm,
// well inside the 10 cm half-base; the two contact points (ends of the bottom edge) both stay
// pressed, and the block neither rotates nor leaves the floor.
//
// Suite: Incline (μ = 0.5 at α = 20°, stick; α = 30°, slide; μ = 0 at α = 30°, frictionless).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "validation_support.hpp"

namespace {

using namespace nscd;
using nscd::validation::kDeg;
using nscd::validation::kG;
using nscd::validation::add_block;
using nscd::validation::add_floor;
using nscd::validation::reaction_from;
using nscd::validation::rel_err;
using nscd::validation::tight_options;


struct InclineScene {
  Registry reg;
  BodyId floor, block;
  double mass = 0.0;
};

InclineScene make_incline(double alpha, double mu, double theta) {
  InclineScene s;
  s.reg.params.dt = 1e-3;
  s.reg.params.theta = theta;
  s.reg.params.gravity = {kG * std::sin(alpha), -kG * std::cos(alpha)};
  const MaterialId m = add_material(s.reg, "granite", 2700.0);
  set_default_contact_law(s.reg, LawSpec{LawKind::IQS_CLB, mu});
  s.floor = add_floor(s.reg, m);
  s.block = add_block(s.reg, m, 0.2, 0.05, 0.0, 0.0);
  s.mass = s.reg.bodies.mass[s.block.index()];  // 2700 × 0.01 = 27 kg/m
  return s;
}

// α = 20°, μ = 0.5: tan 20° = 0.364 < 0.5, the block sticks. Over 2000 steps (2 s) it must not
// move: an exact stick gives u = 0 each step, so the displacement is the solver's residual
// only (tolerance 1e-12 relative to |W r|, i.e. velocities ~1e-14 m/s). Asserted: |Δx|, |Δy| <
// 1e-10 m, |θ| < 1e-9 rad; the floor's reaction equals −m g (both components) within 1e-9 rel.
TEST(Incline, BlockSticksWhenTanAlphaIsBelowMu) {
  for (const double theta : {0.5, 1.0}) {
    InclineScene s = make_incline(20.0 * kDeg, 0.5, theta);
    MoreauJean mj(s.reg, tight_options());
    const std::size_t i = s.block.index();
    const double x0 = s.reg.bodies.x[i], y0 = s.reg.bodies.y[i];
    double worst_dx = 0.0, worst_force = 0.0;
    for (int n = 1; n <= 2000; ++n) {
      const StepReport r = mj.step();
      ASSERT_TRUE(r.converged) << "step " << n;
      ASSERT_EQ(r.contacts, 2u) << "edge–edge contact: the two ends of the bottom face";
      worst_dx = std::max({worst_dx, std::abs(s.reg.bodies.x[i] - x0), std::abs(s.reg.bodies.y[i] - y0)});
      ASSERT_LT(std::abs(s.reg.bodies.x[i] - x0), 1e-10) << "step " << n;
      ASSERT_LT(std::abs(s.reg.bodies.y[i] - y0), 1e-10) << "step " << n;
      ASSERT_LT(std::abs(s.reg.bodies.angle[i]), 1e-9) << "step " << n;
      // the floor carries the whole weight: R = −m g
      const Vec2 R = reaction_from(s.reg, s.floor);
      const Vec2 W = s.mass * s.reg.params.gravity;
      worst_force = std::max(worst_force, norm(R + W) / norm(W));
      ASSERT_LT(norm(R + W) / norm(W), 1e-9) << "step " << n;
      // How the friction splits between the two points is statically indeterminate (only the
      // sum is fixed), so one point may sit on the cone's edge (status Slip with U_T = 0):
      // each point is only asserted pressed and inside or on the cone.
      for (std::size_t k = 0; k < s.reg.contacts.size(); ++k) {
        ASSERT_NE(s.reg.contacts.status[k], ContactStatus::Open);
        ASSERT_LE(std::abs(s.reg.contacts.rt[k]), 0.5 * s.reg.contacts.rn[k] * (1.0 + 1e-12)) << "inside the cone";
      }
    }
    std::printf("[ measured ] incline stick theta=%.2f: max |displacement| %.3e m, reaction rel err %.3e\n", theta,
                worst_dx, worst_force);
  }
}

// Sliding: a = g (sin α − μ cos α). After N steps from rest u_N = N h a (see the header);
// asserted within 1e-6 relative at every 100th step, with the position formula, v_y ≈ 0 and
// no rotation. Forces: Σ R_N = m g cos α, Σ R_T = μ Σ R_N, both within 1e-6 relative.
void check_slide(double alpha, double mu, double theta, const char* label) {
  InclineScene s = make_incline(alpha, mu, theta);
  MoreauJean mj(s.reg, tight_options());
  const std::size_t i = s.block.index();
  const double h = s.reg.params.dt, a = kG * (std::sin(alpha) - mu * std::cos(alpha));
  const double x0 = s.reg.bodies.x[i];
  double worst_v = 0.0, worst_x = 0.0, worst_f = 0.0;
  constexpr int kSteps = 2000;
  for (int n = 1; n <= kSteps; ++n) {
    const StepReport r = mj.step();
    ASSERT_TRUE(r.converged) << label << " step " << n;
    ASSERT_EQ(r.contacts, 2u) << label << " step " << n;
    const double dn = n;
    const double v_exact = dn * h * a, x_exact = a * h * h * (0.5 * dn * (dn - 1.0) + theta * dn);
    worst_v = std::max(worst_v, rel_err(s.reg.bodies.vx[i], v_exact));
    worst_x = std::max(worst_x, rel_err(s.reg.bodies.x[i] - x0, x_exact));
    ASSERT_LT(rel_err(s.reg.bodies.vx[i], v_exact), 1e-6) << label << " step " << n;
    ASSERT_LT(rel_err(s.reg.bodies.x[i] - x0, x_exact), 1e-6) << label << " step " << n;
    ASSERT_LT(std::abs(s.reg.bodies.vy[i]), 1e-9 * a * h * dn) << label << " step " << n;
    ASSERT_LT(std::abs(s.reg.bodies.spin[i]), 1e-6) << label << " step " << n;
    // forces on the block from the floor: normal m g cos α up, friction μ R_N uphill (−x)
    const Vec2 R = reaction_from(s.reg, s.floor);
    const double rn_exact = s.mass * kG * std::cos(alpha);
    worst_f = std::max({worst_f, rel_err(R.y, rn_exact), rel_err(-R.x, mu * rn_exact, rn_exact)});
    ASSERT_LT(rel_err(R.y, rn_exact), 1e-6) << label << " step " << n;
    ASSERT_LT(rel_err(-R.x, mu * rn_exact, rn_exact), 1e-6) << label << " step " << n;
  }
  // hand value for the default case, a = 9.81 (0.5 − 0.5 × 0.866025) = 0.657145 m/s²
  std::printf("[ measured ] incline slide %s theta=%.2f: a=%.6f, v rel err %.3e, x rel err %.3e, force rel err %.3e\n",
              label, theta, a, worst_v, worst_x, worst_f);
}

TEST(Incline, BlockSlidesWithCoulombAcceleration) {
  // α = 30°, μ = 0.5: tan 30° = 0.577 > 0.5, a = 9.81 (0.5 − 0.433013) = 0.657145 m/s²
  for (const double theta : {0.5, 1.0}) check_slide(30.0 * kDeg, 0.5, theta, "mu=0.5");
}

TEST(Incline, FrictionlessBlockSlidesWithGSinAlpha) {
  // μ = 0: a = g sin 30° = 4.905 m/s²
  for (const double theta : {0.5, 1.0}) check_slide(30.0 * kDeg, 0.0, theta, "mu=0");
}

}  // namespace
