// validation/bad_parameters.cpp — bad input gives a clear nscd::Error naming the parameter,
// and a step refused for bad parameters loses nothing.
//
// Checked: the time step dt <= 0 (and non-finite), θ outside [0.5, 1], the alert distance,
// friction μ < 0, restitution e_n outside [0, 1] and e_t outside [−1, 1], unknown law /
// policy / sweep-order names, every NLGS option out of range, and the stepper's big_ratio.
// Then the transactional property: a registry whose parameters were made invalid after some
// steps is left bit for bit unchanged by the refused step (positions, velocities, time, step
// counter, contact table, warm-start memory), and once the parameter is repaired the run
// continues exactly as a run that was never interrupted.
//
// Suite: BadParameters.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "validation_support.hpp"
#include "nscd/core/error.hpp"
#include "nscd/registry/registry.hpp"
#include "nscd/solvers/nlgs.hpp"
#include "error_assertions.hpp"

namespace {

using nscd::testing_support::error_message;

using namespace nscd;
using nscd::validation::add_block;
using nscd::validation::add_floor;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

::testing::AssertionResult Names(const std::string& message, const std::string& parameter) {
  if (message.find(parameter) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "message \"" << message << "\" does not name \"" << parameter << "\"";
}

/// A box resting on a floor with a sliding push: contacts, forces and warm-start memory are all
/// non-trivial after a few steps.
Registry box_scene() {
  Registry reg;
  reg.params.dt = 1e-3;
  const MaterialId m = add_material(reg, "steel", 7800.0);
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.3});
  add_floor(reg, m);
  const BodyId b = add_block(reg, m, 0.2, 0.1, 0.0, 0.0);
  reg.bodies.vx[b.index()] = 0.5;
  reg.bodies.spin[b.index()] = 0.0;
  return reg;
}

TEST(BadParameters, TimeStepThetaAndAlertAreNamed) {
  for (const double dt : {0.0, -1e-3, kNaN, kInf}) {
    Registry reg = box_scene();
    reg.params.dt = dt;
    MoreauJean mj(reg);
    EXPECT_TRUE(Names(error_message([&] { mj.step(); }), "dt")) << "dt = " << dt;
    EXPECT_TRUE(Names(error_message([&] { validate(reg.params); }), "time step")) << "dt = " << dt;
  }
  for (const double theta : {0.49, 1.01, 0.0, -0.5, kNaN}) {
    Registry reg = box_scene();
    reg.params.theta = theta;
    MoreauJean mj(reg);
    EXPECT_TRUE(Names(error_message([&] { mj.step(); }), "theta")) << "theta = " << theta;
  }
  // the ends of [0.5, 1] are valid
  for (const double theta : {0.5, 1.0}) {
    Registry reg = box_scene();
    reg.params.theta = theta;
    MoreauJean mj(reg);
    EXPECT_NO_THROW(mj.step()) << "theta = " << theta;
  }
  for (const double alert : {-1e-3, kNaN}) {
    Registry reg = box_scene();
    reg.params.alert = alert;
    MoreauJean mj(reg);
    EXPECT_TRUE(Names(error_message([&] { mj.step(); }), "alert")) << "alert = " << alert;
  }
  Registry reg = box_scene();
  reg.params.gravity = {0.0, kNaN};
  MoreauJean mj(reg);
  EXPECT_TRUE(Names(error_message([&] { mj.step(); }), "gravity"));
}

TEST(BadParameters, FrictionAndRestitutionAreNamed) {
  Registry reg = box_scene();
  const MaterialId a = find_material(reg, "steel");
  const std::size_t laws_before = reg.contact_laws.laws.size();
  const std::int32_t default_before = reg.contact_laws.default_law;
  EXPECT_TRUE(Names(error_message([&] { set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, -0.1}); }), "mu"));
  EXPECT_TRUE(Names(error_message([&] { set_contact_law(reg, a, a, LawSpec{LawKind::GAP_SGR_CLB, -1e-9}); }), "mu"));
  EXPECT_TRUE(Names(error_message([&] { set_contact_law(reg, a, a, LawSpec{LawKind::IQS_CLB, kNaN}); }), "mu"));
  for (const double e_n : {-0.1, 1.5, kNaN}) {
    LawSpec law{LawKind::RST_CLB, 0.3};
    law.e_n = e_n;
    EXPECT_TRUE(Names(error_message([&] { set_default_contact_law(reg, law); }), "e_n")) << "e_n = " << e_n;
  }
  for (const double e_t : {-1.5, 1.5}) {
    LawSpec law{LawKind::RST_CLB, 0.3};
    law.e_t = e_t;
    EXPECT_TRUE(Names(error_message([&] { set_contact_law(reg, a, a, law); }), "e_t")) << "e_t = " << e_t;
  }
  // the law's name is in the message too, and nothing was added to the table
  EXPECT_TRUE(Names(error_message([&] { set_default_contact_law(reg, LawSpec{LawKind::RST_CLB, -2.0}); }), "RST_CLB"));
  EXPECT_EQ(reg.contact_laws.laws.size(), laws_before);
  EXPECT_EQ(reg.contact_laws.default_law, default_before);
  // the ends of the ranges are valid: mu = 0, e_n = 0 and 1, e_t = −1
  LawSpec edge{LawKind::RST_CLB, 0.0};
  edge.e_n = 1.0;
  edge.e_t = -1.0;
  EXPECT_NO_THROW(set_default_contact_law(reg, edge));
}

// A law written straight into the table (bypassing set_contact_law) is checked by the step.
TEST(BadParameters, LawWrittenIntoTheTableIsCheckedByTheStep) {
  Registry reg = box_scene();
  reg.contact_laws.laws[0].mu = -0.5;
  MoreauJean mj(reg);
  EXPECT_TRUE(Names(error_message([&] { mj.step(); }), "mu"));
  reg.contact_laws.laws[0].mu = 0.3;
  reg.contact_laws.laws[0].kind = LawKind::RST_CLB;
  reg.contact_laws.laws[0].e_n = 2.0;
  EXPECT_TRUE(Names(error_message([&] { mj.step(); }), "e_n"));
  EXPECT_EQ(reg.step, 0);
}

TEST(BadParameters, UnknownNamesListTheValidOnes) {
  EXPECT_EQ(parse_law_kind("IQS_CLB"), LawKind::IQS_CLB);
  EXPECT_EQ(parse_law_kind("GAP_SGR_CLB"), LawKind::GAP_SGR_CLB);
  EXPECT_EQ(parse_law_kind("RST_CLB"), LawKind::RST_CLB);
  for (const char* bad : {"IQS_CLX", "iqs_clb", "", "RST"}) {
    const std::string msg = error_message([&] { parse_law_kind(bad, "--law"); });
    EXPECT_TRUE(Names(msg, "--law")) << bad;
    EXPECT_TRUE(Names(msg, "'" + std::string(bad) + "'"));
    for (const char* valid : {"IQS_CLB", "GAP_SGR_CLB", "RST_CLB"}) EXPECT_TRUE(Names(msg, valid));
  }
  const std::string pol = error_message([] { parse_convergence_policy("Quadratic"); });
  EXPECT_TRUE(Names(pol, "Quadratic"));
  EXPECT_TRUE(Names(pol, "QM/16"));
  const std::string ord = error_message([] { parse_sweep_order("random"); });
  EXPECT_TRUE(Names(ord, "random"));
  EXPECT_TRUE(Names(ord, "shuffled"));
}

TEST(BadParameters, NlgsOptionsOutOfRangeAreNamed) {
  struct Case {
    const char* what;
    void (*spoil)(NlgsOptions&);
  };
  const Case cases[] = {
      {"tolerance", [](NlgsOptions& o) { o.tol = 0.0; }},
      {"tolerance", [](NlgsOptions& o) { o.tol = -1e-4; }},
      {"tolerance", [](NlgsOptions& o) { o.tol = kNaN; }},
      {"checks", [](NlgsOptions& o) { o.check_every = 0; }},
      {"max_sweeps", [](NlgsOptions& o) { o.max_sweeps = 0; }},
      {"min_sweeps", [](NlgsOptions& o) { o.min_sweeps = -1; }},
      {"min_sweeps", [](NlgsOptions& o) { o.min_sweeps = 50, o.max_sweeps = 10; }},
      {"relaxation", [](NlgsOptions& o) { o.relaxation = 0.0; }},
      {"relaxation", [](NlgsOptions& o) { o.relaxation = 2.0; }},
      {"relaxation", [](NlgsOptions& o) { o.relaxation = kNaN; }},
  };
  for (const Case& c : cases) {
    StepperOptions opt;
    c.spoil(opt.nlgs);
    EXPECT_TRUE(Names(error_message([&] { validate(opt.nlgs); }), c.what)) << c.what;
    Registry reg = box_scene();
    EXPECT_TRUE(Names(error_message([&] { MoreauJean mj(reg, opt); }), c.what)) << c.what;
    // set_options refuses and keeps the options in force
    MoreauJean mj(reg);
    EXPECT_TRUE(Names(error_message([&] { mj.set_options(opt); }), c.what)) << c.what;
    EXPECT_EQ(mj.options().nlgs.tol, StepperOptions{}.nlgs.tol);
    EXPECT_EQ(mj.options().nlgs.max_sweeps, StepperOptions{}.nlgs.max_sweeps);
    EXPECT_NO_THROW(mj.step());
  }
  StepperOptions opt;
  opt.big_ratio = 1.0;
  Registry reg = box_scene();
  EXPECT_TRUE(Names(error_message([&] { MoreauJean mj(reg, opt); }), "big_ratio"));
}

/// Everything a step changes, compared bit for bit.
void expect_same_state(const Registry& a, const Registry& b) {
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.bodies.x, b.bodies.x);
  EXPECT_EQ(a.bodies.y, b.bodies.y);
  EXPECT_EQ(a.bodies.angle, b.bodies.angle);
  EXPECT_EQ(a.bodies.vx, b.bodies.vx);
  EXPECT_EQ(a.bodies.vy, b.bodies.vy);
  EXPECT_EQ(a.bodies.spin, b.bodies.spin);
  EXPECT_EQ(a.contacts.size(), b.contacts.size());
  EXPECT_EQ(a.contacts.gap, b.contacts.gap);
  EXPECT_EQ(a.contacts.rn, b.contacts.rn);
  EXPECT_EQ(a.contacts.rt, b.contacts.rt);
  EXPECT_EQ(a.contacts.feature, b.contacts.feature);
}

TEST(BadParameters, RefusedStepLeavesTheRegistryUnchanged) {
  // reference run: 60 steps straight
  Registry ref = box_scene();
  MoreauJean mj_ref(ref);
  for (int n = 0; n < 60; ++n) mj_ref.step();

  // interrupted run: 30 steps, then every kind of bad parameter is refused, then 30 steps
  Registry reg = box_scene();
  MoreauJean mj(reg);
  for (int n = 0; n < 30; ++n) mj.step();
  ASSERT_FALSE(reg.contacts.empty());
  ASSERT_FALSE(mj.warm_start_memory().empty());
  const Registry snapshot = reg;
  const auto memory = mj.warm_start_memory().size();
  const Parameters good = reg.params;
  for (int which = 0; which < 4; ++which) {
    Parameters bad = good;
    if (which == 0) bad.dt = -good.dt;
    if (which == 1) bad.theta = 1.5;
    if (which == 2) bad.alert = -1.0;
    if (which == 3) bad.gravity.x = kInf;
    reg.params = bad;
    EXPECT_THROW(mj.step(), Error) << "case " << which;
    reg.params = good;
    expect_same_state(reg, snapshot);
    EXPECT_EQ(mj.warm_start_memory().size(), memory);
  }
  // a bad law written into the table is refused the same way
  reg.contact_laws.laws[0].mu = -1.0;
  EXPECT_THROW(mj.step(), Error);
  reg.contact_laws.laws[0].mu = 0.3;
  expect_same_state(reg, snapshot);
  // nothing lost: the run goes on exactly as the uninterrupted one
  for (int n = 0; n < 30; ++n) mj.step();
  expect_same_state(reg, ref);
}

}  // namespace
