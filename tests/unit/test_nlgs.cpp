// tests/unit/test_nlgs.cpp — unit tests of the stand-alone NLGS (src/solvers/nlgs.hpp) on small
// FrictionProblem2D built by hand, of its options, and of the problem dump (local_problem.hpp).
//
// Problems (W and q written out below, solutions computed by hand):
//   one contact              NLGS = the exact local solve after one sweep
//   two decoupled contacts   each contact its own local solve
//   block on two points      a rigid block resting on two supports: W 4×4 from its H, weight in q
//   frictionless chain       three bodies stacked on a floor, normal and tangential decoupled
// Suites: NlgsSolve, NlgsAll/NlgsPolicies, NlgsOrders, NlgsOptions, NlgsParse, NlgsNaturalMap, NlgsDump.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "nscd/core/error.hpp"
#include "nscd/laws/coulomb2d.hpp"
#include "nscd/solvers/contact_solver.hpp"
#include "nscd/solvers/local_problem.hpp"
#include "nscd/solvers/nlgs.hpp"
#include "temp_path.hpp"

namespace {

using namespace nscd;

/// Builds a problem from a dense 2nc×2nc W (row-major), keeping its non-zero entries as
/// triplets (the diagonal entries always, so that every diagonal block exists).
FrictionProblem2D from_dense(std::size_t nc, const std::vector<double>& W, std::vector<double> q, std::vector<double> mu) {
  std::vector<std::uint32_t> rows, cols;
  std::vector<double> vals;
  for (std::uint32_t i = 0; i < 2 * nc; ++i)
    for (std::uint32_t j = 0; j < 2 * nc; ++j) {
      const double v = W[i * 2 * nc + j];
      if (v == 0.0 && i != j) continue;
      rows.push_back(i);
      cols.push_back(j);
      vals.push_back(v);
    }
  return FrictionProblem2D::from_triplets(nc, rows, cols, vals, std::move(q), std::move(mu));
}

/// Tight options: converged means the impulses are fixed to ~1e-10 relative (the slowest
/// problem here, the chain, converges by a factor ~0.9 per sweep: the error is ~10× the last change).
NlgsOptions tight(ConvergencePolicy p = ConvergencePolicy::Quad) {
  NlgsOptions o;
  o.policy = p;
  o.tol = 1e-12;
  o.check_every = 1;
  o.max_sweeps = 20000;
  return o;
}

// ---- the problems --------------------------------------------------------------------------------

// One contact: W = [[2, 0.5], [0.5, 2]], q = (−1.75, 2), μ = 0.5. The local solve (see
// test_coulomb2d.cpp, forward slide) gives P = (1, −0.5).
FrictionProblem2D one_contact() { return from_dense(1, {2.0, 0.5, 0.5, 2.0}, {-1.75, 2.0}, {0.5}); }

// Two decoupled contacts: contact 0 as above; contact 1 W = diag(2, 4), q = (−2, 0.4), μ = 0.5:
// stick, P = (1, −0.1).
FrictionProblem2D two_decoupled() {
  return from_dense(2,
                    {2.0, 0.5, 0.0, 0.0,  //
                     0.5, 2.0, 0.0, 0.0,  //
                     0.0, 0.0, 2.0, 0.0,  //
                     0.0, 0.0, 0.0, 4.0},
                    {-1.75, 2.0, -2.0, 0.4}, {0.5, 0.5});
}

// A rigid block (mass m = 2, inertia I = 0.05 about its centre) resting on a fixed floor on two
// points at x_1 = −0.1 and x_2 = 0.3 from its centre, c = 0.05 below it; n = (0, 1), t = (−1, 0).
// With velocity (v_x, v_y, ω): U_N = v_y + ω x_α and U_T = −v_x − ω c, so the rows of H* are
// N_α = (0, 1, x_α), T_α = (−1, 0, −c) and W_αβ = H*_α M⁻¹ H_β, M⁻¹ = diag(1/m, 1/m, 1/I):
//   NN = 1/m + x_α x_β / I,  NT = −x_α c / I,  TN = −c x_β / I,  TT = 1/m + c² / I = 0.55.
//   W_11 = [[0.5 + 0.01/0.05 = 0.7, 0.1], [0.1, 0.55]]    W_22 = [[0.5 + 0.09/0.05 = 2.3, −0.3], [−0.3, 0.55]]
//   W_12 = [[0.5 − 0.03/0.05 = −0.1, 0.1], [−0.3, 0.55]]  W_21 = W_12ᵀ
// q: the block starts at rest, gravity g h = 10 · 1e-3 gives u_free = (0, −0.01, 0): q_α = (−0.01, 0).
// At rest at the end of the step the impulses balance the weight impulse m g h = 0.02 and its
// moment: P_N1 + P_N2 = 0.02, x_1 P_N1 + x_2 P_N2 − c (P_T1 + P_T2) = 0 with P_T1 + P_T2 = 0
// (no horizontal motion), hence P_N1 = 0.02 · 0.3/0.4 = 0.015 and P_N2 = 0.02 · 0.1/0.4 = 0.005.
// (W has rank 3: only the sum P_T1 + P_T2 is determined.)
FrictionProblem2D block_on_two_points(double mu = 0.5) {
  return from_dense(2,
                    {0.7, 0.1, -0.1, 0.1,    //
                     0.1, 0.55, -0.3, 0.55,  //
                     -0.1, -0.3, 2.3, -0.3,  //
                     0.1, 0.55, -0.3, 0.55},
                    {-0.01, 0.0, -0.01, 0.0}, {mu, mu});
}

// Three bodies of masses 1, 2, 3 stacked on a fixed floor (contact 0: floor–body 0, contact 1:
// body 0–body 1, contact 2: body 1–body 2), translations only. U_N of contact j is
// v_y(j) − v_y(j−1), U_T the same with v_x; W_NN = W_TT = the chain matrix
//   [[1/1, −1/1, 0], [−1/1, 1/1 + 1/2, −1/2], [0, −1/2, 1/2 + 1/3]],  W_NT = 0.
// q_N = (−g h, 0, 0) with g h = 0.01 (all bodies fall together); q_T = lateral sliding velocities.
// At rest each contact carries the weight above it: P_N = g h (1+2+3, 2+3, 3) = (0.06, 0.05, 0.03).
FrictionProblem2D chain(double mu, std::array<double, 3> qt) {
  const double a = 1.0, b = -1.0, c = 1.5, d = -0.5, e = 0.5 + 1.0 / 3.0;
  return from_dense(3,
                    {a, 0, b, 0, 0, 0,  //
                     0, a, 0, b, 0, 0,  //
                     b, 0, c, 0, d, 0,  //
                     0, b, 0, c, 0, d,  //
                     0, 0, d, 0, e, 0,  //
                     0, 0, 0, d, 0, e},
                    {-0.01, qt[0], 0.0, qt[1], 0.0, qt[2]}, {mu, mu, mu});
}

// ---- known solutions ------------------------------------------------------------------------------

TEST(NlgsSolve, OneContactIsTheLocalSolve) {
  const FrictionProblem2D p = one_contact();
  std::vector<double> r;
  NlgsOptions o = tight();
  const NlgsResult res = nlgs_solve(p, r, o);
  ASSERT_TRUE(res.converged);
  // Sweep 1 moves r from 0 to the local solution; sweep 2 changes nothing: converged at 2.
  EXPECT_EQ(res.sweeps, 2);
  ASSERT_EQ(r.size(), 2u);
  const LocalImpulse loc = solve_coulomb_2d({2.0, 0.5, 2.0}, -1.75, 2.0, 0.5);
  EXPECT_EQ(r[0], loc.pn);
  EXPECT_EQ(r[1], loc.pt);
  EXPECT_DOUBLE_EQ(r[0], 1.0);
  EXPECT_DOUBLE_EQ(r[1], -0.5);
  EXPECT_LT(natural_map_error(p, r).natural_map, 1e-14);
}

TEST(NlgsSolve, TwoDecoupledContacts) {
  const FrictionProblem2D p = two_decoupled();
  std::vector<double> r;
  const NlgsResult res = nlgs_solve(p, r, tight());
  ASSERT_TRUE(res.converged);
  EXPECT_EQ(res.sweeps, 2);
  EXPECT_DOUBLE_EQ(r[0], 1.0);   // forward slide
  EXPECT_DOUBLE_EQ(r[1], -0.5);
  EXPECT_DOUBLE_EQ(r[2], 1.0);   // stick
  EXPECT_DOUBLE_EQ(r[3], -0.1);
  EXPECT_LT(natural_map_error(p, r).natural_map, 1e-14);
}

TEST(NlgsSolve, BlockOnTwoPointsSharesTheWeightByTheTorqueBalance) {
  const FrictionProblem2D p = block_on_two_points();
  std::vector<double> r;
  const NlgsResult res = nlgs_solve(p, r, tight());
  ASSERT_TRUE(res.converged) << res.sweeps;
  EXPECT_NEAR(r[0] + r[2], 0.02, 1e-11);  // weight impulse m g h
  EXPECT_NEAR(r[0], 0.015, 1e-11);        // share 0.3 / 0.4
  EXPECT_NEAR(r[2], 0.005, 1e-11);        // share 0.1 / 0.4
  EXPECT_NEAR(r[1] + r[3], 0.0, 1e-11);   // no horizontal impulse
  EXPECT_LE(std::abs(r[1]), 0.5 * r[0] + 1e-15);
  EXPECT_LE(std::abs(r[3]), 0.5 * r[2] + 1e-15);
  // The block ends at rest: U = W r + q = 0 at both contacts.
  std::vector<double> u;
  p.multiply(r, u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(u[k] + p.q[k], 0.0, 1e-11) << k;
  EXPECT_LT(natural_map_error(p, r).relative_q, 1e-9);
}

TEST(NlgsSolve, FrictionlessChainCarriesTheWeightAbove) {
  // Lateral velocities q_T: without friction nothing resists them, P_T = 0.
  const FrictionProblem2D p = chain(0.0, {0.2, -0.1, 0.3});
  std::vector<double> r;
  const NlgsResult res = nlgs_solve(p, r, tight());
  ASSERT_TRUE(res.converged) << res.sweeps;
  EXPECT_NEAR(r[0], 0.06, 1e-11);
  EXPECT_NEAR(r[2], 0.05, 1e-11);
  EXPECT_NEAR(r[4], 0.03, 1e-11);
  for (int k : {1, 3, 5}) EXPECT_EQ(r[k], 0.0);
  EXPECT_LT(natural_map_error(p, r).relative_q, 1e-9);
}

// ---- convergence policies ---------------------------------------------------------------------------

class NlgsPolicies : public ::testing::TestWithParam<ConvergencePolicy> {};

TEST_P(NlgsPolicies, ConvergeOnTheHandProblems) {
  NlgsOptions o;
  o.policy = GetParam();
  o.tol = 1e-8;
  o.max_sweeps = 20000;
  const std::vector<FrictionProblem2D> problems = {one_contact(), two_decoupled(), block_on_two_points(),
                                                   chain(0.0, {0.2, -0.1, 0.3}), chain(0.3, {0.02, -0.03, 0.05})};
  for (std::size_t k = 0; k < problems.size(); ++k) {
    std::vector<double> r;
    const NlgsResult res = nlgs_solve(problems[k], r, o);
    EXPECT_TRUE(res.converged) << "problem " << k << ", " << res.sweeps << " sweeps";
    EXPECT_LT(res.sweeps, o.max_sweeps) << "problem " << k;
    EXPECT_LT(natural_map_error(problems[k], r).relative_q, 1e-6) << "problem " << k;
  }
  // The block's shares, whatever the policy.
  std::vector<double> r;
  nlgs_solve(problems[2], r, o);
  EXPECT_NEAR(r[0], 0.015, 1e-7);
  EXPECT_NEAR(r[2], 0.005, 1e-7);
}

INSTANTIATE_TEST_SUITE_P(NlgsAll, NlgsPolicies,
                         ::testing::Values(ConvergencePolicy::Quad, ConvergencePolicy::Maxm, ConvergencePolicy::QM16,
                                           ConvergencePolicy::Strict, ConvergencePolicy::NonStrict,
                                           ConvergencePolicy::Energy),
                         [](const auto& info) {
                           std::string n(name_of(info.param));
                           return n == "QM/16" ? std::string("QM16") : n;
                         });

// ---- sweep orders and relaxation --------------------------------------------------------------------

// The chain with friction has a unique solution: W_NT = 0 decouples the directions, the normal
// problem is an LCP with the SPD chain matrix (unique P_N), then the tangential one a strictly
// convex QP on the box |P_T| <= μ P_N (unique P_T). Every order and relaxation must find it.
TEST(NlgsOrders, OrdersAndRelaxationsGiveTheSameSolution) {
  const FrictionProblem2D p = chain(0.3, {0.02, -0.03, 0.05});
  std::vector<double> ref;
  ASSERT_TRUE(nlgs_solve(p, ref, tight()).converged);
  // By hand: P_N = (0.06, 0.05, 0.03) as without friction; cone limits μ P_N = (0.018, 0.015,
  // 0.009). Free tangential body velocities from q_T: v_0 = 0.02, v_1 = v_0 − 0.03 = −0.01,
  // v_2 = v_1 + 0.05 = 0.04. Guess: contacts 0 and 1 stick (v_0 = v_1 = 0), contact 2 slides
  // forward, P_T2 = −0.009. Then v_2 = 0.04 − 0.009/3 = 0.037 = U_T2 > 0 (consistent);
  // body 1: −0.01 + (P_T1 − P_T2)/2 = 0 -> P_T1 = 0.011 (<= 0.015); body 0: 0.02 + P_T0 − P_T1 = 0
  // -> P_T0 = −0.009 (<= 0.018). All consistent: r = (0.06, −0.009, 0.05, 0.011, 0.03, −0.009).
  const std::vector<double> expected = {0.06, -0.009, 0.05, 0.011, 0.03, -0.009};
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(ref[k], expected[k], 1e-11) << k;
  std::vector<double> u;
  p.multiply(ref, u);
  EXPECT_NEAR(u[5] + p.q[5], 0.037, 1e-11);  // contact 2 slides
  EXPECT_NEAR(u[1] + p.q[1], 0.0, 1e-11);    // contacts 0 and 1 stick
  EXPECT_NEAR(u[3] + p.q[3], 0.0, 1e-11);
  for (const SweepOrder order : {SweepOrder::Fixed, SweepOrder::Reversed, SweepOrder::Shuffled, SweepOrder::Alternating})
    for (const double omega : {0.8, 1.0, 1.2}) {
      NlgsOptions o = tight();
      o.order = order;
      o.relaxation = omega;
      o.check_every = 10;  // relaxed sweeps between checks (a checked sweep is plain)
      o.seed = 42;
      std::vector<double> r;
      const NlgsResult res = nlgs_solve(p, r, o);
      ASSERT_TRUE(res.converged) << name_of(order) << " ω = " << omega;
      for (int k = 0; k < 6; ++k) EXPECT_NEAR(r[k], ref[k], 1e-9) << name_of(order) << " ω = " << omega << " k " << k;
      EXPECT_LT(natural_map_error(p, r).relative_q, 1e-8);
    }
}

TEST(NlgsOrders, ShuffledIsDeterministicForASeed) {
  const FrictionProblem2D p = block_on_two_points();
  NlgsOptions o;
  o.order = SweepOrder::Shuffled;
  o.seed = 7;
  o.max_sweeps = 13;
  o.min_sweeps = 13;
  std::vector<double> a, b;
  nlgs_solve(p, a, o);
  nlgs_solve(p, b, o);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(a[k], b[k]);
}

// ---- options: min / max sweeps, validation -------------------------------------------------------------

TEST(NlgsOptions, MinSweepsIsRespected) {
  // One contact converges at sweep 2 with a check every sweep; min_sweeps holds it to 50.
  NlgsOptions o = tight();
  o.min_sweeps = 50;
  std::vector<double> r;
  NlgsResult res = nlgs_solve(one_contact(), r, o);
  EXPECT_TRUE(res.converged);
  EXPECT_EQ(res.sweeps, 50);
  // With a check every 10 sweeps and min_sweeps 25 the first check past 25 is at 30.
  o.check_every = 10;
  o.min_sweeps = 25;
  r.clear();
  res = nlgs_solve(one_contact(), r, o);
  EXPECT_TRUE(res.converged);
  EXPECT_EQ(res.sweeps, 30);
  // Default check every 10: one contact converges at the first check, sweep 10.
  o.min_sweeps = 0;
  r.clear();
  EXPECT_EQ(nlgs_solve(one_contact(), r, o).sweeps, 10);
}

TEST(NlgsOptions, MaxSweepsReachedWithoutConvergence) {
  // The chain needs many Gauss–Seidel sweeps to carry the floor's impulse up: 7 are too few for
  // a tolerance of 1e-12; the last sweep is checked even though 7 is not a multiple of 10.
  NlgsOptions o;
  o.policy = ConvergencePolicy::Strict;
  o.tol = 1e-12;
  o.max_sweeps = 7;
  std::vector<double> r;
  const NlgsResult res = nlgs_solve(chain(0.0, {0.0, 0.0, 0.0}), r, o);
  EXPECT_FALSE(res.converged);
  EXPECT_EQ(res.sweeps, 7);
  EXPECT_GT(res.criteria.maxm_dv, 1.0);
  EXPECT_EQ(res.criteria.n_active, 3u);
}

TEST(NlgsOptions, WarmStartFromTheSolutionConvergesAtOnce) {
  const FrictionProblem2D p = block_on_two_points();
  std::vector<double> r;
  ASSERT_TRUE(nlgs_solve(p, r, tight()).converged);
  NlgsOptions o = tight();
  const NlgsResult res = nlgs_solve(p, r, o);
  EXPECT_TRUE(res.converged);
  EXPECT_EQ(res.sweeps, 1);
}

TEST(NlgsOptions, InvalidOptionsThrow) {
  const FrictionProblem2D p = one_contact();
  auto expect_throw = [&](auto change, const char* what) {
    NlgsOptions o;
    change(o);
    std::vector<double> r;
    EXPECT_THROW(nlgs_solve(p, r, o), Error) << what;
    EXPECT_THROW(validate(o), Error) << what;
  };
  expect_throw([](NlgsOptions& o) { o.tol = 0.0; }, "tol = 0");
  expect_throw([](NlgsOptions& o) { o.tol = -1e-4; }, "tol < 0");
  expect_throw([](NlgsOptions& o) { o.tol = std::nan(""); }, "tol NaN");
  expect_throw([](NlgsOptions& o) { o.check_every = 0; }, "check_every = 0");
  expect_throw([](NlgsOptions& o) { o.min_sweeps = 20; o.max_sweeps = 10; }, "max < min");
  expect_throw([](NlgsOptions& o) { o.relaxation = 0.0; }, "relaxation 0");
  expect_throw([](NlgsOptions& o) { o.relaxation = 2.0; }, "relaxation 2");
  expect_throw([](NlgsOptions& o) { o.relaxation = -0.5; }, "relaxation < 0");
  expect_throw([](NlgsOptions& o) { o.threads = 0; }, "threads 0");
  expect_throw([](NlgsOptions& o) { o.threads = 257; }, "threads 257");
  expect_throw([](NlgsOptions& o) { o.threads = 2; }, "threads 2, fixed order");
  {  // valid options, but a stand-alone problem has no bodies to colour by
    NlgsOptions o;
    o.order = SweepOrder::Colored;
    o.threads = 2;
    EXPECT_NO_THROW(validate(o));
    std::vector<double> r;
    EXPECT_THROW(nlgs_solve(p, r, o), Error);
  }
  // The limits themselves are fine.
  NlgsOptions o;
  o.min_sweeps = o.max_sweeps = 10;
  o.relaxation = 1.99;
  o.check_every = 2;
  EXPECT_NO_THROW(validate(o));
  // a check every sweep leaves no sweep to relax: refused rather than silently plain
  o.check_every = 1;
  EXPECT_THROW(validate(o), Error);
  o.relaxation = 1.0;
  EXPECT_NO_THROW(validate(o));
}

// ---- names ---------------------------------------------------------------------------------------------

TEST(NlgsParse, PolicyAndOrderNamesRoundTrip) {
  for (const ConvergencePolicy p : {ConvergencePolicy::Quad, ConvergencePolicy::Maxm, ConvergencePolicy::QM16,
                                    ConvergencePolicy::Strict, ConvergencePolicy::NonStrict, ConvergencePolicy::Energy})
    EXPECT_EQ(parse_convergence_policy(name_of(p)), p) << name_of(p);
  EXPECT_EQ(name_of(ConvergencePolicy::QM16), "QM/16");
  for (const SweepOrder o : {SweepOrder::Fixed, SweepOrder::Reversed, SweepOrder::Shuffled, SweepOrder::Alternating,
                           SweepOrder::Colored})
    EXPECT_EQ(parse_sweep_order(name_of(o)), o) << name_of(o);
  EXPECT_EQ(name_of(SweepOrder::Shuffled), "shuffled");
}

TEST(NlgsParse, UnknownNamesThrow) {
  EXPECT_THROW(parse_convergence_policy("quad"), Error);  // names are case sensitive
  EXPECT_THROW(parse_convergence_policy("QM16"), Error);
  EXPECT_THROW(parse_convergence_policy(""), Error);
  EXPECT_THROW(parse_sweep_order("random"), Error);
  EXPECT_THROW(parse_sweep_order("Fixed"), Error);
  try {
    parse_convergence_policy("Exact");
    FAIL() << "did not throw";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("Exact"), std::string::npos) << m;
    EXPECT_NE(m.find("QM/16"), std::string::npos) << m;  // lists the valid names
  }
}

// ---- natural-map error ---------------------------------------------------------------------------------

// One contact, W = I: u = r + q; the error is |r − P_K(r − (u + μ|u_T| e_N))|.
TEST(NlgsNaturalMap, HandValues) {
  auto single = [](double qn, double qt, double mu) {
    return from_dense(1, {1.0, 0.0, 0.0, 1.0}, {qn, qt}, {mu});
  };
  // Open frictionless contact, r = 0 (exact): u = (1, 0), z = (−1, 0) in the polar cone -> 0.
  // (An earlier version read |z_T| <= μ z_N as 0 <= −0 for μ = 0 and reported 1.)
  EXPECT_EQ(natural_map_error(single(1.0, 0.0, 0.0), {0.0, 0.0}).natural_map, 0.0);
  // Open frictionless contact sliding freely: u = (1, 0.5), z = (−1, −0.5) -> 0.
  EXPECT_EQ(natural_map_error(single(1.0, 0.5, 0.0), {0.0, 0.0}).natural_map, 0.0);
  // Open with friction: z = (−1 − 0.5·0.5, −0.5) in the polar cone -> 0.
  EXPECT_EQ(natural_map_error(single(1.0, 0.5, 0.5), {0.0, 0.0}).natural_map, 0.0);
  // Closing contact left at r = 0: u = (−1, 0), z = (1, 0) inside the cone -> |r − z| = 1;
  // |q| = |u| = 1, |r| = 0: both relative errors 1.
  ProblemError e = natural_map_error(single(-1.0, 0.0, 0.5), {0.0, 0.0});
  EXPECT_DOUBLE_EQ(e.natural_map, 1.0);
  EXPECT_DOUBLE_EQ(e.relative_q, 1.0);
  EXPECT_DOUBLE_EQ(e.relative_siconos, 1.0);
  // Its solution r = (1, 0): u = 0, z = r -> 0.
  EXPECT_EQ(natural_map_error(single(-1.0, 0.0, 0.5), {1.0, 0.0}).natural_map, 0.0);
  // Too much impulse, r = (2, 0): u = (1, 0), z = (1, 0) -> error 1; Siconos divides by
  // max(|q|, |r|, |u|) = 2: 0.5.
  e = natural_map_error(single(-1.0, 0.0, 0.5), {2.0, 0.0});
  EXPECT_DOUBLE_EQ(e.natural_map, 1.0);
  EXPECT_DOUBLE_EQ(e.relative_q, 1.0);
  EXPECT_DOUBLE_EQ(e.relative_siconos, 0.5);
  // Sliding solution of q = (−1, 2), μ = 0.5: r = (1, −0.5), u = (0, 1.5); z = (1 − 0.75, −2)
  // projects on the edge s = −1: d = (0.25 + 1)/1.25 = 1 -> (1, −0.5) = r: error 0.
  EXPECT_NEAR(natural_map_error(single(-1.0, 2.0, 0.5), {1.0, -0.5}).natural_map, 0.0, 1e-15);
  // The same r with the wrong sense: r = (1, 0.5), u = (0, 2.5): z = (1 − 1.25, −2) = (−0.25, −2)
  // -> edge s = −1: d = (−0.25 + 1)/1.25 = 0.6, P = (0.6, −0.3); |r − P| = |(0.4, 0.8)| = √0.8.
  EXPECT_NEAR(natural_map_error(single(-1.0, 2.0, 0.5), {1.0, 0.5}).natural_map, std::sqrt(0.8), 1e-15);
}

// ---- problem dump round trip -------------------------------------------------------------------------

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

TEST(NlgsDump, WriteThenReadIsBitwiseIdentical) {
  // A random sparse problem with values that need all 17 digits (and some tiny / huge ones).
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::size_t nc = 40;
  std::vector<std::uint32_t> rows, cols;
  std::vector<double> vals;
  for (std::uint32_t i = 0; i < nc; ++i)
    for (std::uint32_t j : {i, (i * 7 + 3) % std::uint32_t(nc), (i + 1) % std::uint32_t(nc)})
      for (int e = 0; e < 4; ++e) {
        rows.push_back(2 * i + e / 2);
        cols.push_back(2 * j + e % 2);
        vals.push_back(u(rng) * std::pow(10.0, 20.0 * u(rng)));
      }
  std::vector<double> q(2 * nc), mu(nc), r(2 * nc);
  for (auto& v : q) v = u(rng) / 3.0;
  for (auto& v : mu) v = 0.5 + 0.5 * u(rng);
  for (auto& v : r) v = u(rng) * 1e-7;
  const FrictionProblem2D p = FrictionProblem2D::from_triplets(nc, rows, cols, vals, q, mu);

  const auto file = nscd::testing_support::unique_temp_path("test_nlgs_dump").concat(".txt");
  write_problem(file, p, r);
  std::vector<double> r2;
  const FrictionProblem2D p2 = read_problem(file, &r2);
  std::filesystem::remove(file);

  ASSERT_EQ(p2.nc, p.nc);
  EXPECT_EQ(p2.row_start, p.row_start);
  EXPECT_EQ(p2.col, p.col);
  EXPECT_EQ(p2.diag, p.diag);
  ASSERT_EQ(p2.block.size(), p.block.size());
  for (std::size_t k = 0; k < p.block.size(); ++k)
    for (int e = 0; e < 4; ++e) ASSERT_TRUE(same_bits(p2.block[k][e], p.block[k][e])) << k << " " << e;
  ASSERT_EQ(p2.q.size(), p.q.size());
  for (std::size_t k = 0; k < p.q.size(); ++k) ASSERT_TRUE(same_bits(p2.q[k], p.q[k])) << k;
  ASSERT_EQ(p2.mu.size(), p.mu.size());
  for (std::size_t k = 0; k < p.mu.size(); ++k) ASSERT_TRUE(same_bits(p2.mu[k], p.mu[k])) << k;
  ASSERT_EQ(r2.size(), r.size());
  for (std::size_t k = 0; k < r.size(); ++k) ASSERT_TRUE(same_bits(r2[k], r[k])) << k;
}

TEST(NlgsDump, WithoutImpulsesAndReadingErrors) {
  const FrictionProblem2D p = block_on_two_points();
  const auto file = nscd::testing_support::unique_temp_path("test_nlgs_dump_nor").concat(".txt");
  write_problem(file, p);
  std::vector<double> r = {9.0};
  const FrictionProblem2D p2 = read_problem(file, &r);
  EXPECT_EQ(r, std::vector<double>{9.0});  // no impulses in the file: r untouched
  EXPECT_EQ(p2.q, p.q);
  // The same problem, solved again, gives the same impulses bit for bit.
  std::vector<double> ra, rb;
  nlgs_solve(p, ra, tight());
  nlgs_solve(p2, rb, tight());
  EXPECT_EQ(ra, rb);
  // Not a dump: the error names the file.
  {
    std::ofstream out(file);
    out << "something else\n";
  }
  try {
    read_problem(file);
    FAIL() << "did not throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  std::filesystem::remove(file);
}

// The stepper's solvers are made by name (contact_solver.hpp), the name from its options.
TEST(ContactSolver, IsMadeByItsName) {
  NlgsOptions colored;
  colored.order = SweepOrder::ColoredRows;
  EXPECT_EQ(contact_solver_name(SolverKind::NLGS, NlgsOptions{}), "NLGS");
  EXPECT_EQ(contact_solver_name(SolverKind::NLGS, colored), "NLGS_COLORED");
  EXPECT_EQ(contact_solver_name(SolverKind::NEWTON_AC, colored), "NEWTON_AC");
  for (const std::string_view name : {"NLGS", "NLGS_COLORED", "NEWTON_AC"})
    EXPECT_EQ(make_contact_solver(name, {})->name(), name);
  EXPECT_THROW(make_contact_solver("NSGS", {}), Error);
  // a system without contacts or links: solved at once
  for (const std::string_view name : {"NLGS", "NLGS_COLORED"}) {
    ContactSystem empty;
    const std::unique_ptr<ContactSolver> s = make_contact_solver(name, {});
    s->prepare(empty, 1);
    s->solve(empty, 1);
    EXPECT_TRUE(s->report().converged) << name;
    EXPECT_EQ(s->report().sweeps, 0) << name;
  }
}

}  // namespace
