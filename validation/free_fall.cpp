// validation/free_fall.cpp — bodies without contact: the θ-method's exact discrete answer.
//
// Without contact the Moreau–Jean step (moreau_jean.hpp) reduces to
//     u_{n+1} = u_n + h M⁻¹ F(t_n + (1−θ)h),
//     q_{n+1} = q_n + h ((1−θ) u_n + θ u_{n+1}),
// and for the forces used here the sums have closed forms, derived in each test. The
// simulation must match them at every step to 1e-12 relative: the only error left is
// floating-point rounding, which grows like n·ε ≈ 1000 × 1.1e-16 ≈ 1e-13 over 1000 steps.
// Quantities that pass through zero (a velocity reversing) are compared relative to
// max(|expected|, 1) in SI units, the scale of the motion (speeds ~1 m/s, lengths ~1 m).
//
// Suites: FreeFall (gravity for θ ∈ {0.5, 0.6, 0.75, 1}, a spinning body), Drives (imposed
// velocity, imposed force and moment).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "validation_support.hpp"

namespace {

using namespace nscd;
using nscd::validation::rel_err;

constexpr double kTol = 1e-12;

/// |a − b| / |b| for 2D vectors (the norm of b never vanishes in these cases).
double rel_err2(Vec2 a, Vec2 b) { return norm(a - b) / norm(b); }

/// Keeps the largest error seen (reported at the end of each test) and passes it through.
double track(double& worst, double e) {
  worst = std::max(worst, e);
  return e;
}

Vec2 position(const Registry& reg, BodyId b) { return {reg.bodies.x[b.index()], reg.bodies.y[b.index()]}; }
Vec2 velocity(const Registry& reg, BodyId b) { return {reg.bodies.vx[b.index()], reg.bodies.vy[b.index()]}; }

class FreeFallTheta : public ::testing::TestWithParam<double> {};

// Gravity g constant, so F = m g and
//     u_n = u_0 + n h g,
//     q_n = q_0 + Σ_{k<n} h ((1−θ) u_k + θ u_{k+1})
//         = q_0 + n h u_0 + h² g Σ_{k<n} (k + θ)
//         = q_0 + n h u_0 + h² g (n(n−1)/2 + θ n).
// For θ = 1/2 this is q_0 + n h u_0 + g (n h)²/2, the continuous parabola itself.
TEST_P(FreeFallTheta, MatchesTheDiscreteParabolaAtEveryStep) {
  const double theta = GetParam();
  Registry reg;
  reg.params.dt = 1e-3;
  reg.params.theta = theta;
  reg.params.gravity = {0.3, -9.81};  // not along an axis: both components are checked
  const double h = reg.params.dt;
  const Vec2 g = reg.params.gravity, q0{0.25, 3.0}, u0{1.5, 2.0};
  // a polygon body, so that detection runs (and finds nothing: one body only)
  const MaterialId m = add_material(reg, "steel", 7800.0);
  const BodyId b = add_polygon_body(reg, rectangle(0.1, 0.05), m, q0, 0.0, "falling");
  reg.bodies.vx[b.index()] = u0.x;
  reg.bodies.vy[b.index()] = u0.y;

  MoreauJean mj(reg);
  double worst_u = 0.0, worst_q = 0.0;
  for (int n = 1; n <= 1000; ++n) {
    const StepReport r = mj.step();
    ASSERT_EQ(r.contacts, 0u);
    const double dn = n;
    const Vec2 u_exact = u0 + dn * h * g;
    const Vec2 q_exact = q0 + dn * h * u0 + h * h * (0.5 * dn * (dn - 1.0) + theta * dn) * g;
    worst_u = std::max(worst_u, rel_err2(velocity(reg, b), u_exact));
    worst_q = std::max(worst_q, rel_err2(position(reg, b), q_exact));
    ASSERT_LT(rel_err2(velocity(reg, b), u_exact), kTol) << "theta " << theta << ", step " << n;
    ASSERT_LT(rel_err2(position(reg, b), q_exact), kTol) << "theta " << theta << ", step " << n;
    ASSERT_LT(rel_err(reg.time, dn * h), kTol);
    ASSERT_EQ(reg.step, n);
  }
  EXPECT_EQ(reg.bodies.angle[b.index()], 0.0);  // no moment: no rotation at all
  EXPECT_EQ(reg.bodies.spin[b.index()], 0.0);
  std::printf("[ measured ] free fall theta=%.2f: worst rel err u %.3e, q %.3e over 1000 steps\n", theta, worst_u, worst_q);
}

INSTANTIATE_TEST_SUITE_P(Theta, FreeFallTheta, ::testing::Values(0.5, 0.6, 0.75, 1.0));

// A free body spinning at ω0 with no moment: ω_n = ω0 exactly (nothing is added to it), and
// the angle advances linearly, a_n = a_0 + n h ω0 for every θ (the (1−θ)/θ split of a constant
// sums to 1). Without gravity the kinetic energy ½ m v² + ½ I ω² is constant, and the body
// keeps its shape: each world vertex stays at the same distance from the centre of mass.
TEST(FreeFall, SpinningBodyKeepsItsSpinAndTheAngleAdvancesLinearly) {
  double worst = 0.0;
  for (const double theta : {0.5, 0.6, 0.75, 1.0}) {
    Registry reg;
    reg.params.dt = 2e-3;
    reg.params.theta = theta;
    reg.params.gravity = {0.0, 0.0};
    const double h = reg.params.dt, w0 = 7.5, a0 = 0.3;
    const MaterialId m = add_material(reg, "wood", 600.0);
    const BodyId b = add_polygon_body(reg, regular_polygon(5, 0.2), m, {1.0, 1.0}, a0, "spinner");
    reg.bodies.spin[b.index()] = w0;
    reg.bodies.vx[b.index()] = -0.4;
    const double e0 = kinetic_energy(reg);
    const Polygon shape0 = world_polygon(reg, PolygId(0));
    const Vec2 c0 = position(reg, b);

    MoreauJean mj(reg);
    for (int n = 1; n <= 1000; ++n) {
      mj.step();
      ASSERT_EQ(reg.bodies.spin[b.index()], w0) << "theta " << theta << ", step " << n;
      ASSERT_LT(track(worst, rel_err(reg.bodies.angle[b.index()], a0 + n * h * w0)), kTol) << "theta " << theta << ", step " << n;
      ASSERT_LT(track(worst, rel_err(reg.bodies.x[b.index()], 1.0 - 0.4 * n * h)), kTol);
      ASSERT_EQ(reg.bodies.y[b.index()], 1.0);
    }
    EXPECT_LT(rel_err(kinetic_energy(reg), e0), kTol);
    // rigid: vertex distances to the centre are unchanged (the angle went round ~2.4 turns)
    const Polygon shape = world_polygon(reg, PolygId(0));
    const Vec2 c = position(reg, b);
    for (std::size_t k = 0; k < shape.size(); ++k) EXPECT_NEAR(norm(shape[k] - c), norm(shape0[k] - c0), 1e-14);
  }
  std::printf("[ measured ] spinning free body: worst rel err %.3e (spin exact)\n", worst);
}

// Imposed velocity v(t) = c t on X (gravity has an x component that must NOT act on it):
// the stepper uses the end-of-step value as u_{n+1} and the start velocity is v(t_n), so
//     vx_n = c n h,   x_n = x_0 + Σ_{k<n} h ((1−θ) c k h + θ c (k+1) h) = x_0 + c h² (n(n−1)/2 + θ n).
// The Y dof stays free: y_n = y_0 + h² g_y (n(n−1)/2 + θ n) from rest.
TEST(Drives, ImposedVelocityIsFollowedExactly) {
  double worst = 0.0;
  for (const double theta : {0.5, 0.6, 0.75, 1.0}) {
    Registry reg;
    reg.params.dt = 1e-3;
    reg.params.theta = theta;
    reg.params.gravity = {2.0, -9.81};
    const double h = reg.params.dt, c = 0.8, gy = reg.params.gravity.y;
    RigidBodySpec spec;
    spec.name = "driven";
    spec.position = {0.5, 2.0};
    spec.mass = 3.0;
    spec.inertia = 0.2;
    const BodyId b = add_body(reg, spec);
    impose_velocity(reg, b, Dof::X, TimeFunction::lambda([c](double t) { return c * t; }));

    MoreauJean mj(reg);
    for (int n = 1; n <= 1000; ++n) {
      mj.step();
      const double dn = n, s = 0.5 * dn * (dn - 1.0) + theta * dn;
      ASSERT_LT(track(worst, rel_err(reg.bodies.vx[b.index()], c * dn * h, 1.0)), kTol) << "theta " << theta << ", step " << n;
      ASSERT_LT(track(worst, rel_err(reg.bodies.x[b.index()], 0.5 + c * h * h * s, 1.0)), kTol) << "theta " << theta << ", step " << n;
      ASSERT_LT(track(worst, rel_err(reg.bodies.vy[b.index()], dn * h * gy, 1.0)), kTol);
      ASSERT_LT(track(worst, rel_err(reg.bodies.y[b.index()], 2.0 + h * h * gy * s, 1.0)), kTol);
    }
  }
  std::printf("[ measured ] imposed velocity: worst rel err %.3e\n", worst);
}

// Imposed force f(t) = c t on Y, added to gravity, evaluated at t_m = t_k + (1−θ)h:
//     u_{k+1} = u_k + h (g + c (k h + (1−θ) h)/m)
//  => u_n = u_0 + n h g + (c h²/m) S(n),            S(n) = n(n−1)/2 + (1−θ) n;
//     q_n = q_0 + h (Σ_{k<n} u_k + θ (u_n − u_0)),   Σ_{k<n} u_k = n u_0 + h g n(n−1)/2
//                                                    + (c h²/m)(n(n−1)(n−2)/6 + (1−θ) n(n−1)/2).
// A constant moment M on Rot: ω_n = ω_0 + n h M/I, a_n = a_0 + n h ω_0 + h² (M/I)(n(n−1)/2 + θ n).
// The t_m evaluation shows: had the force been taken at t_k, S(n) would lack (1−θ) n.
TEST(Drives, ImposedForceAndMomentFollowTheDiscreteIntegral) {
  double worst = 0.0;
  for (const double theta : {0.5, 0.6, 0.75, 1.0}) {
    Registry reg;
    reg.params.dt = 1e-3;
    reg.params.theta = theta;
    reg.params.gravity = {0.0, -9.81};
    const double h = reg.params.dt, c = 40.0, mass = 2.5, inertia = 0.15, M = -0.6, g = reg.params.gravity.y;
    const double u0 = 1.2, q0 = 0.7, w0 = 0.5, a0 = -0.1;
    RigidBodySpec spec;
    spec.name = "pushed";
    spec.position = {0.0, q0};
    spec.angle = a0;
    spec.velocity = {0.0, u0};
    spec.spin = w0;
    spec.mass = mass;
    spec.inertia = inertia;
    const BodyId b = add_body(reg, spec);
    impose_force(reg, b, Dof::Y, TimeFunction::lambda([c](double t) { return c * t; }));
    impose_force(reg, b, Dof::Rot, TimeFunction::constant(M));

    MoreauJean mj(reg);
    for (int n = 1; n <= 1000; ++n) {
      mj.step();
      const double dn = n, k2 = 0.5 * dn * (dn - 1.0);
      const double un = u0 + dn * h * g + c * h * h / mass * (k2 + (1.0 - theta) * dn);
      const double sum_u = dn * u0 + h * g * k2 + c * h * h / mass * (dn * (dn - 1.0) * (dn - 2.0) / 6.0 + (1.0 - theta) * k2);
      const double qn = q0 + h * (sum_u + theta * (un - u0));
      ASSERT_LT(track(worst, rel_err(reg.bodies.vy[b.index()], un, 1.0)), kTol) << "theta " << theta << ", step " << n;
      ASSERT_LT(track(worst, rel_err(reg.bodies.y[b.index()], qn, 1.0)), kTol) << "theta " << theta << ", step " << n;
      ASSERT_LT(track(worst, rel_err(reg.bodies.spin[b.index()], w0 + dn * h * M / inertia, 1.0)), kTol);
      ASSERT_LT(track(worst, rel_err(reg.bodies.angle[b.index()], a0 + dn * h * w0 + h * h * M / inertia * (k2 + theta * dn), 1.0)), kTol);
      ASSERT_EQ(reg.bodies.vx[b.index()], 0.0);
    }
  }
  std::printf("[ measured ] imposed force and moment: worst rel err %.3e\n", worst);
}

}  // namespace
