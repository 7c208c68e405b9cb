// tests/unit/test_core.cpp — unit tests of src/core: the name table, TimeFunction, the
// registry's material / contact-law tables, parameter validation, Vec2/Rot2 algebra and ids.
//
// Suites: Names, TimeFunction, Registry, CoreParameters, CoreMath, CoreIds.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "nscd/core/error.hpp"
#include "nscd/core/ids.hpp"
#include "nscd/core/math.hpp"
#include "nscd/interactions/interaction_table.hpp"
#include "nscd/solvers/solver_kind.hpp"
#include "nscd/registry/registry.hpp"
#include "nscd/core/time_function.hpp"
#include "error_assertions.hpp"
#include "special_values.hpp"

namespace {

using nscd::testing_support::error_message;
using nscd::testing_support::Contains;

using namespace nscd;

using nscd::testing_support::kInf;
using nscd::testing_support::kNaN;

// ---- names --------------------------------------------------------------------------------

TEST(Names, EveryNameResolvesAndRoundTrips) {
  EXPECT_EQ(parse_contactor_kind("POLYG"), ContactorKind::POLYG);
  EXPECT_EQ(parse_interaction_kind("PLPLx"), (InteractionKind{ContactorKind::POLYG, ContactorKind::POLYG}));
  EXPECT_EQ(parse_law_kind("IQS_CLB"), LawKind::IQS_CLB);
  EXPECT_EQ(parse_law_kind("GAP_SGR_CLB"), LawKind::GAP_SGR_CLB);
  EXPECT_EQ(parse_law_kind("RST_CLB"), LawKind::RST_CLB);
  EXPECT_EQ(parse_solver_kind("NLGS"), SolverKind::NLGS);
  EXPECT_EQ(parse_solver_kind("NEWTON_AC"), SolverKind::NEWTON_AC);

  for (auto k : {ContactorKind::POLYG}) EXPECT_EQ(parse_contactor_kind(name_of(k)), k);
  for (const char* n : {"PLPLx", "DKDKx", "DKKDx", "DKPLx", "DKJCx", "PLJCx", "PLKDx", "PTPT2"})
    EXPECT_EQ(name_of(parse_interaction_kind(n)), n);
  for (auto k : {LawKind::IQS_CLB, LawKind::GAP_SGR_CLB, LawKind::RST_CLB}) EXPECT_EQ(parse_law_kind(name_of(k)), k);
  for (auto k : {SolverKind::NLGS, SolverKind::NEWTON_AC}) EXPECT_EQ(parse_solver_kind(name_of(k)), k);

  EXPECT_EQ(name_of(LawKind::GAP_SGR_CLB), "GAP_SGR_CLB");
  EXPECT_EQ(name_of(SolverKind::NEWTON_AC), "NEWTON_AC");
  EXPECT_EQ(name_of(InteractionKind{ContactorKind::POLYG, ContactorKind::POLYG}), "PLPLx");
  // the candidate comes first: a disk on a polygon is DKPLx, and no POLYG-on-DISKx kind exists
  EXPECT_EQ(name_of(InteractionKind{ContactorKind::DISKx, ContactorKind::POLYG}), "DKPLx");
  EXPECT_EQ(name_of(InteractionKind{ContactorKind::POLYG, ContactorKind::DISKx}), "?");
}

TEST(Names, UnknownNameListsTheValidOnes) {
  const std::string law = error_message([] { parse_law_kind("IQS_MOHR", "--law"); });
  EXPECT_TRUE(Contains(law, "--law"));
  EXPECT_TRUE(Contains(law, "'IQS_MOHR'"));
  for (const char* n : {"IQS_CLB", "GAP_SGR_CLB", "RST_CLB"}) EXPECT_TRUE(Contains(law, n));

  const std::string solver = error_message([] { parse_solver_kind("GAUSS_SEIDEL"); });
  EXPECT_TRUE(Contains(solver, "solver"));
  EXPECT_TRUE(Contains(solver, "NLGS"));
  EXPECT_TRUE(Contains(solver, "NEWTON_AC"));

  const std::string contactor = error_message([] { parse_contactor_kind("SPHER"); });
  EXPECT_TRUE(Contains(contactor, "'SPHER'"));
  for (const char* n : {"POLYG", "DISKx", "JONCx", "xKSID", "PT2Dx"}) EXPECT_TRUE(Contains(contactor, n));
  EXPECT_EQ(parse_contactor_kind("DISKx"), ContactorKind::DISKx);
  EXPECT_EQ(parse_interaction_kind("PLJCx"), (InteractionKind{ContactorKind::POLYG, ContactorKind::JONCx}));
  EXPECT_EQ(name_of(InteractionKind{ContactorKind::DISKx, ContactorKind::xKSID}), "DKKDx");

  const std::string inter = error_message([] { parse_interaction_kind(""); });
  for (const char* n : {"PLPLx", "DKDKx", "DKKDx", "DKPLx", "DKJCx", "PLJCx", "PLKDx", "PTPT2"}) EXPECT_TRUE(Contains(inter, n));
}

// ---- TimeFunction -------------------------------------------------------------------------

TEST(TimeFunction, DefaultAndConstant) {
  const TimeFunction zero;
  EXPECT_EQ(zero.kind(), TimeFunction::Kind::Constant);
  EXPECT_EQ(zero(3.0), 0.0);

  const TimeFunction c = TimeFunction::constant(-2.5);
  EXPECT_EQ(c.kind(), TimeFunction::Kind::Constant);
  EXPECT_EQ(c.A(), -2.5);
  EXPECT_EQ(c(0.0), -2.5);
  EXPECT_EQ(c(1e6), -2.5);
}

// The paper's vertical load (Saussine et al. 2006, §3.1): F(t) = A + B cos(2π f t − φ) with
// A = −1000, B = −500, f = 20 Hz, φ = −π, so F(t) = −1000 − 500 cos(40π t + π)
// = −1000 + 500 cos(40π t); period 1/20 = 0.05 s.
TEST(TimeFunction, CosineWithThePapersValues) {
  const TimeFunction F = TimeFunction::cosine(-1000.0, -500.0, 20.0, -kPi);
  EXPECT_EQ(F.kind(), TimeFunction::Kind::Cosine);
  EXPECT_EQ(F.A(), -1000.0);
  EXPECT_EQ(F.B(), -500.0);
  EXPECT_EQ(F.frequency(), 20.0);
  EXPECT_EQ(F.phase(), -kPi);
  EXPECT_EQ(F.ramp_duration(), 0.0);
  // F(0) = −1000 − 500 cos(π) = −500
  EXPECT_NEAR(F(0.0), -500.0, 1e-9);
  // t = 1/80 (quarter period): cos(π/2 + π) = 0  ->  −1000
  EXPECT_NEAR(F(1.0 / 80.0), -1000.0, 1e-9);
  // t = 1/40 (half period): cos(π + π) = 1  ->  −1500 (the peak load)
  EXPECT_NEAR(F(1.0 / 40.0), -1500.0, 1e-9);
  // t = 0.05 (one period): back to −500
  EXPECT_NEAR(F(0.05), -500.0, 1e-9);
  // t = 1/120: cos(π/3 + π) = −1/2  ->  −1000 + 250 = −750
  EXPECT_NEAR(F(1.0 / 120.0), -750.0, 1e-9);
}

TEST(TimeFunction, CosineLinearRamp) {
  // Same load with a 0.1 s linear ramp-in: F_r(t) = min(1, t/0.1) F(t).
  const TimeFunction F = TimeFunction::cosine(-1000.0, -500.0, 20.0, -kPi, 0.1);
  EXPECT_EQ(F.ramp_duration(), 0.1);
  EXPECT_NEAR(F(0.0), 0.0, 1e-12);                  // ramp(0) = 0
  EXPECT_NEAR(F(0.025), 0.25 * -1500.0, 1e-9);      // ramp = 1/4, F = −1500
  EXPECT_NEAR(F(0.05), 0.5 * -500.0, 1e-9);         // ramp = 1/2, F = −500
  EXPECT_NEAR(F(0.2), -500.0, 1e-9);                // ramp saturates at 1, 4 periods: −500
  EXPECT_NEAR(F(0.225), -1500.0, 1e-9);             // 4.5 periods: −1500
  EXPECT_NEAR(F(-1.0), 0.0, 1e-12);                 // before t = 0 the ramp is clamped to 0
}

TEST(TimeFunction, Lambda) {
  const TimeFunction f = TimeFunction::lambda([](double t) { return t * t - 1.0; });
  EXPECT_EQ(f.kind(), TimeFunction::Kind::Lambda);
  EXPECT_EQ(f(3.0), 8.0);
  EXPECT_EQ(f(0.0), -1.0);
  // copies share the same behaviour
  const TimeFunction g = f;
  EXPECT_EQ(g(2.0), 3.0);
}

TEST(TimeFunction, InvalidArgumentsThrow) {
  EXPECT_TRUE(Contains(error_message([] { TimeFunction::constant(kNaN); }), "constant"));
  EXPECT_THROW(TimeFunction::constant(kInf), Error);
  EXPECT_THROW(TimeFunction::cosine(kNaN, 1.0, 1.0, 0.0), Error);
  EXPECT_THROW(TimeFunction::cosine(0.0, kInf, 1.0, 0.0), Error);
  EXPECT_THROW(TimeFunction::cosine(0.0, 1.0, kNaN, 0.0), Error);
  EXPECT_THROW(TimeFunction::cosine(0.0, 1.0, 1.0, kInf), Error);
  EXPECT_TRUE(Contains(error_message([] { TimeFunction::cosine(0.0, 1.0, -20.0, 0.0); }), "frequency"));
  EXPECT_TRUE(Contains(error_message([] { TimeFunction::cosine(0.0, 1.0, 20.0, 0.0, -0.1); }), "ramp"));
  EXPECT_THROW(TimeFunction::cosine(0.0, 1.0, 20.0, 0.0, kNaN), Error);
  EXPECT_THROW(TimeFunction::cosine(0.0, 1.0, 20.0, 0.0, kInf), Error);
  EXPECT_TRUE(Contains(error_message([] { TimeFunction::lambda({}); }), "empty"));
  // a zero frequency is a valid constant-in-time cosine: A + B cos(−φ)
  EXPECT_NEAR(TimeFunction::cosine(1.0, 2.0, 0.0, 0.0)(5.0), 3.0, 1e-12);
}

// ---- registry: materials and contact laws ---------------------------------------------------

TEST(Registry, AddAndFindMaterial) {
  Registry reg;
  const MaterialId ballast = add_material(reg, "BALLAST", 2700.0);
  const MaterialId wall = add_material(reg, "WALL", 7800.0);
  EXPECT_EQ(ballast.index(), 0u);
  EXPECT_EQ(wall.index(), 1u);
  EXPECT_EQ(reg.materials.size(), 2u);
  EXPECT_EQ(reg.materials.density[wall.index()], 7800.0);
  EXPECT_EQ(find_material(reg, "WALL"), wall);
  EXPECT_EQ(find_material(reg, "BALLAST"), ballast);
  EXPECT_TRUE(Contains(error_message([&] { find_material(reg, "GRAVEL"); }), "'GRAVEL'"));
}

TEST(Registry, AddMaterialRejectsDuplicatesAndBadDensity) {
  Registry reg;
  add_material(reg, "BALLAST", 2700.0);
  const std::string dup = error_message([&] { add_material(reg, "BALLAST", 1000.0); });
  EXPECT_TRUE(Contains(dup, "'BALLAST'"));
  EXPECT_TRUE(Contains(dup, "twice"));
  for (double rho : {0.0, -1.0, kNaN, kInf}) {
    const std::string m = error_message([&] { add_material(reg, "SAND", rho); });
    EXPECT_TRUE(Contains(m, "'SAND'"));
    EXPECT_TRUE(Contains(m, "density"));
  }
  // nothing was added by the failed calls
  EXPECT_EQ(reg.materials.size(), 1u);
  EXPECT_EQ(reg.contact_laws.n_materials, 1u);
}

TEST(Registry, ContactLawLookupIsSymmetricWithDefault) {
  Registry reg;
  const MaterialId a = add_material(reg, "A", 1.0);
  const MaterialId b = add_material(reg, "B", 1.0);
  const MaterialId c = add_material(reg, "C", 1.0);
  // no law at all: pairs never interact
  EXPECT_EQ(reg.contact_laws.default_law, -1);
  EXPECT_EQ(contact_law_index(reg, a, b), -1);
  EXPECT_EQ(contact_law_index(reg, a, a), -1);

  set_contact_law(reg, a, b, LawSpec{LawKind::IQS_CLB, 0.8, 0.0, 0.0});
  EXPECT_EQ(contact_law_index(reg, a, b), 0);
  EXPECT_EQ(contact_law_index(reg, b, a), 0);  // symmetric
  EXPECT_EQ(contact_law_index(reg, a, c), -1);
  EXPECT_EQ(reg.contact_laws.laws[0].mu, 0.8);

  set_default_contact_law(reg, LawSpec{LawKind::GAP_SGR_CLB, 0.3, 0.0, 0.0});
  EXPECT_EQ(contact_law_index(reg, a, c), 1);
  EXPECT_EQ(contact_law_index(reg, c, c), 1);
  EXPECT_EQ(contact_law_index(reg, b, a), 0);  // the explicit law still wins

  // a later law for the same pair replaces the earlier one, both orders
  set_contact_law(reg, b, a, LawSpec{LawKind::RST_CLB, 0.5, 0.2, -0.1});
  EXPECT_EQ(contact_law_index(reg, a, b), 2);
  EXPECT_EQ(contact_law_index(reg, b, a), 2);
  EXPECT_EQ(reg.contact_laws.laws[2].kind, LawKind::RST_CLB);

  // a material added afterwards keeps the existing pair table and starts on the default
  const MaterialId d = add_material(reg, "D", 1.0);
  EXPECT_EQ(reg.contact_laws.n_materials, 4u);
  EXPECT_EQ(contact_law_index(reg, a, b), 2);
  EXPECT_EQ(contact_law_index(reg, d, a), 1);

  EXPECT_THROW(set_contact_law(reg, a, MaterialId(9), LawSpec{}), Error);
  EXPECT_THROW(set_contact_law(reg, MaterialId{}, a, LawSpec{}), Error);
}

TEST(Registry, LawValidation) {
  Registry reg;
  const MaterialId a = add_material(reg, "A", 1.0);
  const std::string mu = error_message([&] { set_contact_law(reg, a, a, LawSpec{LawKind::IQS_CLB, -0.1, 0.0, 0.0}); });
  EXPECT_TRUE(Contains(mu, "IQS_CLB"));
  EXPECT_TRUE(Contains(mu, "mu"));
  EXPECT_THROW(validate(LawSpec{LawKind::IQS_CLB, kNaN, 0.0, 0.0}), Error);
  EXPECT_THROW(validate(LawSpec{LawKind::IQS_CLB, kInf, 0.0, 0.0}), Error);
  for (double en : {-0.01, 1.01, kNaN}) {
    const std::string m = error_message([&] { set_default_contact_law(reg, LawSpec{LawKind::RST_CLB, 0.5, en, 0.0}); });
    EXPECT_TRUE(Contains(m, "RST_CLB"));
    EXPECT_TRUE(Contains(m, "e_n"));
  }
  // tangential restitution may be negative (Moreau's impact law) but |e_t| <= 1
  EXPECT_NO_THROW(validate(LawSpec{LawKind::RST_CLB, 0.5, 1.0, -1.0}));
  EXPECT_TRUE(Contains(error_message([] { validate(LawSpec{LawKind::RST_CLB, 0.5, 0.5, 1.5}); }), "e_t"));
  EXPECT_THROW(validate(LawSpec{LawKind::RST_CLB, 0.5, 0.5, kNaN}), Error);
  // the boundaries are valid; failed calls stored nothing
  EXPECT_NO_THROW(validate(LawSpec{LawKind::RST_CLB, 0.0, 0.0, 0.0}));
  EXPECT_NO_THROW(validate(LawSpec{LawKind::RST_CLB, 0.0, 1.0, 1.0}));
  EXPECT_TRUE(reg.contact_laws.laws.empty());
  EXPECT_EQ(reg.contact_laws.default_law, -1);
}

// ---- parameters -----------------------------------------------------------------------------

TEST(CoreParameters, DefaultsAreValid) {
  const Parameters p;
  EXPECT_NO_THROW(validate(p));
  Parameters q;
  q.theta = 1.0;
  q.alert = 0.0;
  EXPECT_NO_THROW(validate(q));
}

TEST(CoreParameters, InvalidValuesNameTheParameter) {
  auto message_with = [](auto change) {
    Parameters p;
    change(p);
    return error_message([&] { validate(p); });
  };
  EXPECT_TRUE(Contains(message_with([](Parameters& p) { p.dt = 0.0; }), "dt"));
  EXPECT_TRUE(Contains(message_with([](Parameters& p) { p.dt = -1e-4; }), "dt"));
  EXPECT_TRUE(Contains(message_with([](Parameters& p) { p.dt = kNaN; }), "dt"));
  EXPECT_TRUE(Contains(message_with([](Parameters& p) { p.dt = kInf; }), "dt"));
  EXPECT_TRUE(Contains(message_with([](Parameters& p) { p.theta = 0.49; }), "theta"));
  EXPECT_TRUE(Contains(message_with([](Parameters& p) { p.theta = 1.01; }), "theta"));
  EXPECT_TRUE(Contains(message_with([](Parameters& p) { p.theta = kNaN; }), "theta"));
  EXPECT_TRUE(Contains(message_with([](Parameters& p) { p.alert = -1e-6; }), "alert"));
  EXPECT_TRUE(Contains(message_with([](Parameters& p) { p.alert = kNaN; }), "alert"));
  EXPECT_TRUE(Contains(message_with([](Parameters& p) { p.gravity.y = kNaN; }), "gravity"));
  EXPECT_TRUE(Contains(message_with([](Parameters& p) { p.gravity.x = -kInf; }), "gravity"));
}

// ---- Vec2 / Rot2 ----------------------------------------------------------------------------

TEST(CoreMath, Vec2Algebra) {
  const Vec2 a{1.0, 2.0}, b{3.0, -1.0};
  EXPECT_EQ(a + b, (Vec2{4.0, 1.0}));
  EXPECT_EQ(a - b, (Vec2{-2.0, 3.0}));
  EXPECT_EQ(-a, (Vec2{-1.0, -2.0}));
  EXPECT_EQ(2.0 * a, (Vec2{2.0, 4.0}));
  EXPECT_EQ(a * 2.0, (Vec2{2.0, 4.0}));
  EXPECT_EQ(dot(a, b), 1.0);      // 3 − 2
  EXPECT_EQ(cross(a, b), -7.0);   // 1·(−1) − 2·3
  EXPECT_EQ(cross(b, a), 7.0);    // antisymmetric
  EXPECT_EQ(perp(Vec2{1.0, 0.0}), (Vec2{0.0, 1.0}));
  EXPECT_EQ(perp(a), (Vec2{-2.0, 1.0}));
  EXPECT_EQ(cross(a, perp(a)), dot(a, a));  // perp turns left: cross = |a|²
  EXPECT_EQ(dot(a, perp(a)), 0.0);
  EXPECT_EQ(norm(Vec2{3.0, 4.0}), 5.0);
  const Vec2 u = normalized(Vec2{3.0, 4.0});
  EXPECT_DOUBLE_EQ(u.x, 0.6);
  EXPECT_DOUBLE_EQ(u.y, 0.8);

  Vec2 c = a;
  c += b;
  EXPECT_EQ(c, (Vec2{4.0, 1.0}));
  c -= a;
  EXPECT_EQ(c, b);
  c *= -2.0;
  EXPECT_EQ(c, (Vec2{-6.0, 2.0}));
  static_assert(cross(Vec2{1.0, 0.0}, Vec2{0.0, 1.0}) == 1.0, "cross is constexpr");
}

TEST(CoreMath, Rot2) {
  const Rot2 q = Rot2::of(kPi / 2.0);
  const Vec2 ex = q.apply(Vec2{1.0, 0.0});
  EXPECT_NEAR(ex.x, 0.0, 1e-15);
  EXPECT_NEAR(ex.y, 1.0, 1e-15);
  const Vec2 v{2.0, -3.0};
  const Vec2 w = q.apply(v);  // (x, y) -> (−y, x) for +90°
  EXPECT_NEAR(w.x, 3.0, 1e-15);
  EXPECT_NEAR(w.y, 2.0, 1e-15);

  const Rot2 r = Rot2::of(0.7);
  const Vec2 back = r.apply_inverse(r.apply(v));
  EXPECT_NEAR(back.x, v.x, 1e-14);
  EXPECT_NEAR(back.y, v.y, 1e-14);
  EXPECT_NEAR(norm(r.apply(v)), norm(v), 1e-14);                 // rotations keep lengths
  const Vec2 a{1.0, 2.0};
  EXPECT_NEAR(cross(r.apply(v), r.apply(a)), cross(v, a), 1e-14);  // and orientation

  // R(α) R(β) = R(α + β)
  const Vec2 ab = Rot2::of(0.3).apply(Rot2::of(0.4).apply(v));
  const Vec2 sum = r.apply(v);
  EXPECT_NEAR(ab.x, sum.x, 1e-14);
  EXPECT_NEAR(ab.y, sum.y, 1e-14);

  const Rot2 id;
  EXPECT_EQ(id.apply(v), v);
}

// ---- ids ------------------------------------------------------------------------------------

TEST(CoreIds, DefaultIsInvalidAndIdsCompare) {
  const BodyId none;
  EXPECT_FALSE(none.valid());
  const BodyId b3(3), b5(5);
  EXPECT_TRUE(b3.valid());
  EXPECT_EQ(b3.index(), 3u);
  EXPECT_TRUE(b3 < b5);
  EXPECT_EQ(b3, BodyId(3));
  EXPECT_EQ(std::hash<BodyId>{}(b3), std::hash<BodyId>{}(BodyId(3)));
}

}  // namespace
