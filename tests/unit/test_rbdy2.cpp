// tests/unit/test_rbdy2.cpp — unit tests of src/bodies (RBDY2 rigid bodies): validation of
// add_body, boundary conditions per degree of freedom (Fixed / Velocity / Force / Free), the
// external force, imposed velocities and the kinetic energy.
//
// Suites: Rbdy2AddBody, Rbdy2Drives, Rbdy2Energy.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/core/error.hpp"
#include "error_assertions.hpp"
#include "special_values.hpp"

namespace {

using nscd::testing_support::error_message;
using nscd::testing_support::Contains;

using namespace nscd;

using nscd::testing_support::kInf;
using nscd::testing_support::kNaN;

/// A body of mass 2 kg/m and inertia 0.5 kg·m²/m at (1, 2), moving at (3, −4) with spin 2.
RigidBodySpec sample_spec(const std::string& name = "grain 7") {
  RigidBodySpec s;
  s.name = name;
  s.position = {1.0, 2.0};
  s.angle = 0.25;
  s.velocity = {3.0, -4.0};
  s.spin = 2.0;
  s.mass = 2.0;
  s.inertia = 0.5;
  return s;
}

// ---- add_body ---------------------------------------------------------------------------------

TEST(Rbdy2AddBody, StoresTheState) {
  Registry reg;
  const BodyId b = add_body(reg, sample_spec());
  ASSERT_EQ(b.index(), 0u);
  const auto& t = reg.bodies;
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t.x[0], 1.0);
  EXPECT_EQ(t.y[0], 2.0);
  EXPECT_EQ(t.angle[0], 0.25);
  EXPECT_EQ(t.vx[0], 3.0);
  EXPECT_EQ(t.vy[0], -4.0);
  EXPECT_EQ(t.spin[0], 2.0);
  EXPECT_EQ(t.mass[0], 2.0);
  EXPECT_EQ(t.inertia[0], 0.5);
  EXPECT_EQ(t.inv_mass_x[0], 0.5);
  EXPECT_EQ(t.inv_mass_y[0], 0.5);
  EXPECT_EQ(t.inv_inertia[0], 2.0);
  EXPECT_EQ(t.x0[0], 1.0);
  EXPECT_EQ(t.y0[0], 2.0);
  EXPECT_EQ(t.angle0[0], 0.25);
  EXPECT_EQ(t.name[0], "grain 7");
  EXPECT_EQ(t.is_driven[0], 0);
  EXPECT_EQ(add_body(reg, sample_spec("b")).index(), 1u);
}

TEST(Rbdy2AddBody, RejectsBadDataAndNamesTheBody) {
  Registry reg;
  add_body(reg, sample_spec("first"));  // so the rejected one is "body 1"
  auto message_with = [&](auto change) {
    RigidBodySpec s = sample_spec();
    change(s);
    return error_message([&] { add_body(reg, s); });
  };
  const std::string bad[] = {
      message_with([](RigidBodySpec& s) { s.position.x = kNaN; }),
      message_with([](RigidBodySpec& s) { s.position.y = kInf; }),
      message_with([](RigidBodySpec& s) { s.angle = kNaN; }),
      message_with([](RigidBodySpec& s) { s.velocity.y = -kInf; }),
      message_with([](RigidBodySpec& s) { s.spin = kNaN; }),
      message_with([](RigidBodySpec& s) { s.mass = kNaN; }),
      message_with([](RigidBodySpec& s) { s.inertia = kInf; }),
  };
  for (const auto& m : bad) {
    EXPECT_TRUE(Contains(m, "body 1 'grain 7'"));
    EXPECT_TRUE(Contains(m, "finite"));
  }
  for (double m : {0.0, -2.0}) {
    const std::string msg = message_with([m](RigidBodySpec& s) { s.mass = m; });
    EXPECT_TRUE(Contains(msg, "'grain 7'"));
    EXPECT_TRUE(Contains(msg, "mass must be > 0"));
  }
  for (double j : {0.0, -0.5}) {
    const std::string msg = message_with([j](RigidBodySpec& s) { s.inertia = j; });
    EXPECT_TRUE(Contains(msg, "'grain 7'"));
    EXPECT_TRUE(Contains(msg, "inertia must be > 0"));
  }
  EXPECT_TRUE(Contains(message_with([](RigidBodySpec& s) { s.material = MaterialId(0); }), "material"));
  // an unnamed body is named by its index alone
  EXPECT_TRUE(Contains(message_with([](RigidBodySpec& s) { s.name.clear(); s.mass = -1.0; }), "body 1:"));
  // failed calls leave the table as it was
  EXPECT_EQ(reg.bodies.size(), 1u);
  EXPECT_EQ(reg.bodies.name.size(), 1u);
  EXPECT_EQ(reg.bodies.inv_mass_x.size(), 1u);
}

// ---- boundary conditions ----------------------------------------------------------------------

TEST(Rbdy2Drives, FixDofZeroesOnlyThatInverseMass) {
  Registry reg;
  const BodyId a = add_body(reg, sample_spec("a"));
  const BodyId b = add_body(reg, sample_spec("b"));
  fix_dof(reg, a, Dof::Y);
  EXPECT_EQ(drive_of(reg, a, Dof::Y), Drive::Fixed);
  EXPECT_EQ(drive_of(reg, a, Dof::X), Drive::Free);
  EXPECT_EQ(reg.bodies.inv_mass_x[0], 0.5);
  EXPECT_EQ(reg.bodies.inv_mass_y[0], 0.0);
  EXPECT_EQ(reg.bodies.inv_inertia[0], 2.0);
  EXPECT_EQ(reg.bodies.is_driven[0], 1);
  // the other body is untouched
  EXPECT_EQ(reg.bodies.inv_mass_y[1], 0.5);
  EXPECT_EQ(reg.bodies.is_driven[1], 0);

  fix_body(reg, b);
  EXPECT_EQ(reg.bodies.inv_mass_x[1], 0.0);
  EXPECT_EQ(reg.bodies.inv_mass_y[1], 0.0);
  EXPECT_EQ(reg.bodies.inv_inertia[1], 0.0);
  for (Dof d : {Dof::X, Dof::Y, Dof::Rot}) EXPECT_EQ(drive_of(reg, b, d), Drive::Fixed);
  EXPECT_EQ(reg.bodies.mass[1], 2.0);  // the true mass is kept
  EXPECT_EQ(reg.bodies.inv_mass_x[0], 0.5);

  // apply_imposed_velocities sets Fixed dofs to 0 and leaves free ones alone
  apply_imposed_velocities(reg, 1.0);
  EXPECT_EQ(reg.bodies.vx[0], 3.0);
  EXPECT_EQ(reg.bodies.vy[0], 0.0);
  EXPECT_EQ(reg.bodies.spin[0], 2.0);
  EXPECT_EQ(reg.bodies.vx[1], 0.0);
  EXPECT_EQ(reg.bodies.vy[1], 0.0);
  EXPECT_EQ(reg.bodies.spin[1], 0.0);
}

TEST(Rbdy2Drives, ImposedVelocityFollowsTheTimeFunction) {
  Registry reg;
  const BodyId b = add_body(reg, sample_spec());
  impose_velocity(reg, b, Dof::X, TimeFunction::lambda([](double t) { return 2.0 * t; }));
  impose_velocity(reg, b, Dof::Rot, TimeFunction::constant(-1.5));
  EXPECT_EQ(drive_of(reg, b, Dof::X), Drive::Velocity);
  EXPECT_EQ(reg.bodies.inv_mass_x[0], 0.0);
  EXPECT_EQ(reg.bodies.inv_mass_y[0], 0.5);
  EXPECT_EQ(reg.bodies.inv_inertia[0], 0.0);

  apply_imposed_velocities(reg, 1.5);
  EXPECT_EQ(reg.bodies.vx[0], 3.0);   // 2 × 1.5
  EXPECT_EQ(reg.bodies.vy[0], -4.0);  // free dof untouched
  EXPECT_EQ(reg.bodies.spin[0], -1.5);
  apply_imposed_velocities(reg, 0.25);
  EXPECT_EQ(reg.bodies.vx[0], 0.5);

  // kinematic dofs get no external force: gravity on y only, 0 on x and the moment
  reg.params.gravity = {1.0, -9.81};
  const BodyForce f = external_force(reg, b, 0.0);
  EXPECT_EQ(f.fx, 0.0);
  EXPECT_DOUBLE_EQ(f.fy, -19.62);  // 2 × (−9.81)
  EXPECT_EQ(f.m, 0.0);
}

TEST(Rbdy2Drives, ImposedForceAddsToGravity) {
  Registry reg;
  reg.params.gravity = {0.0, -9.81};
  const BodyId b = add_body(reg, sample_spec());
  // free body: weight only
  BodyForce f = external_force(reg, b, 0.0);
  EXPECT_EQ(f.fx, 0.0);
  EXPECT_DOUBLE_EQ(f.fy, -19.62);
  EXPECT_EQ(f.m, 0.0);

  // the paper's load on y: f(0) = −500, f(1/40) = −1500; a constant moment 0.3
  impose_force(reg, b, Dof::Y, TimeFunction::cosine(-1000.0, -500.0, 20.0, -kPi));
  impose_force(reg, b, Dof::Rot, TimeFunction::constant(0.3));
  EXPECT_EQ(drive_of(reg, b, Dof::Y), Drive::Force);
  EXPECT_EQ(reg.bodies.is_driven[0], 1);
  // a force keeps the dof dynamic
  EXPECT_EQ(reg.bodies.inv_mass_y[0], 0.5);
  EXPECT_EQ(reg.bodies.inv_inertia[0], 2.0);
  f = external_force(reg, b, 0.0);
  EXPECT_NEAR(f.fy, -19.62 - 500.0, 1e-9);
  EXPECT_DOUBLE_EQ(f.m, 0.3);
  f = external_force(reg, b, 1.0 / 40.0);
  EXPECT_NEAR(f.fy, -19.62 - 1500.0, 1e-9);
  EXPECT_EQ(f.fx, 0.0);

  // apply_imposed_velocities does not touch force-driven dofs
  apply_imposed_velocities(reg, 0.0);
  EXPECT_EQ(reg.bodies.vy[0], -4.0);
  EXPECT_EQ(reg.bodies.spin[0], 2.0);
}

TEST(Rbdy2Drives, LaterConditionReplacesEarlierAndFreeRestores) {
  Registry reg;
  reg.params.gravity = {0.0, -10.0};
  const BodyId b = add_body(reg, sample_spec());
  impose_velocity(reg, b, Dof::Y, TimeFunction::constant(1.0));
  impose_force(reg, b, Dof::Y, TimeFunction::constant(4.0));
  EXPECT_EQ(drive_of(reg, b, Dof::Y), Drive::Force);
  EXPECT_EQ(reg.bodies.drives.size(), 1u);
  EXPECT_EQ(reg.bodies.inv_mass_y[0], 0.5);             // no longer kinematic
  EXPECT_DOUBLE_EQ(external_force(reg, b, 0.0).fy, -16.0);  // 2 × (−10) + 4

  fix_dof(reg, b, Dof::Y);
  EXPECT_EQ(drive_of(reg, b, Dof::Y), Drive::Fixed);
  EXPECT_EQ(reg.bodies.drives.size(), 1u);
  EXPECT_EQ(reg.bodies.inv_mass_y[0], 0.0);
  EXPECT_EQ(external_force(reg, b, 0.0).fy, 0.0);

  impose_velocity(reg, b, Dof::X, TimeFunction::constant(7.0));
  EXPECT_EQ(reg.bodies.drives.size(), 2u);

  free_dof(reg, b, Dof::Y);
  EXPECT_EQ(drive_of(reg, b, Dof::Y), Drive::Free);
  EXPECT_EQ(reg.bodies.inv_mass_y[0], 0.5);
  EXPECT_EQ(reg.bodies.is_driven[0], 1);  // x is still driven
  EXPECT_DOUBLE_EQ(external_force(reg, b, 0.0).fy, -20.0);

  free_dof(reg, b, Dof::X);
  EXPECT_EQ(reg.bodies.inv_mass_x[0], 0.5);
  EXPECT_EQ(reg.bodies.is_driven[0], 0);
  EXPECT_TRUE(reg.bodies.drives.empty());
  free_dof(reg, b, Dof::Rot);  // freeing a free dof is harmless
  EXPECT_EQ(reg.bodies.inv_inertia[0], 2.0);
}

TEST(Rbdy2Drives, UnknownBodyIdsThrow) {
  Registry reg;
  add_body(reg, sample_spec());
  for (BodyId bad : {BodyId(1), BodyId(99), BodyId{}}) {
    EXPECT_TRUE(Contains(error_message([&] { fix_dof(reg, bad, Dof::X); }), "unknown body id"));
    EXPECT_THROW(fix_body(reg, bad), Error);
    EXPECT_THROW(impose_velocity(reg, bad, Dof::Y, TimeFunction::constant(1.0)), Error);
    EXPECT_THROW(impose_force(reg, bad, Dof::Rot, TimeFunction::constant(1.0)), Error);
    EXPECT_THROW(free_dof(reg, bad, Dof::X), Error);
    EXPECT_THROW(drive_of(reg, bad, Dof::X), Error);
    EXPECT_TRUE(Contains(error_message([&] { external_force(reg, bad, 0.0); }), "unknown body id"));
  }
  EXPECT_TRUE(reg.bodies.drives.empty());
}

// ---- kinetic energy -------------------------------------------------------------------------

TEST(Rbdy2Energy, KineticEnergyByHand) {
  Registry reg;
  EXPECT_EQ(kinetic_energy(reg), 0.0);
  const BodyId a = add_body(reg, sample_spec("a"));
  // ½·2·(3² + 4²) + ½·0.5·2² = 25 + 1 = 26
  EXPECT_DOUBLE_EQ(kinetic_energy(reg), 26.0);

  RigidBodySpec s = sample_spec("b");
  s.velocity = {0.0, 1.0};
  s.spin = 0.0;
  s.mass = 10.0;
  add_body(reg, s);
  // + ½·10·1² = 5
  EXPECT_DOUBLE_EQ(kinetic_energy(reg), 31.0);

  // a partly fixed body still counts (its free dofs move)
  fix_dof(reg, a, Dof::X);
  EXPECT_DOUBLE_EQ(kinetic_energy(reg), 31.0);
  // a fully fixed body does not count, whatever its stored velocity
  fix_body(reg, a);
  EXPECT_DOUBLE_EQ(kinetic_energy(reg), 5.0);
}

}  // namespace
