// tests/unit/test_nlgs.cpp — unit tests of the stand-alone NLGS (src/solvers/nlgs.hpp) on small
// FrictionProblem2D built by hand, and of the natural-map error (local_problem.hpp).
//
// Problems (nlgs_problems.hpp: W and q written out, solutions computed by hand):
//   one contact              NLGS = the exact local solve after one sweep
//   two decoupled contacts   each contact its own local solve
//   block on two points      a rigid block resting on two supports: W 4×4 from its H, weight in q
//   frictionless chain       three bodies stacked on a floor, normal and tangential decoupled
// Suites: NlgsSolve, NlgsAll/NlgsPolicies, NlgsOrders, NlgsNaturalMap. The options, the names
// and the problem dump: test_nlgs_options.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "nscd/laws/coulomb2d.hpp"
#include "nscd/solvers/local_problem.hpp"
#include "nscd/solvers/nlgs.hpp"
#include "nlgs_problems.hpp"

namespace {

using namespace nscd;
using namespace nscd::nlgs_problems;

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

}  // namespace
