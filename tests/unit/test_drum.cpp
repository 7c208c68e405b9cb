// tests/unit/test_drum.cpp — the rotating drum (issue #12): the scene builder (shared/drum), the
// free-surface angle measures on a bed whose surface is known, and a disk on the wall of a
// turning ring (DKKDx): the wall's velocity enters the contact's relative velocity, so friction
// drags the disk the way the wall moves, and only friction does.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/round_shapes.hpp"
#include "nscd/core/error.hpp"
#include "nscd/laws/material_pairs.hpp"
#include "nscd/shared/drum.hpp"
#include "nscd/solvers/moreau_jean.hpp"

namespace nscd {
namespace {

constexpr double kDeg = 180.0 / kPi;

TEST(DrumScene, RadiusFromFillAndGrainsInsideWithoutOverlap) {
  scenes::DrumOptions o;
  o.grains = 200;
  o.fill = 0.45;
  const scenes::DrumScene d = scenes::drum_scene(o);
  ASSERT_EQ(d.grains.size(), 200u);
  ASSERT_EQ(d.reg.xksid.size(), 1u);
  double sum_r2 = 0.0;
  for (double r : d.reg.diskx.radius) {
    EXPECT_GE(r, o.r_min);
    EXPECT_LE(r, o.r_max);
    sum_r2 += r * r;
  }
  EXPECT_NEAR(d.radius, std::sqrt(sum_r2 / (o.fill * o.packing)), 1e-12);
  EXPECT_DOUBLE_EQ(d.reg.xksid.radius[0], d.radius);
  EXPECT_EQ(d.inner_radius, d.radius);  // a smooth wall
  EXPECT_EQ(d.bumps, 0u);
  EXPECT_EQ(scenes::grains_outside(d, 0.0), "");
  const BodyTable& b = d.reg.bodies;
  for (std::size_t i = 0; i < d.grains.size(); ++i)
    for (std::size_t j = i + 1; j < d.grains.size(); ++j) {
      const std::size_t p = d.grains[i].index(), q = d.grains[j].index();
      const double dist = std::hypot(b.x[p] - b.x[q], b.y[p] - b.y[q]);
      ASSERT_GT(dist, d.reg.diskx.radius[i] + d.reg.diskx.radius[j]) << "grains " << i << " and " << j << " overlap";
    }
  // the drum is kinematic (the driver imposes its rotation), the bed starts in the lower half
  EXPECT_EQ(b.inv_mass_x[d.drum.index()], 0.0);
  EXPECT_EQ(b.inv_inertia[d.drum.index()], 0.0);
  EXPECT_LT(scenes::bed_angle(d).centre_of_mass.y, 0.0);
  // the same seed gives the same scene
  const scenes::DrumScene again = scenes::drum_scene(o);
  EXPECT_EQ(again.reg.diskx.radius, d.reg.diskx.radius);
  EXPECT_EQ(again.reg.bodies.x, d.reg.bodies.x);
}

TEST(DrumScene, RoughWallCarriesTouchingBumpsOnTheDrum) {
  scenes::DrumOptions o;
  o.grains = 150;
  o.bump_radius = 3e-3;
  const scenes::DrumScene d = scenes::drum_scene(o);
  double sum_r2 = 0.0;
  for (std::size_t k = 0; k < d.reg.diskx.size(); ++k)
    if (d.reg.diskx.body[k] != d.drum) sum_r2 += d.reg.diskx.radius[k] * d.reg.diskx.radius[k];
  EXPECT_NEAR(d.inner_radius, std::sqrt(sum_r2 / (o.fill * o.packing)), 1e-12);
  EXPECT_NEAR(d.radius, d.inner_radius + o.bump_radius, 1e-12);
  ASSERT_EQ(d.bumps, static_cast<std::size_t>(std::floor(kPi * d.radius / o.bump_radius)));
  ASSERT_EQ(d.reg.diskx.size(), d.grains.size() + d.bumps);
  const BodyTable& b = d.reg.bodies;
  std::size_t on_drum = 0;
  for (std::size_t k = 0; k < d.reg.diskx.size(); ++k) {
    if (d.reg.diskx.body[k] != d.drum) continue;
    ++on_drum;
    EXPECT_NEAR(norm(d.reg.diskx.offset[k]), d.radius, 1e-12);
    EXPECT_EQ(d.reg.diskx.radius[k], o.bump_radius);
    for (const BodyId g : d.grains) {  // no grain starts on a bump
      const std::size_t i = g.index();
      const Vec2 c{b.x[i], b.y[i]};
      ASSERT_GT(norm(c - d.reg.diskx.offset[k]), o.bump_radius + o.r_max);
    }
  }
  EXPECT_EQ(on_drum, d.bumps);
  EXPECT_EQ(scenes::grains_outside(d, 0.0), "");  // the bumps are not grains
  o.bump_radius = -1e-3;
  EXPECT_THROW(scenes::drum_scene(o), Error);
}

TEST(DrumScene, RefusesBadOptions) {
  scenes::DrumOptions o;
  o.grains = 0;
  EXPECT_THROW(scenes::drum_scene(o), Error);
  o = {};
  o.fill = 0.6;
  EXPECT_THROW(scenes::drum_scene(o), Error);
  o = {};
  o.r_min = 5e-3;  // > r_max
  EXPECT_THROW(scenes::drum_scene(o), Error);
  o = {};
  o.packing = 1.0;
  EXPECT_THROW(scenes::drum_scene(o), Error);
  o = {};
  o.fill = 0.5;
  o.packing = 0.95;  // a bed that dense cannot come from the lattice: too few sites in the ring
  try {
    scenes::drum_scene(o);
    ADD_FAILURE() << "a lattice too small for the grains was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lower the fill fraction"), std::string::npos) << e.what();
  }
}

// A bed of equal small disks on a fine square grid filling the part of the drum below a straight
// line through (0, c) inclined by `tilt`: its surface is flat and known.
scenes::DrumScene flat_bed(double R, double tilt, double c, double h) {
  scenes::DrumScene d;
  d.radius = R;
  d.grain_material = add_material(d.reg, "grain", 1000.0);
  RigidBodySpec ring;
  ring.name = "drum";
  ring.material = d.grain_material;
  ring.mass = ring.inertia = 1.0;
  d.drum = add_body(d.reg, ring);
  attach_xksid(d.reg, d.drum, {0.0, 0.0}, R);
  fix_body(d.reg, d.drum);
  const double slope = std::tan(tilt);
  for (double x = -R + 0.5 * h; x < R; x += h)
    for (double y = -R + 0.5 * h; y < R; y += h)
      if (x * x + y * y < R * R && y < c + slope * x) d.grains.push_back(add_disk_body(d.reg, 0.45 * h, d.grain_material, {x, y}));
  return d;
}

TEST(DrumAngle, CentreOfMassAndFitGiveAFlatSurfacesInclination) {
  const double R = 0.1, h = 5e-4;
  for (double tilt_deg : {0.0, 12.0, 25.0, -30.0}) {
    const scenes::DrumScene d = flat_bed(R, tilt_deg / kDeg, -0.02, h);
    const scenes::BedAngle a = scenes::bed_angle(d);
    EXPECT_NEAR(a.angle_deg, tilt_deg, 0.1) << "tilt " << tilt_deg;
    EXPECT_NEAR(scenes::surface_fit_angle(d), tilt_deg, 0.5) << "tilt " << tilt_deg;
    // the segment's area from |OG| against the grid's count of cells
    const double fill = static_cast<double>(d.grains.size()) * h * h / (kPi * R * R);
    EXPECT_NEAR(scenes::segment_fill(R, a.distance), fill, 0.005) << "tilt " << tilt_deg;
  }
  // the measure turns with the bed: every grain turned by 20 degrees about the drum's centre
  scenes::DrumScene d = flat_bed(R, 0.0, -0.03, 1e-3);
  const double before = scenes::bed_angle(d).angle_deg, t = 20.0 / kDeg;
  for (const BodyId g : d.grains) {
    double& x = d.reg.bodies.x[g.index()];
    double& y = d.reg.bodies.y[g.index()];
    const double x0 = x, y0 = y;
    x = std::cos(t) * x0 - std::sin(t) * y0;
    y = std::sin(t) * x0 + std::cos(t) * y0;
  }
  EXPECT_NEAR(scenes::bed_angle(d).angle_deg - before, 20.0, 1e-9);
}

TEST(DrumAngle, BedMotionSeesARigidRotation) {
  scenes::DrumOptions o;
  o.grains = 40;
  scenes::DrumScene d = scenes::drum_scene(o);
  BodyTable& b = d.reg.bodies;
  for (const BodyId g : d.grains) {  // v = ω × r, ω = 0.7 rad/s about the drum's centre
    b.vx[g.index()] = -0.7 * b.y[g.index()];
    b.vy[g.index()] = 0.7 * b.x[g.index()];
  }
  const scenes::BedMotion m = scenes::bed_motion(d);
  EXPECT_NEAR(m.spin, 0.7, 1e-12);
  EXPECT_EQ(m.wall_contacts, 0u);  // no step taken: no contact yet
  EXPECT_EQ(m.wall_slip, 0.0);
}

TEST(DrumAngle, SegmentFill) {
  EXPECT_NEAR(scenes::segment_fill(2.0, 4.0 * 2.0 / (3.0 * kPi)), 0.5, 1e-12);
  EXPECT_NEAR(scenes::segment_fill(2.0, 0.0), 1.0, 1e-12);
  EXPECT_EQ(scenes::segment_fill(2.0, 2.5), 0.0);
  EXPECT_GT(scenes::segment_fill(1.0, 0.5), scenes::segment_fill(1.0, 0.6));
  EXPECT_THROW(scenes::segment_fill(0.0, 0.1), Error);
  EXPECT_THROW(scenes::segment_fill(1.0, -0.1), Error);
}

TEST(DrumAngle, GrainsOutsideAreNamed) {
  scenes::DrumOptions o;
  o.grains = 20;
  scenes::DrumScene d = scenes::drum_scene(o);
  EXPECT_EQ(scenes::grains_outside(d, 0.0), "");
  d.reg.bodies.x[d.grains[3].index()] = d.radius;  // half out
  EXPECT_NE(scenes::grains_outside(d, 1e-3).find("disk 3"), std::string::npos);
}

TEST(DrumScene, PentagonsFillTheSameAreaAndStayInside) {
  scenes::DrumOptions o;
  o.grains = 100;
  o.pentagons = true;
  o.bump_radius = 3e-3;
  const scenes::DrumScene d = scenes::drum_scene(o);
  ASSERT_EQ(d.grains.size(), 100u);
  ASSERT_EQ(d.reg.polyg.size(), 100u);  // one pentagon per grain; the bumps are the only disks
  EXPECT_EQ(d.reg.diskx.size(), d.bumps);
  double area = 0.0;
  for (const double a : d.reg.polyg.area) area += a;
  // R_in from the pentagons' own area: fill π R_in² packing = Σ area
  EXPECT_NEAR(d.inner_radius, std::sqrt(area / (kPi * o.fill * o.packing)), 1e-12);
  EXPECT_EQ(scenes::grains_outside(d, 0.0), "");
  // a pentagon pushed half out of the ring is named (its reach is its farthest vertex)
  scenes::DrumScene moved = scenes::drum_scene(o);
  moved.reg.bodies.x[moved.grains[5].index()] = moved.radius - 0.5 * moved.reg.polyg.radius[5];
  moved.reg.bodies.y[moved.grains[5].index()] = 0.0;
  EXPECT_NE(scenes::grains_outside(moved, 1e-6).find("pentagon 5"), std::string::npos);
}

// One disk resting on the bottom of a ring of radius R turning at ω (counter-clockwise: its
// bottom moves toward +x). One step of h from rest: the disk slides on the wall (ωR far above
// what friction can give in one step), so friction μ m g pushes it toward +x and spins it
// counter-clockwise: vx = μ g h, spin = μ m g r h / I = 2 μ g h / r.
struct OneStep {
  double vx, vy, spin;
};
OneStep disk_on_turning_ring(double omega, double mu) {
  Registry reg;
  reg.params.dt = 1e-3;
  const MaterialId m = add_material(reg, "stone", 2500.0);
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, mu});
  RigidBodySpec ring;
  ring.name = "drum";
  ring.material = m;
  ring.mass = 100.0;
  ring.inertia = 10.0;
  const double R = 0.5, r = 0.05;
  const BodyId drum = add_body(reg, ring);
  attach_xksid(reg, drum, {0.0, 0.0}, R);
  fix_dof(reg, drum, Dof::X);
  fix_dof(reg, drum, Dof::Y);
  impose_velocity(reg, drum, Dof::Rot, TimeFunction::constant(omega));
  const BodyId disk = add_disk_body(reg, r, m, {0.0, -R + r});
  MoreauJean mj(reg, StepperOptions{});
  const StepReport rep = mj.step();
  EXPECT_TRUE(rep.converged);
  EXPECT_EQ(reg.contacts.size(), 1u);
  const std::size_t i = disk.index();
  return {reg.bodies.vx[i], reg.bodies.vy[i], reg.bodies.spin[i]};
}

TEST(DrumWall, TurningRingDragsADiskByFriction) {
  const double g = 9.81, h = 1e-3, r = 0.05;
  const OneStep ccw = disk_on_turning_ring(1.0, 0.4);
  EXPECT_NEAR(ccw.vx, 0.4 * g * h, 1e-9);
  EXPECT_NEAR(ccw.spin, 2.0 * 0.4 * g * h / r, 1e-8);
  EXPECT_NEAR(ccw.vy, 0.0, 1e-9);  // the wall holds the disk's weight
  const OneStep cw = disk_on_turning_ring(-1.0, 0.4);  // the other way: the drag reverses
  EXPECT_NEAR(cw.vx, -0.4 * g * h, 1e-9);
  EXPECT_NEAR(cw.spin, -2.0 * 0.4 * g * h / r, 1e-8);
  const OneStep smooth = disk_on_turning_ring(1.0, 0.0);  // no friction, no drag
  EXPECT_NEAR(smooth.vx, 0.0, 1e-12);
  EXPECT_NEAR(smooth.spin, 0.0, 1e-12);
  const OneStep still = disk_on_turning_ring(0.0, 0.4);  // a ring at rest: nothing moves
  EXPECT_NEAR(still.vx, 0.0, 1e-12);
  EXPECT_NEAR(still.spin, 0.0, 1e-12);
}

}  // namespace
}  // namespace nscd
