// validation/disks.cpp — the round contactors (DISKx, JONCx, xKSID) in the same stepper, laws
// and solvers as the polygons, checked against analytic mechanics (issue #12).
//
//   * A disk rolling without slipping down an incline (gravity rotated by α over a horizontal
//     floor, as in incline.cpp): a = (2/3) g sin α for a solid disk (I = m R²/2) while
//     μ >= tan α / 3. The contact point stays under the centre, so the lever arms are constant
//     and the θ-method is exact: u_N = N h a, x_N − x_0 = a h² (N(N−1)/2 + θ N), ω = −u/R.
//     With μ < tan α / 3 the disk slides and spins: a = g (sin α − μ cos α), R ω̇ = −2 μ g cos α.
//     Both on a POLYG floor (DKPLx) and on a JONCx floor (DKJCx).
//   * Two equal disks, head on, RST_CLB with e_n: after the impact u₁ = v(1 − e)/2,
//     u₂ = v(1 + e)/2 (momentum conserved, relative velocity reversed times e).
//   * Resting contacts: a disk on a block on the floor (DKPLx over PLPLx), a square on a JONCx
//     (PLJCx, two points), a disk at the bottom of a fixed drum (DKKDx), a square lying in it
//     (PLKDx, two points): nothing moves, and the supports carry exactly the weight.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "nscd/contactors/round_shapes.hpp"
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

constexpr double kR = 0.05;  // disk radius (m)

enum class Floor { Polygon, Jonc };

struct DiskScene {
  Registry reg;
  BodyId floor, disk;
};

DiskScene make_rolling(double alpha, double mu, double theta, Floor floor) {
  DiskScene s;
  s.reg.params.dt = 1e-3;
  s.reg.params.theta = theta;
  s.reg.params.gravity = {kG * std::sin(alpha), -kG * std::cos(alpha)};
  const MaterialId m = add_material(s.reg, "steel", 7800.0);
  set_default_contact_law(s.reg, LawSpec{LawKind::IQS_CLB, mu});
  if (floor == Floor::Polygon) {
    s.floor = add_floor(s.reg, m);
  } else {  // a JONCx of half-thickness 0.1 whose top face is y = 0
    s.floor = add_jonc_body(s.reg, 10.0, 0.1, m, {0.0, -0.1}, 0.0, "floor");
    fix_body(s.reg, s.floor);
  }
  s.disk = add_disk_body(s.reg, kR, m, {0.0, kR}, "disk");
  return s;
}

void check_rolling(double alpha, double mu, double theta, Floor floor, const char* label) {
  DiskScene s = make_rolling(alpha, mu, theta, floor);
  MoreauJean mj(s.reg, tight_options());
  const std::size_t i = s.disk.index();
  const double h = s.reg.params.dt;
  const bool rolls = mu >= std::tan(alpha) / 3.0;
  const double a = rolls ? (2.0 / 3.0) * kG * std::sin(alpha) : kG * (std::sin(alpha) - mu * std::cos(alpha));
  const double spin_rate = rolls ? -a / kR : -2.0 * mu * kG * std::cos(alpha) / kR;  // ω̇
  const double x0 = s.reg.bodies.x[i], y0 = s.reg.bodies.y[i];
  double worst = 0.0;
  for (int n = 1; n <= 1000; ++n) {
    const StepReport r = mj.step();
    ASSERT_TRUE(r.converged) << label << " step " << n;
    ASSERT_EQ(r.contacts, 1u) << label << " step " << n;
    const double dn = n, v = dn * h * a, x = a * h * h * (0.5 * dn * (dn - 1.0) + theta * dn);
    const double e = std::max({rel_err(s.reg.bodies.vx[i], v), rel_err(s.reg.bodies.x[i] - x0, x),
                               rel_err(s.reg.bodies.spin[i], dn * h * spin_rate)});
    worst = std::max(worst, e);
    ASSERT_LT(e, 1e-8) << label << " step " << n << ": vx " << s.reg.bodies.vx[i] << " expected " << v;
    ASSERT_LT(std::abs(s.reg.bodies.y[i] - y0), 1e-10) << label << " step " << n;
  }
  // the contact force: R_N = m g cos α, R_T = m (g sin α − a) uphill
  const double m = s.reg.bodies.mass[i];
  const Vec2 R = reaction_from(s.reg, s.floor);
  EXPECT_LT(rel_err(R.y, m * kG * std::cos(alpha)), 1e-8) << label;
  EXPECT_LT(rel_err(-R.x, m * (kG * std::sin(alpha) - a)), 1e-6) << label;
  std::printf("[ measured ] %s: %s, worst relative error of v, x, omega over 1000 steps %.3e\n", label,
              rolls ? "rolls" : "slides", worst);
}

TEST(Disks, RollingDownAnInclineIsExactOnAPolygonAndOnAJonc) {
  for (const double theta : {0.5, 1.0}) {
    check_rolling(20.0 * kDeg, 0.5, theta, Floor::Polygon, theta == 0.5 ? "DKPLx roll theta 0.5" : "DKPLx roll theta 1");
    check_rolling(20.0 * kDeg, 0.5, theta, Floor::Jonc, theta == 0.5 ? "DKJCx roll theta 0.5" : "DKJCx roll theta 1");
  }
}

TEST(Disks, SlidesAndSpinsWhenMuIsBelowTanAlphaOverThree) {
  // tan 30° / 3 = 0.192 > μ = 0.1: sliding, friction μ m g cos α spins the disk up
  check_rolling(30.0 * kDeg, 0.1, 0.5, Floor::Polygon, "DKPLx slide");
  check_rolling(30.0 * kDeg, 0.1, 0.5, Floor::Jonc, "DKJCx slide");
}

TEST(Disks, HeadOnCollisionWithRestitution) {
  constexpr double v = 2.0;
  for (const double e : {0.0, 0.5, 1.0}) {
    Registry reg;
    reg.params.dt = 1e-4;
    reg.params.gravity = {0.0, 0.0};
    const MaterialId m = add_material(reg, "glass", 2500.0);
    LawSpec law{LawKind::RST_CLB, 0.3};
    law.e_n = e;
    set_default_contact_law(reg, law);
    const BodyId a = add_disk_body(reg, kR, m, {0.0, 0.0}, "a");
    const BodyId b = add_disk_body(reg, kR, m, {2.0 * kR, 0.0}, "b");  // touching, gap 0
    reg.bodies.vx[a.index()] = v;
    MoreauJean mj(reg, tight_options());
    for (int n = 0; n < 50; ++n) ASSERT_TRUE(mj.step().converged);
    EXPECT_NEAR(reg.bodies.vx[a.index()], 0.5 * v * (1.0 - e), 1e-10 * v) << "e " << e;
    EXPECT_NEAR(reg.bodies.vx[b.index()], 0.5 * v * (1.0 + e), 1e-10 * v) << "e " << e;
    EXPECT_NEAR(reg.bodies.vy[a.index()], 0.0, 1e-12);
    EXPECT_NEAR(reg.bodies.spin[b.index()], 0.0, 1e-12);
    std::printf("[ measured ] DKDKx head-on e=%.1f: u1 %.12f u2 %.12f (expected %.12f %.12f)\n", e,
                reg.bodies.vx[a.index()], reg.bodies.vx[b.index()], 0.5 * v * (1.0 - e), 0.5 * v * (1.0 + e));
  }
}

// Nothing moves over 1000 steps and the support carries the weight of what it holds.
void check_at_rest(Registry& reg, BodyId support, double weight, std::size_t contacts, const char* label) {
  const std::size_t nb = reg.bodies.size();
  std::vector<double> x0(reg.bodies.x), y0(reg.bodies.y);
  MoreauJean mj(reg, tight_options());
  for (int n = 1; n <= 1000; ++n) {
    const StepReport r = mj.step();
    ASSERT_TRUE(r.converged) << label << " step " << n;
    ASSERT_EQ(r.contacts, contacts) << label << " step " << n;
  }
  for (std::size_t i = 0; i < nb; ++i) {
    EXPECT_LT(std::abs(reg.bodies.x[i] - x0[i]), 1e-10) << label << " body " << i;
    EXPECT_LT(std::abs(reg.bodies.y[i] - y0[i]), 1e-10) << label << " body " << i;
  }
  const Vec2 R = reaction_from(reg, support);
  EXPECT_LT(rel_err(R.y, weight), 1e-9) << label;
  EXPECT_LT(std::abs(R.x), 1e-9 * weight) << label;
}

// A fixed drum of inner radius 0.5 centred on the origin (a body with an xKSID), and the law.
BodyId add_fixed_drum(Registry& reg, MaterialId m) {
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.5});
  RigidBodySpec drum_spec;
  drum_spec.name = "drum";
  drum_spec.material = m;
  drum_spec.mass = 100.0;
  drum_spec.inertia = 10.0;
  const BodyId drum = add_body(reg, drum_spec);
  attach_xksid(reg, drum, {0.0, 0.0}, 0.5);
  fix_body(reg, drum);
  return drum;
}

TEST(Disks, RestingContactsCarryTheWeight) {
  {  // a disk on a block on the floor: DKPLx over PLPLx
    Registry reg;
    const MaterialId m = add_material(reg, "stone", 2500.0);
    set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.5});
    const BodyId floor = add_floor(reg, m);
    const BodyId block = add_block(reg, m, 0.3, 0.1, 0.0, 0.0);
    const BodyId disk = add_disk_body(reg, kR, m, {0.04, 0.1 + kR});
    const double w = kG * (reg.bodies.mass[block.index()] + reg.bodies.mass[disk.index()]);
    check_at_rest(reg, floor, w, 3, "disk on block (DKPLx + PLPLx)");
  }
  {  // a square on a JONCx: PLJCx, two points
    Registry reg;
    const MaterialId m = add_material(reg, "stone", 2500.0);
    set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.5});
    const BodyId wall = add_jonc_body(reg, 1.0, 0.02, m, {0.0, -0.02}, 0.0, "wall");
    fix_body(reg, wall);
    const BodyId sq = add_block(reg, m, 0.1, 0.1, 0.3, 0.0);
    check_at_rest(reg, wall, kG * reg.bodies.mass[sq.index()], 2, "square on jonc (PLJCx)");
  }
  {  // a disk at the bottom of a fixed drum of radius 0.5: DKKDx
    Registry reg;
    const MaterialId m = add_material(reg, "stone", 2500.0);
    const BodyId drum = add_fixed_drum(reg, m);
    const BodyId disk = add_disk_body(reg, kR, m, {0.0, -0.5 + kR});
    check_at_rest(reg, drum, kG * reg.bodies.mass[disk.index()], 1, "disk in drum (DKKDx)");
  }
  {  // a square lying at the bottom of a fixed drum of radius 0.5, its two bottom corners on the
     // wall: PLKDx, two points whose normals lean toward the centre and whose sideways parts cancel
    Registry reg;
    const MaterialId m = add_material(reg, "stone", 2500.0);
    const BodyId drum = add_fixed_drum(reg, m);
    const double h = 0.05;  // half-side
    const BodyId sq = add_block(reg, m, 2 * h, 2 * h, 0.0, -std::sqrt(0.25 - h * h));
    check_at_rest(reg, drum, kG * reg.bodies.mass[sq.index()], 2, "square in drum (PLKDx)");
  }
}

}  // namespace
