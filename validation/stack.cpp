// validation/stack.cpp — a stack of boxes at rest on a fixed floor (IQS_CLB, μ = 0.5).
//
// Five boxes 0.2 m × 0.1 m (density 2000 kg/m³: m = 2000 × 0.02 = 40 kg/m each) are stacked
// exactly (gaps 0) on a fixed floor. Statics: each interface carries the weight of the boxes
// above it, the floor the whole stack,
//     Σ R_N(floor) = 5 m g = 5 × 40 × 9.81 = 1962 N/m,   Σ R_T = 0,
// and the interface between box k and box k+1 (k = 1..4, counted from the floor) carries
// (5 − k) m g. In the θ-method a resting stack is an exact fixed point: the free velocity
// −h g of every box is cancelled by the impulses (U_N = 0 at every contact), so q_{n+1} = q_n.
// What can break it is a solver that stops short (U_N ≠ 0 left over, accumulating as drift,
// because IQS_CLB does not push an overlap back out) or a warm start that feeds a wrong
// impulse. The solver is therefore run tight (Strict, tol 1e-10, checked every sweep) and the
// stack is watched for 10,000 steps: positions within 1e-9 m of the start, velocities below
// 1e-9 m/s, floor reaction within 1e-6 relative of the weight at every step after settling.
//
// Suite: Stack (five boxes; a pyramid of six pentagons, below).
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
using nscd::validation::reaction_from;
using nscd::validation::rel_err;
using nscd::validation::tight_options;


TEST(Stack, FiveBoxesRestOnTheFloorWithoutDrift) {
  Registry reg;
  reg.params.dt = 1e-3;
  reg.params.theta = 0.5;
  reg.params.gravity = {0.0, -kG};
  const MaterialId m = add_material(reg, "concrete", 2000.0);
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.5});
  const BodyId floor = add_floor(reg, m);
  constexpr int kBoxes = 5;
  constexpr double kW = 0.2, kH = 0.1;
  std::vector<BodyId> boxes;
  for (int k = 0; k < kBoxes; ++k) boxes.push_back(add_block(reg, m, kW, kH, 0.0, k * kH, "box " + std::to_string(k)));
  const double mass = reg.bodies.mass[boxes[0].index()];
  ASSERT_NEAR(mass, 40.0, 1e-12);
  const double weight = kBoxes * mass * kG;  // 1962 N/m

  StepperOptions opt = tight_options(1e-10, 100000);
  MoreauJean mj(reg, opt);
  std::vector<double> x0, y0, a0;
  for (BodyId b : boxes) {
    x0.push_back(reg.bodies.x[b.index()]);
    y0.push_back(reg.bodies.y[b.index()]);
    a0.push_back(reg.bodies.angle[b.index()]);
  }
  constexpr int kSteps = 10000, kSettle = 10;
  double worst_dq = 0.0, worst_v = 0.0, worst_rn = 0.0, worst_rt = 0.0;
  int max_sweeps = 0, sweeps_after_settle = 0;
  for (int n = 1; n <= kSteps; ++n) {
    const StepReport r = mj.step();
    ASSERT_TRUE(r.converged) << "step " << n;
    // 2 points (the two ends of each face) per interface: floor–box 0 and 4 box–box
    ASSERT_EQ(r.contacts, 2u * kBoxes) << "step " << n;
    max_sweeps = std::max(max_sweeps, r.sweeps);
    if (n <= kSettle) continue;
    sweeps_after_settle = std::max(sweeps_after_settle, r.sweeps);
    for (std::size_t k = 0; k < boxes.size(); ++k) {
      const std::size_t i = boxes[k].index();
      const double dq = std::max({std::abs(reg.bodies.x[i] - x0[k]), std::abs(reg.bodies.y[i] - y0[k]),
                                  kW * std::abs(reg.bodies.angle[i] - a0[k])});
      const double v = std::max({std::abs(reg.bodies.vx[i]), std::abs(reg.bodies.vy[i]), kW * std::abs(reg.bodies.spin[i])});
      worst_dq = std::max(worst_dq, dq);
      worst_v = std::max(worst_v, v);
      ASSERT_LT(dq, 1e-9) << "box " << k << " drifted, step " << n;
      ASSERT_LT(v, 1e-9) << "box " << k << " moves, step " << n;
    }
    const Vec2 R = reaction_from(reg, floor);
    worst_rn = std::max(worst_rn, rel_err(R.y, weight));
    worst_rt = std::max(worst_rt, std::abs(R.x) / weight);
    ASSERT_LT(rel_err(R.y, weight), 1e-6) << "step " << n;
    ASSERT_LT(std::abs(R.x) / weight, 1e-6) << "step " << n;
  }
  // each box–box interface carries the boxes above it: (5 − k) m g between box k−1 and box k
  for (int k = 1; k < kBoxes; ++k) {
    double rn = 0.0;
    for (std::size_t c = 0; c < reg.contacts.size(); ++c)
      if (reg.contacts.an_body[c] == boxes[k - 1] || reg.contacts.cd_body[c] == boxes[k - 1])
        if (reg.contacts.an_body[c] == boxes[k] || reg.contacts.cd_body[c] == boxes[k]) rn += reg.contacts.rn[c];
    EXPECT_LT(rel_err(rn, (kBoxes - k) * mass * kG), 1e-6) << "interface below box " << k;
  }
  std::printf("[ measured ] stack: max drift %.3e m, max velocity %.3e m/s, floor R_N rel err %.3e, |R_T|/W %.3e, "
              "sweeps max %d (after settling %d)\n",
              worst_dq, worst_v, worst_rn, worst_rt, max_sweeps, sweeps_after_settle);
}

// A pyramid of six regular pentagons (circumscribed radius R = 5 cm, inradius r = R cos 36°
// = 4.045 cm, density 2000: m = 2000 × (5/2) R² sin 72° = 11.89 kg/m each):
//   row 1  three upright pentagons (flat base on the floor), centres 10 cm apart (gaps 4.9 mm,
//          beyond the alert distance);
//   row 2  two inverted pentagons (vertex down) in the V's: their lower faces (normals at
//          −54° and −126°) are parallel to the upper faces of row 1 (normals at 126°, 54°) and
//          touch them, centre height Y = r + (2r − (s/2) cos 54°)/sin 54° = 10.41 cm;
//   row 3  one upright pentagon on the two flat tops of row 2, base at Y + r.
// The contact normals are not axis-aligned (36° from vertical between rows 1 and 2), the
// wedges push row 1 outward, so friction at the floor matters (μ = 0.5 suffices: the outer
// base pentagon needs H/N = 0.545 mg / 1.75 mg = 0.31). Whatever the internal forces, the
// floor carries the whole weight, Σ R_N(floor) = 6 m g, Σ R_T(floor) = 0 by symmetry; at
// rest nothing moves.
TEST(Stack, PyramidOfPentagonsRestsWithoutDrift) {
  Registry reg;
  reg.params.dt = 1e-3;
  reg.params.gravity = {0.0, -kG};
  const MaterialId m = add_material(reg, "stone", 2000.0);
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.5});
  const BodyId floor = add_floor(reg, m);
  constexpr double R = 0.05, s = 0.1;
  const double r = R * std::cos(36.0 * kPi / 180.0), c54 = std::cos(54.0 * kPi / 180.0), s54 = std::sin(54.0 * kPi / 180.0);
  const Polygon up = regular_polygon(5, 2.0 * R, 0.5 * kPi), down = regular_polygon(5, 2.0 * R, -0.5 * kPi);
  std::vector<BodyId> grains;
  for (int k = 0; k < 3; ++k) grains.push_back(add_polygon_body(reg, up, m, {k * s, r}, 0.0, "row 1"));
  const double Y = r + (2.0 * r - 0.5 * s * c54) / s54;
  for (int k = 0; k < 2; ++k) grains.push_back(add_polygon_body(reg, down, m, {(k + 0.5) * s, Y}, 0.0, "row 2"));
  grains.push_back(add_polygon_body(reg, up, m, {s, Y + 2.0 * r}, 0.0, "row 3"));
  const double mass = reg.bodies.mass[grains[0].index()];
  ASSERT_NEAR(mass, 2000.0 * 2.5 * R * R * std::sin(72.0 * kPi / 180.0), 1e-9);
  const double weight = 6.0 * mass * kG;

  MoreauJean mj(reg, tight_options(1e-10, 100000));
  std::vector<double> q0;
  for (BodyId b : grains)
    for (const double v : {reg.bodies.x[b.index()], reg.bodies.y[b.index()], reg.bodies.angle[b.index()]}) q0.push_back(v);
  double worst_dq = 0.0, worst_v = 0.0, worst_rn = 0.0;
  std::size_t contacts = 0;
  for (int n = 1; n <= 5000; ++n) {
    const StepReport rep = mj.step();
    ASSERT_TRUE(rep.converged) << "step " << n << ", residual " << rep.residual << ", iterations " << rep.sweeps;
    if (n == 1) contacts = rep.contacts;
    ASSERT_EQ(rep.contacts, contacts) << "the contact set must not change at rest, step " << n;
    if (n <= 10) continue;
    for (std::size_t k = 0; k < grains.size(); ++k) {
      const std::size_t i = grains[k].index();
      const double dq = std::max({std::abs(reg.bodies.x[i] - q0[3 * k]), std::abs(reg.bodies.y[i] - q0[3 * k + 1]),
                                  R * std::abs(reg.bodies.angle[i] - q0[3 * k + 2])});
      const double v = std::max({std::abs(reg.bodies.vx[i]), std::abs(reg.bodies.vy[i]), R * std::abs(reg.bodies.spin[i])});
      worst_dq = std::max(worst_dq, dq);
      worst_v = std::max(worst_v, v);
      ASSERT_LT(dq, 1e-9) << "grain " << k << " drifted, step " << n;
      ASSERT_LT(v, 1e-9) << "grain " << k << " moves, step " << n;
    }
    const Vec2 Rf = reaction_from(reg, floor);
    worst_rn = std::max(worst_rn, rel_err(Rf.y, weight));
    ASSERT_LT(rel_err(Rf.y, weight), 1e-6) << "step " << n;
    ASSERT_LT(std::abs(Rf.x) / weight, 1e-6) << "step " << n;
  }
  // floor: 3 faces × 2 ends; rows 1–2: 4 faces × 2; rows 2–3: 2 faces × 2
  EXPECT_EQ(contacts, 18u);
  std::printf("[ measured ] pyramid: %zu contacts, max drift %.3e m, max velocity %.3e m/s, floor R_N rel err %.3e\n",
              contacts, worst_dq, worst_v, worst_rn);
}

}  // namespace
