// tests/unit/test_springs.cpp — unit tests of the sublayer springs: the VOIGT_ROD law solved
// implicitly (laws/voigt_rod.hpp), PT2Dx points (contactors/pt2dx.hpp) and PTPT2 links
// (interactions/ptpt2.hpp), checked against hand computations.
//
// Reminder of the law (voigt_rod.hpp): over a step h, with L_m the length at q_m and U the
// end-of-step rate of extension, R = −k (L_m + θ h U − L0 (1 + ε0)) − ν U, written
// P = h R = ha − hb U with ha = −h k (L_m − rest), hb = h (k θ h + ν); for the velocity c the
// link would have without its own impulse and its Delassus scalar w (U = c + w P),
// P = (ha − hb c)/(1 + hb w).
//
// Suites: SpringsLaw, SpringsAddSpring, SpringsGeometry, SpringsPoints, SpringsStep.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/pt2dx.hpp"
#include "nscd/core/error.hpp"
#include "nscd/interactions/ptpt2.hpp"
#include "nscd/laws/voigt_rod.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "nscd/solvers/scene_backend.hpp"
#include "error_assertions.hpp"
#include "special_values.hpp"

namespace {

using nscd::testing_support::error_message;
using nscd::testing_support::Contains;

using namespace nscd;

using nscd::testing_support::kInf;
using nscd::testing_support::kNaN;

BodyId plain_body(Registry& reg, Vec2 position, double angle = 0.0, double mass = 1.0, double inertia = 1.0,
                  const std::string& name = "") {
  RigidBodySpec s;
  s.name = name;
  s.position = position;
  s.angle = angle;
  s.mass = mass;
  s.inertia = inertia;
  return add_body(reg, s);
}

// ---- the implicit law -----------------------------------------------------------------------

TEST(SpringsLaw, AffineCoefficientsByHand) {
  // k = 1000, ν = 10, rest 0.5, L_m = 0.48, h = 1e-3, θ = 0.5:
  //   ha = −h k (L_m − rest) = −1e-3 × 1000 × (−0.02) = 0.02
  //   hb = h (k θ h + ν)     = 1e-3 × (1000 × 0.5e-3 + 10) = 0.0105
  const VoigtAffine v = voigt_affine(1000.0, 10.0, 0.5, 0.48, 1e-3, 0.5);
  EXPECT_NEAR(v.ha, 0.02, 1e-16);
  EXPECT_NEAR(v.hb, 0.0105, 1e-16);
  // θ = 1 doubles the stiffness part of hb: 1e-3 × (1000 × 1e-3 + 10) = 0.011
  EXPECT_NEAR(voigt_affine(1000.0, 10.0, 0.5, 0.48, 1e-3, 1.0).hb, 0.011, 1e-16);
}

TEST(SpringsLaw, ImpulseByHandSatisfiesTheLaw) {
  // w = 2, c = 0.1: P = (0.02 − 0.0105 × 0.1)/(1 + 0.0105 × 2) = 0.01895/1.021 = 0.0185602350636631
  const double h = 1e-3, theta = 0.5, k = 1000.0, nu = 10.0, rest = 0.5, Lm = 0.48, w = 2.0, c = 0.1;
  const VoigtAffine v = voigt_affine(k, nu, rest, Lm, h, theta);
  const double P = voigt_impulse(v, w, c);
  EXPECT_NEAR(P, 0.01856023506366308, 1e-16);
  // and the end-of-step law holds: U = c + w P = 0.137120470, R = P/h = 18.560235 N,
  // −k (L_m + θ h U − rest) − ν U = 20 − 0.068560 − 1.371205 = 18.560235 N
  const double U = c + w * P;
  EXPECT_NEAR(P / h, -k * (Lm + theta * h * U - rest) - nu * U, 1e-11);
}

TEST(SpringsLaw, AtRestTheForceIsTheStaticSpringForce) {
  // If the impulse brings the link to rest (U = c + w P = 0, i.e. c = −w P), the law reads
  // P = ha: R = −k (L − L0 (1 + ε0)). With L0 = 0.4, ε0 = 0.25 the rest length is 0.5, and
  // at L = 0.48 the spring pushes with R = −1000 × (0.48 − 0.5) = 20 N, whatever ν.
  const double h = 1e-3, L0 = 0.4, eps0 = 0.25;
  for (const double nu : {0.0, 10.0, 1e6}) {
    const VoigtAffine v = voigt_affine(1000.0, nu, L0 * (1.0 + eps0), 0.48, h, 0.5);
    const double w = 3.0;
    const double P = voigt_impulse(v, w, -w * v.ha);
    EXPECT_NEAR(P / h, 20.0, 1e-9) << "nu " << nu;
  }
  // stretched instead of compressed: L = 0.53 pulls back with R = −30 N
  const VoigtAffine v = voigt_affine(1000.0, 10.0, 0.5, 0.53, h, 0.5);
  EXPECT_NEAR(voigt_impulse(v, 1.0, -v.ha) / h, -30.0, 1e-9);
}

TEST(SpringsLaw, PureDampingIsADashpot) {
  // k = 0, ν = 50, h = 1e-3, w = 4, c = 0.2: ha = 0, hb = h ν = 0.05,
  //   P = −0.05 × 0.2 / (1 + 0.05 × 4) = −0.01/1.2 = −0.0083333,
  //   U = 0.2 − 4 × 0.0083333 = 0.1666667, R = P/h = −8.333333 = −ν U;
  // the length and θ play no part.
  for (const double Lm : {0.1, 0.5, 2.0})
    for (const double theta : {0.5, 1.0}) {
      const VoigtAffine v = voigt_affine(0.0, 50.0, 0.5, Lm, 1e-3, theta);
      EXPECT_EQ(v.ha, 0.0);
      const double P = voigt_impulse(v, 4.0, 0.2);
      EXPECT_NEAR(P, -0.01 / 1.2, 1e-17);
      EXPECT_NEAR(P / 1e-3, -50.0 * (0.2 + 4.0 * P), 1e-12);
    }
}

// ---- add_spring -----------------------------------------------------------------------------

class SpringsAddSpring : public ::testing::Test {
 protected:
  void SetUp() override {
    a = plain_body(reg, {0.0, 0.0});
    b = plain_body(reg, {0.0, 2.0});
    pa = attach_point(reg, a, {0.0, 0.5});   // world (0, 0.5)
    pb = attach_point(reg, b, {0.0, -0.5});  // world (0, 1.5)
  }
  Registry reg;
  BodyId a, b;
  PointId pa, pb;
};

TEST_F(SpringsAddSpring, RefusesBadParametersAndLeavesNoLink) {
  EXPECT_TRUE(Contains(error_message([&] { add_spring(reg, pb, pa, VoigtRod{-1.0, 1.0, 1.0, 0.0}); }), "stiffness k must be >= 0"));
  EXPECT_TRUE(Contains(error_message([&] { add_spring(reg, pb, pa, VoigtRod{1.0, -0.5, 1.0, 0.0}); }), "viscosity nu must be >= 0"));
  EXPECT_TRUE(Contains(error_message([&] { add_spring(reg, pb, pa, VoigtRod{kNaN, 1.0, 1.0, 0.0}); }), "stiffness k"));
  EXPECT_TRUE(Contains(error_message([&] { add_spring(reg, pb, pa, VoigtRod{1.0, kInf, 1.0, 0.0}); }), "viscosity nu"));
  EXPECT_TRUE(Contains(error_message([&] { add_spring(reg, pb, pa, VoigtRod{1.0, 1.0, kInf, 0.0}); }), "L0 and eps0 must be finite"));
  EXPECT_TRUE(Contains(error_message([&] { add_spring(reg, pb, pa, VoigtRod{1.0, 1.0, 1.0, kNaN}); }), "L0 and eps0 must be finite"));
  // every message names the link about to be created
  EXPECT_TRUE(Contains(error_message([&] { add_spring(reg, pb, pa, VoigtRod{-1.0, 1.0, 1.0, 0.0}); }), "PTPT2 link 0"));
  EXPECT_TRUE(reg.links.empty());
}

TEST_F(SpringsAddSpring, RefusesCoincidentPointsAndUnknownIds) {
  const PointId same = attach_point_world(reg, b, {0.0, 0.5});  // on pa's spot, another body
  EXPECT_TRUE(Contains(error_message([&] { add_spring(reg, same, pa, VoigtRod{1.0, 1.0, 1.0, 0.0}); }), "coincide"));
  EXPECT_TRUE(Contains(error_message([&] { add_spring(reg, pb, PointId(99), VoigtRod{1.0, 1.0, 1.0, 0.0}); }), "unknown PT2Dx point id"));
  EXPECT_TRUE(Contains(error_message([&] { add_spring(reg, PointId(3), pa, VoigtRod{1.0, 1.0, 1.0, 0.0}); }), "unknown PT2Dx point id"));
  EXPECT_TRUE(Contains(error_message([&] { add_spring(reg, PointId(), pa, VoigtRod{1.0, 1.0, 1.0, 0.0}); }), "unknown PT2Dx point id"));
  EXPECT_TRUE(reg.links.empty());
  // k = 0 or ν = 0 alone is admissible (a pure dashpot, a pure spring)
  EXPECT_NO_THROW(add_spring(reg, pb, pa, VoigtRod{0.0, 1.0, 1.0, 0.0}));
  EXPECT_NO_THROW(add_spring(reg, pb, pa, VoigtRod{1.0, 0.0, 1.0, 0.0}));
  EXPECT_EQ(reg.links.size(), 2u);
}

TEST_F(SpringsAddSpring, ReferenceLengthDefaultsToTheCurrentLength) {
  // pa at (0, 0.5), pb at (0, 1.5): the current length is 1, the frame n = (0, 1) from the
  // antagonist pa to the candidate pb, force 0 at creation
  const LinkId l0 = add_spring(reg, pb, pa, VoigtRod{10.0, 1.0, 0.0, 0.0});
  const LinkId l1 = add_spring(reg, pb, pa, VoigtRod{10.0, 1.0, -3.0, 0.2});
  const LinkId l2 = add_spring(reg, pb, pa, VoigtRod{10.0, 1.0, 0.7, 0.2});
  EXPECT_EQ(reg.links.law[l0.index()].L0, 1.0);
  EXPECT_EQ(reg.links.law[l1.index()].L0, 1.0);
  EXPECT_EQ(reg.links.law[l1.index()].eps0, 0.2);  // the prestrain is kept
  EXPECT_EQ(reg.links.law[l2.index()].L0, 0.7);    // a given L0 is kept
  for (LinkId l : {l0, l1, l2}) {
    EXPECT_EQ(reg.links.length[l.index()], 1.0);
    EXPECT_EQ(reg.links.normal[l.index()], (Vec2{0.0, 1.0}));
    EXPECT_EQ(reg.links.rn[l.index()], 0.0);
    EXPECT_EQ(reg.links.candidate[l.index()], pb);
    EXPECT_EQ(reg.links.antagonist[l.index()], pa);
  }
}

// ---- geometry: link frame, lever arms, relative velocity --------------------------------------

class SpringsGeometry : public ::testing::Test {
 protected:
  // Candidate body A at (1, 2) turned by π/2, its point (0.5, 0) in the body frame lands at
  // (1, 2) + R(π/2)(0.5, 0) = (1, 2.5). Antagonist body B at (4.3, 6) turned by π, its point
  // (0.3, −0.5) lands at (4.3, 6) + R(π)(0.3, −0.5) = (4.3, 6) + (−0.3, 0.5) = (4, 6.5).
  //   d = (1, 2.5) − (4, 6.5) = (−3, −4): L = 5, n = (−0.6, −0.8)
  //   cd_rn = cross((0, 0.5), n)    = 0 × (−0.8) − 0.5 × (−0.6)      = 0.3
  //   an_rn = cross((−0.3, 0.5), n) = (−0.3)(−0.8) − 0.5 × (−0.6)    = 0.54
  void SetUp() override {
    A = plain_body(reg, {1.0, 2.0}, 0.5 * kPi, 2.0, 0.25, "A");
    B = plain_body(reg, {4.3, 6.0}, kPi, 4.0, 0.5, "B");
    pc = attach_point(reg, A, {0.5, 0.0});
    pa = attach_point(reg, B, {0.3, -0.5});
    link = add_spring(reg, pc, pa, VoigtRod{100.0, 1.0, 0.0, 0.0});
  }
  LinkFrame frame_at(Vec2 ca, double aa, Vec2 cb, double ab) const {
    const double x[2] = {ca.x, cb.x}, y[2] = {ca.y, cb.y}, angle[2] = {aa, ab};
    return link_frame(reg, link, x, y, angle);
  }
  Registry reg;
  BodyId A, B;
  PointId pc, pa;
  LinkId link;
};

TEST_F(SpringsGeometry, FrameAndLeverArmsOfRotatedBodiesByHand) {
  const LinkFrame f = link_frame(reg, link, reg.bodies.x, reg.bodies.y, reg.bodies.angle);
  EXPECT_NEAR(f.length, 5.0, 1e-14);
  EXPECT_NEAR(f.n.x, -0.6, 1e-15);
  EXPECT_NEAR(f.n.y, -0.8, 1e-15);
  EXPECT_NEAR(f.cd_rn, 0.3, 1e-15);
  EXPECT_NEAR(f.an_rn, 0.54, 1e-15);
  EXPECT_NEAR(reg.links.law[link.index()].L0, 5.0, 1e-14);  // taken from the current length
  // at another configuration: A moved to (1, −1) unturned, point at (1.5, −1); B unchanged:
  //   d = (1.5, −1) − (4, 6.5) = (−2.5, −7.5), L = √62.5 = 7.9056942, n = d/L,
  //   cd_rn = cross((0.5, 0), n) = 0.5 n_y = 0.5 × (−7.5)/7.9056942 = −0.4743416
  const LinkFrame g = frame_at({1.0, -1.0}, 0.0, {4.3, 6.0}, kPi);
  EXPECT_NEAR(g.length, std::sqrt(62.5), 1e-14);
  EXPECT_NEAR(g.n.x, -2.5 / std::sqrt(62.5), 1e-15);
  EXPECT_NEAR(g.cd_rn, 0.5 * (-7.5) / std::sqrt(62.5), 1e-15);
}

TEST_F(SpringsGeometry, ZeroLengthKeepsTheLastDirection) {
  // A at (4, 6) turned by π/2 puts its point at (4, 6.5), on B's: no direction, the last one
  // (the registry's, (−0.6, −0.8)) is kept
  const LinkFrame f = frame_at({4.0, 6.0}, 0.5 * kPi, {4.3, 6.0}, kPi);
  EXPECT_NEAR(f.length, 0.0, 1e-15);
  if (f.length == 0.0) {
    EXPECT_EQ(f.n, reg.links.normal[link.index()]);
  }
  EXPECT_TRUE(std::isfinite(f.n.x) && std::isfinite(f.n.y));
  EXPECT_NEAR(norm(f.n), 1.0, 1e-12);
}

TEST_F(SpringsGeometry, LinkVelocityIsTheRateOfChangeOfTheLength) {
  // v_A = (0.3, −0.2), ω_A = 1.5; v_B = (−0.1, 0.4), ω_B = −0.7:
  //   U = n·(v_A − v_B) + ω_A cd_rn − ω_B an_rn
  //     = (−0.6)(0.4) + (−0.8)(−0.6) + 1.5 × 0.3 + 0.7 × 0.54 = 0.24 + 0.45 + 0.378 = 1.068
  const Vec2 vA{0.3, -0.2}, vB{-0.1, 0.4};
  const double wA = 1.5, wB = -0.7;
  const LinkFrame f = frame_at({1.0, 2.0}, 0.5 * kPi, {4.3, 6.0}, kPi);
  SolverLink l;
  l.cd = 0;
  l.an = 1;
  l.nx = f.n.x;
  l.ny = f.n.y;
  l.cd_rn = f.cd_rn;
  l.an_rn = f.an_rn;
  SolverBody sa, sb;
  sa.vx = vA.x;
  sa.vy = vA.y;
  sa.w = wA;
  sb.vx = vB.x;
  sb.vy = vB.y;
  sb.w = wB;
  const double U = link_velocity(l, sa, sb);
  EXPECT_NEAR(U, 1.068, 1e-14);
  // central difference of the length along the rigid motions
  const double e = 1e-6;
  const LinkFrame fp = frame_at(Vec2{1.0, 2.0} + e * vA, 0.5 * kPi + e * wA, Vec2{4.3, 6.0} + e * vB, kPi + e * wB);
  const LinkFrame fm = frame_at(Vec2{1.0, 2.0} - e * vA, 0.5 * kPi - e * wA, Vec2{4.3, 6.0} - e * vB, kPi - e * wB);
  EXPECT_NEAR((fp.length - fm.length) / (2.0 * e), U, 1e-8);

  // The impulse acts along the same rows: applying dp changes U by w dp, with
  // w = 1/m_A + 1/m_B + cd_rn²/I_A + an_rn²/I_B = 0.5 + 0.25 + 0.09/0.25 + 0.2916/0.5 = 1.6932
  sa.inv_mx = sa.inv_my = 0.5;
  sa.inv_i = 4.0;
  sb.inv_mx = sb.inv_my = 0.25;
  sb.inv_i = 2.0;
  const double w = link_delassus(l, sa, sb);
  EXPECT_NEAR(w, 1.6932, 1e-14);
  apply_link_impulse(l, sa, sb, 0.1);
  EXPECT_NEAR(link_velocity(l, sa, sb), U + 0.1 * w, 1e-14);
}

// ---- PT2Dx points -----------------------------------------------------------------------------

TEST(SpringsPoints, AttachPointWorldRoundTrip) {
  // body at (1, 2) turned by 0.7; the world point (1.5, 2.25) is stored in the body frame as
  // R(−0.7)(0.5, 0.25) = (0.5 cos 0.7 + 0.25 sin 0.7, −0.5 sin 0.7 + 0.25 cos 0.7)
  //                    = (0.5434755, −0.1308983)
  Registry reg;
  const BodyId b = plain_body(reg, {1.0, 2.0}, 0.7);
  const PointId p = attach_point_world(reg, b, {1.5, 2.25});
  EXPECT_EQ(reg.points.body[p.index()], b);
  EXPECT_NEAR(reg.points.point[p.index()].x, 0.5434755154516671, 1e-15);
  EXPECT_NEAR(reg.points.point[p.index()].y, -0.13089829679772338, 1e-15);
  const Vec2 back = point_position(reg, p, 1.0, 2.0, 0.7);
  EXPECT_NEAR(back.x, 1.5, 1e-15);
  EXPECT_NEAR(back.y, 2.25, 1e-15);
  // the point follows the body: turned by a further π/2 about (1, 2), then moved by (1, 0)
  //   R(0.7 + π/2) p = R(π/2)(0.5, 0.25) = (−0.25, 0.5): (2 − 0.25, 2 + 0.5)
  const Vec2 moved = point_position(reg, p, 2.0, 2.0, 0.7 + 0.5 * kPi);
  EXPECT_NEAR(moved.x, 1.75, 1e-15);
  EXPECT_NEAR(moved.y, 2.5, 1e-15);
  // attach_point in the body frame gives the same point
  const PointId q = attach_point(reg, b, reg.points.point[p.index()]);
  EXPECT_EQ(reg.points.point[q.index()], reg.points.point[p.index()]);
  EXPECT_EQ(reg.points.size(), 2u);
}

TEST(SpringsPoints, RefusesUnknownBodiesAndNonFinitePoints) {
  Registry reg;
  const BodyId b = plain_body(reg, {0.0, 0.0});
  EXPECT_TRUE(Contains(error_message([&] { attach_point(reg, BodyId(4), {0.0, 0.0}); }), "unknown body id"));
  EXPECT_TRUE(Contains(error_message([&] { attach_point_world(reg, BodyId(), {0.0, 0.0}); }), "unknown body id"));
  EXPECT_TRUE(Contains(error_message([&] { attach_point(reg, b, {kNaN, 0.0}); }), "not finite"));
  EXPECT_TRUE(Contains(error_message([&] { attach_point_world(reg, b, {0.0, kInf}); }), "not finite"));
  EXPECT_TRUE(reg.points.empty());
}

// ---- one step of a body on a spring, through the stepper ----------------------------------------

// A body of mass 2 kg/m at (0, 1), no gravity, tied at its centre of mass to a fixed ground
// point at the origin: n = (0, 1), lever arm 0, w = 1/m = 0.5. From rest, L_m = L = 1 and c = 0.
// With k = 1000, ν = 0, h = 1e-3, θ = 0.5 and a spring of L0 = 1, prestrain ε0:
//   rest length L0 (1 + ε0); ha = −h k (1 − (1 + ε0)) = h k ε0; hb = h k θ h = 5e-4;
//   P = ha / (1 + hb w).
// ε0 = 0.1: P = 0.1/1.00025 = 0.0999750062, R = 99.9750062 N, v = P/m = 0.0499875031 m/s,
// y = 1 + θ h v = 1.0000249938. ε0 = 0: no force, nothing moves.
struct OneSpring {
  Registry reg;
  BodyId body;
};

OneSpring one_spring(double eps0, double L0) {
  OneSpring s;
  s.reg.params.dt = 1e-3;
  s.reg.params.theta = 0.5;
  s.reg.params.gravity = {0.0, 0.0};
  const BodyId ground = plain_body(s.reg, {0.0, 0.0}, 0.0, 1.0, 1.0, "ground");
  fix_body(s.reg, ground);
  s.body = plain_body(s.reg, {0.0, 1.0}, 0.0, 2.0, 1.0, "body");
  add_spring(s.reg, attach_point(s.reg, s.body, {0.0, 0.0}), attach_point(s.reg, ground, {0.0, 0.0}),
             VoigtRod{1000.0, 0.0, L0, eps0});
  return s;
}

TEST(SpringsStep, PrestrainShiftsTheRestLength) {
  OneSpring s = one_spring(0.1, 1.0);
  MoreauJean mj(s.reg);
  const StepReport r = mj.step();
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(s.reg.links.rn[0], 99.97500624843788, 1e-10);
  EXPECT_NEAR(s.reg.bodies.vy[s.body.index()], 0.04998750312421894, 1e-14);
  EXPECT_NEAR(s.reg.bodies.y[s.body.index()], 1.0000249937515622, 1e-15);
  EXPECT_EQ(s.reg.bodies.vx[s.body.index()], 0.0);
  EXPECT_EQ(s.reg.bodies.spin[s.body.index()], 0.0);
  EXPECT_EQ(s.reg.links.length[0], 1.0);  // the frame is taken at q_m = q_i (at rest)

  // the same with L0 left to default (the current length, 1): same answer
  OneSpring d = one_spring(0.1, 0.0);
  MoreauJean md(d.reg);
  md.step();
  EXPECT_EQ(d.reg.links.rn[0], s.reg.links.rn[0]);

  // without prestrain the spring is at rest: nothing moves
  OneSpring z = one_spring(0.0, 0.0);
  MoreauJean mz(z.reg);
  mz.step();
  EXPECT_EQ(z.reg.links.rn[0], 0.0);
  EXPECT_EQ(z.reg.bodies.y[z.body.index()], 1.0);
}

TEST(SpringsStep, StaticEquilibriumUnderGravity) {
  // with gravity g = 9.81 and ν = 10 (to damp), the body settles where k (L0 (1 + ε0) − L) = m g:
  //   L = 1.1 − 2 × 9.81/1000 = 1.08038
  OneSpring s = one_spring(0.1, 1.0);
  s.reg.params.gravity = {0.0, -9.81};
  s.reg.links.law[0].nu = 10.0;
  MoreauJean mj(s.reg);
  for (int n = 0; n < 20000; ++n) mj.step();  // ζ = ν/(2√(k m)) = 0.11, decay time 1/(ζ ω0) = 0.4 s
  EXPECT_NEAR(s.reg.bodies.y[s.body.index()], 1.1 - 2.0 * 9.81 / 1000.0, 1e-9);
  EXPECT_NEAR(s.reg.links.rn[0], 2.0 * 9.81, 1e-6);
}

}  // namespace
