// validation/step_calls.cpp — MoreauJean::step() is exactly its five phases in order.
//
// step() = begin_step, detect, prepare, solve, end_step (moreau_jean.hpp). A driver that
// calls the phases itself (to dump the local problem, or to time the phases) must get the
// same run bit for bit: two copies of a small falling scene — three pentagons and a box
// dropped onto a floor and onto each other, so that contacts appear, persist and are
// warm-started — are stepped 100 times, one with step(), one with the five calls, and every
// state array is compared with ==, not within a tolerance.
//
// The phases enforce their order: any call out of sequence throws nscd::Error naming the call,
// and leaves the stepper where it was, so the correct sequence can resume and still match.
//
// Suite: StepCalls.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "validation_support.hpp"
#include "nscd/core/error.hpp"

namespace {

using namespace nscd;
using nscd::validation::add_block;
using nscd::validation::add_floor;

/// Floor, a box resting on it, two pentagons falling onto the box from 1 cm and 2 cm, a third
/// pentagon falling onto the floor beside it with a spin (contacts from step ~45 on, h = 1e-3).
Registry falling_scene() {
  Registry reg;
  reg.params.dt = 1e-3;
  reg.params.theta = 0.5;
  const MaterialId m = add_material(reg, "granite", 2700.0);
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.5});
  add_floor(reg, m, 4.0, 0.5);
  add_block(reg, m, 0.3, 0.05, 0.0, 0.0, "box");
  const Polygon p = regular_polygon(5, 0.06, 0.5 * kPi);   // flat base, inradius 0.0243
  const double r = 0.03 * std::cos(kPi / 5.0);
  add_polygon_body(reg, p, m, {-0.06, 0.05 + r + 0.01}, 0.1, "pentagon 1");
  add_polygon_body(reg, p, m, {0.05, 0.05 + r + 0.02}, -0.2, "pentagon 2");
  const BodyId spinning = add_polygon_body(reg, p, m, {0.3, r + 0.005}, 0.0, "pentagon 3");
  reg.bodies.spin[spinning.index()] = 3.0;
  return reg;
}

void expect_bitwise_equal(const Registry& a, const Registry& b, int step) {
  ASSERT_EQ(a.time, b.time) << "step " << step;
  ASSERT_EQ(a.step, b.step);
  ASSERT_EQ(a.bodies.x, b.bodies.x) << "step " << step;
  ASSERT_EQ(a.bodies.y, b.bodies.y) << "step " << step;
  ASSERT_EQ(a.bodies.angle, b.bodies.angle) << "step " << step;
  ASSERT_EQ(a.bodies.vx, b.bodies.vx) << "step " << step;
  ASSERT_EQ(a.bodies.vy, b.bodies.vy) << "step " << step;
  ASSERT_EQ(a.bodies.spin, b.bodies.spin) << "step " << step;
  ASSERT_EQ(a.contacts.size(), b.contacts.size()) << "step " << step;
  ASSERT_EQ(a.contacts.gap, b.contacts.gap) << "step " << step;
  ASSERT_EQ(a.contacts.point, b.contacts.point) << "step " << step;
  ASSERT_EQ(a.contacts.rn, b.contacts.rn) << "step " << step;
  ASSERT_EQ(a.contacts.rt, b.contacts.rt) << "step " << step;
  ASSERT_EQ(a.contacts.status, b.contacts.status) << "step " << step;
}

TEST(StepCalls, StepEqualsTheFivePhasesBitForBit) {
  Registry a = falling_scene(), b = falling_scene();
  MoreauJean ma(a), mb(b);
  std::size_t max_contacts = 0, warm = 0;
  for (int n = 1; n <= 100; ++n) {
    const StepReport ra = ma.step();
    mb.begin_step();
    mb.detect();
    mb.prepare();
    mb.solve();
    mb.end_step();
    const StepReport& rb = mb.report();
    expect_bitwise_equal(a, b, n);
    ASSERT_EQ(ra.step, rb.step);
    ASSERT_EQ(ra.sweeps, rb.sweeps) << "step " << n;
    ASSERT_EQ(ra.contacts, rb.contacts);
    ASSERT_EQ(ra.active, rb.active);
    ASSERT_EQ(ra.warm_started, rb.warm_started);
    ASSERT_EQ(ra.max_overlap, rb.max_overlap);
    ASSERT_EQ(ma.impulses(), mb.impulses());
    max_contacts = std::max(max_contacts, ra.contacts);
    warm += ra.warm_started;
  }
  // the scene did what it is for: several contacts, warm-started from step to step
  EXPECT_GE(max_contacts, 6u);
  EXPECT_GT(warm, 50u);
}

/// Expects `call` to throw nscd::Error whose message names `name`.
template <class F>
void expect_out_of_order(F&& call, const std::string& name) {
  try {
    call();
    ADD_FAILURE() << name << " did not throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
  }
}

TEST(StepCalls, OutOfOrderCallsThrowAndChangeNothing) {
  Registry a = falling_scene(), b = falling_scene();
  MoreauJean ma(a), mb(b);
  for (int n = 1; n <= 100; ++n) {
    ma.step();
    // before begin_step: everything but begin_step (and step) is refused
    expect_out_of_order([&] { mb.detect(); }, "detect");
    expect_out_of_order([&] { mb.prepare(); }, "prepare");
    expect_out_of_order([&] { mb.solve(); }, "solve");
    expect_out_of_order([&] { mb.end_step(); }, "end_step");
    mb.begin_step();
    expect_out_of_order([&] { mb.begin_step(); }, "begin_step");
    expect_out_of_order([&] { mb.step(); }, "begin_step");  // step() starts with begin_step
    expect_out_of_order([&] { mb.prepare(); }, "prepare");
    expect_out_of_order([&] { mb.solve(); }, "solve");
    expect_out_of_order([&] { mb.end_step(); }, "end_step");
    EXPECT_THROW(mb.local_problem(), Error);  // not before prepare
    mb.detect();
    expect_out_of_order([&] { mb.detect(); }, "detect");
    expect_out_of_order([&] { mb.solve(); }, "solve");
    expect_out_of_order([&] { mb.end_step(); }, "end_step");
    expect_out_of_order([&] { mb.begin_step(); }, "begin_step");
    mb.prepare();
    expect_out_of_order([&] { mb.prepare(); }, "prepare");
    expect_out_of_order([&] { mb.end_step(); }, "end_step");
    expect_out_of_order([&] { mb.detect(); }, "detect");
    mb.solve();
    expect_out_of_order([&] { mb.solve(); }, "solve");
    expect_out_of_order([&] { mb.begin_step(); }, "begin_step");
    expect_out_of_order([&] { mb.prepare(); }, "prepare");
    mb.end_step();
    expect_out_of_order([&] { mb.end_step(); }, "end_step");
    // the refused calls changed nothing: still bit for bit the plain run
    expect_bitwise_equal(a, b, n);
  }
}

}  // namespace
