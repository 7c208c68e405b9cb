// tests/unit/test_coulomb2d.cpp — unit tests of src/laws: the exact single-contact 2D
// Signorini–Coulomb solve (coulomb2d.hpp) and the contact laws as shifts (contact_laws.hpp).
//
// Every case of solve_coulomb_2d (open, stick, slide forward, slide backward) is checked against
// a hand computation, with a diagonal block and with a full one (W_NT != 0), for μ = 0 and on the
// boundary of the cone; then 10^5 random SPD blocks check the Signorini–Coulomb conditions.
// The law shifts (IQS_CLB, GAP_SGR_CLB, RST_CLB) are checked by hand, RST_CLB's closed/open
// decision included.
//
// Suites: Coulomb2d, Coulomb2dRandom, LawShift.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "nscd/laws/contact_laws.hpp"
#include "nscd/laws/coulomb2d.hpp"

namespace {

using namespace nscd;

struct Velocity {
  double un, ut;
};

/// U = b + W P.
Velocity velocity(const Block2& W, double bn, double bt, const LocalImpulse& P) {
  return {bn + W.nn * P.pn + W.nt * P.pt, bt + W.nt * P.pn + W.tt * P.pt};
}

// ---- open -------------------------------------------------------------------------------------

TEST(Coulomb2d, OpenWhenTheFreeNormalVelocityIsNotNegative) {
  const Block2 W{2.0, 0.5, 2.0};
  // b_N > 0: the contact separates without impulse, whatever b_T (no friction without P_N).
  for (const double bt : {-10.0, 0.0, 3.0}) {
    const LocalImpulse P = solve_coulomb_2d(W, 0.3, bt, 0.5);
    EXPECT_EQ(P.pn, 0.0);
    EXPECT_EQ(P.pt, 0.0);
    EXPECT_EQ(P.status, ContactStatus::Open);
  }
  // b_N = 0: at rest in the normal direction, still no impulse.
  const LocalImpulse P = solve_coulomb_2d(W, 0.0, -1.0, 0.5);
  EXPECT_EQ(P.pn, 0.0);
  EXPECT_EQ(P.pt, 0.0);
  EXPECT_EQ(P.status, ContactStatus::Open);
}

// ---- diagonal block W = diag(2, 4), μ = 0.5 ------------------------------------------------------

TEST(Coulomb2d, StickDiagonal) {
  // P = −W⁻¹ b = (2/2, −0.4/4) = (1, −0.1); |P_T| = 0.1 <= μ P_N = 0.5: stick, U = 0.
  const Block2 W{2.0, 0.0, 4.0};
  const LocalImpulse P = solve_coulomb_2d(W, -2.0, 0.4, 0.5);
  EXPECT_EQ(P.status, ContactStatus::Stick);
  EXPECT_DOUBLE_EQ(P.pn, 1.0);
  EXPECT_DOUBLE_EQ(P.pt, -0.1);
  const Velocity U = velocity(W, -2.0, 0.4, P);
  EXPECT_NEAR(U.un, 0.0, 1e-15);
  EXPECT_NEAR(U.ut, 0.0, 1e-15);
}

TEST(Coulomb2d, SlideForwardDiagonal) {
  // b = (−2, 4): stick would need P_T = −1, outside the cone (μ P_N = 0.5). Slide with
  // U_T > 0: U_N = −2 + 2 P_N = 0 -> P_N = 1, P_T = −μ P_N = −0.5, U_T = 4 + 4(−0.5) = 2 > 0.
  const Block2 W{2.0, 0.0, 4.0};
  const LocalImpulse P = solve_coulomb_2d(W, -2.0, 4.0, 0.5);
  EXPECT_EQ(P.status, ContactStatus::SlipForward);
  EXPECT_DOUBLE_EQ(P.pn, 1.0);
  EXPECT_DOUBLE_EQ(P.pt, -0.5);
  const Velocity U = velocity(W, -2.0, 4.0, P);
  EXPECT_NEAR(U.un, 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(U.ut, 2.0);
}

TEST(Coulomb2d, SlideBackwardDiagonal) {
  // Mirror image of the forward case: b = (−2, −4) -> P = (1, +0.5), U_T = −4 + 2 = −2 < 0.
  const Block2 W{2.0, 0.0, 4.0};
  const LocalImpulse P = solve_coulomb_2d(W, -2.0, -4.0, 0.5);
  EXPECT_EQ(P.status, ContactStatus::SlipBackward);
  EXPECT_DOUBLE_EQ(P.pn, 1.0);
  EXPECT_DOUBLE_EQ(P.pt, 0.5);
  const Velocity U = velocity(W, -2.0, -4.0, P);
  EXPECT_NEAR(U.un, 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(U.ut, -2.0);
}

// ---- full block W = [[2, 0.5], [0.5, 2]] (det 3.75), μ = 0.5 -----------------------------------

TEST(Coulomb2d, StickFullBlock) {
  // Choose P = (1, 0.2) inside the cone (0.2 <= 0.5) and b = −W P = −(2.1, 0.9).
  const Block2 W{2.0, 0.5, 2.0};
  const LocalImpulse P = solve_coulomb_2d(W, -2.1, -0.9, 0.5);
  EXPECT_EQ(P.status, ContactStatus::Stick);
  EXPECT_NEAR(P.pn, 1.0, 1e-15);
  EXPECT_NEAR(P.pt, 0.2, 1e-15);
}

TEST(Coulomb2d, SlideForwardFullBlockUsesTheCoupling) {
  // Choose P = (1, −0.5) (forward slide) and U = (0, 1.5): b = U − W P
  //   W P = (2·1 + 0.5·(−0.5), 0.5·1 + 2·(−0.5)) = (1.75, −0.5), b = (−1.75, 2).
  // Stick would give P = −W⁻¹ b = ((3.5 + 1)/3.75, (−0.875 − 4)/3.75) = (1.2, −1.3): outside.
  // Slide +: (W_NN − μ W_NT) P_N = 1.75 P_N = 1.75 -> P_N = 1; U_T = 2 + (0.5 − 1)·1 = 1.5 > 0.
  const Block2 W{2.0, 0.5, 2.0};
  const LocalImpulse P = solve_coulomb_2d(W, -1.75, 2.0, 0.5);
  EXPECT_EQ(P.status, ContactStatus::SlipForward);
  EXPECT_DOUBLE_EQ(P.pn, 1.0);
  EXPECT_DOUBLE_EQ(P.pt, -0.5);
  const Velocity U = velocity(W, -1.75, 2.0, P);
  EXPECT_NEAR(U.un, 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(U.ut, 1.5);
  // A diagonal approximation (P_N = −b_N / W_NN = 0.875) would be wrong here.
  EXPECT_GT(std::abs(P.pn - 0.875), 0.1);
}

TEST(Coulomb2d, SlideBackwardFullBlock) {
  // Choose P = (1, 0.5) (backward slide) and U = (0, −1.5): W P = (2.25, 1.5), b = (−2.25, −3).
  // Stick: P = ((4.5 − 1.5)/3.75, (−1.125 + 6)/3.75) = (0.8, 1.3), outside the cone.
  // Slide −: (W_NN + μ W_NT) P_N = 2.25 P_N = 2.25 -> P_N = 1; U_T = −3 + (0.5 + 1)·1 = −1.5 < 0.
  const Block2 W{2.0, 0.5, 2.0};
  const LocalImpulse P = solve_coulomb_2d(W, -2.25, -3.0, 0.5);
  EXPECT_EQ(P.status, ContactStatus::SlipBackward);
  EXPECT_DOUBLE_EQ(P.pn, 1.0);
  EXPECT_DOUBLE_EQ(P.pt, 0.5);
  const Velocity U = velocity(W, -2.25, -3.0, P);
  EXPECT_NEAR(U.un, 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(U.ut, -1.5);
}

TEST(Coulomb2d, SlideBackwardAlthoughTheFreeTangentialVelocityIsPositive) {
  // A strong negative coupling reverses the slip: W = [[2, −1.5], [−1.5, 2]] (det 1.75),
  // μ = 0.5, |W_NT| = 1.5 < W_NN / (2μ) = 2. Choose P = (1, 0.5), U = (0, −0.25):
  //   W P = (2 − 0.75, −1.5 + 1) = (1.25, −0.5), b = (−1.25, 0.25): b_T > 0.
  // Stick: P = ((2.5 − 0.375)/1.75, (1.875 − 0.5)/1.75) = (1.214, 0.786), |P_T| > 0.607: no.
  // Slide + (tried first, sign of b_T): P_N = 1.25/2.75, U_T = 0.25 − 2.5·0.4545 < 0: no.
  // Slide −: P_N = 1.25/1.25 = 1, U_T = 0.25 + (−1.5 + 1)·1 = −0.25 < 0: consistent.
  const Block2 W{2.0, -1.5, 2.0};
  const LocalImpulse P = solve_coulomb_2d(W, -1.25, 0.25, 0.5);
  EXPECT_EQ(P.status, ContactStatus::SlipBackward);
  EXPECT_DOUBLE_EQ(P.pn, 1.0);
  EXPECT_DOUBLE_EQ(P.pt, 0.5);
  const Velocity U = velocity(W, -1.25, 0.25, P);
  EXPECT_NEAR(U.un, 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(U.ut, -0.25);
}

// ---- frictionless -------------------------------------------------------------------------------

TEST(Coulomb2d, FrictionlessClosesTheNormalOnly) {
  // μ = 0, W = [[2, 0.5], [0.5, 2]]: P_T = 0 and U_N = 0 -> P_N = −b_N / W_NN; U_T = b_T + W_TN P_N.
  const Block2 W{2.0, 0.5, 2.0};
  // b = (−2, 1): P_N = 1, U_T = 1 + 0.5 = 1.5 (forward).
  LocalImpulse P = solve_coulomb_2d(W, -2.0, 1.0, 0.0);
  EXPECT_EQ(P.status, ContactStatus::SlipForward);
  EXPECT_DOUBLE_EQ(P.pn, 1.0);
  EXPECT_EQ(P.pt, 0.0);
  EXPECT_DOUBLE_EQ(velocity(W, -2.0, 1.0, P).ut, 1.5);
  // b = (−2, −1): P_N = 1, U_T = −1 + 0.5 = −0.5 (backward).
  P = solve_coulomb_2d(W, -2.0, -1.0, 0.0);
  EXPECT_EQ(P.status, ContactStatus::SlipBackward);
  EXPECT_DOUBLE_EQ(P.pn, 1.0);
  EXPECT_EQ(P.pt, 0.0);
  EXPECT_DOUBLE_EQ(velocity(W, -2.0, -1.0, P).ut, -0.5);
  // b = (−2, −0.5): U_T = −0.5 + 0.5 = 0 exactly: the stick case (P_T = 0 = μ P_N) is consistent.
  P = solve_coulomb_2d(W, -2.0, -0.5, 0.0);
  EXPECT_DOUBLE_EQ(P.pn, 1.0);
  EXPECT_EQ(P.pt, 0.0);
  EXPECT_NEAR(velocity(W, -2.0, -0.5, P).ut, 0.0, 1e-15);
}

// ---- boundary of the cone -------------------------------------------------------------------------

TEST(Coulomb2d, BoundaryOfTheConeDiagonalIsStick) {
  // W = diag(2, 4), μ = 0.5, b = (−2, 2): P = −W⁻¹ b = (1, −0.5), exactly |P_T| = μ P_N (all
  // the arithmetic is exact in binary). The first consistent case, stick, is returned, U = 0.
  const Block2 W{2.0, 0.0, 4.0};
  const LocalImpulse P = solve_coulomb_2d(W, -2.0, 2.0, 0.5);
  EXPECT_EQ(P.status, ContactStatus::Stick);
  EXPECT_EQ(P.pn, 1.0);
  EXPECT_EQ(P.pt, -0.5);
  const Velocity U = velocity(W, -2.0, 2.0, P);
  EXPECT_EQ(U.un, 0.0);
  EXPECT_EQ(U.ut, 0.0);
}

TEST(Coulomb2d, BoundaryOfTheConeFullBlock) {
  // W = [[2, 0.5], [0.5, 2]], P = (1, −0.5) on the cone's edge, U = 0: b = −W P = (−1.75, 0.5).
  // Stick and forward slide coincide here (U_T = 0); rounding may pick either, the impulse
  // is the same.
  const Block2 W{2.0, 0.5, 2.0};
  const LocalImpulse P = solve_coulomb_2d(W, -1.75, 0.5, 0.5);
  EXPECT_TRUE(P.status == ContactStatus::Stick || P.status == ContactStatus::SlipForward);
  EXPECT_NEAR(P.pn, 1.0, 1e-15);
  EXPECT_NEAR(P.pt, -0.5, 1e-15);
  const Velocity U = velocity(W, -1.75, 0.5, P);
  EXPECT_NEAR(U.un, 0.0, 1e-15);
  EXPECT_NEAR(U.ut, 0.0, 1e-15);
}

// ---- randomized Signorini–Coulomb check -----------------------------------------------------------

TEST(Coulomb2dRandom, SatisfiesSignoriniCoulombOnRandomBlocks) {
  // 10^5 random SPD blocks with |W_NT| < W_NN / (2μ) (so that W_NN ∓ μ W_NT > W_NN / 2 > 0:
  // both slide cases are well posed), entries over 4 decades, b over 6 decades, μ in [0, 1.5]
  // (every 10th μ = 0). Tolerance: 1e-12 relative to the sizes of the terms that are summed.
  std::mt19937_64 rng(20060101);
  std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
  const double eps = 1e-12;
  int counts[4] = {0, 0, 0, 0};
  for (int k = 0; k < 100000; ++k) {
    Block2 W;
    W.nn = std::pow(10.0, 4.0 * unit(rng) - 2.0);
    W.tt = std::pow(10.0, 4.0 * unit(rng) - 2.0);
    const double mu = k % 10 == 0 ? 0.0 : 1.5 * unit(rng);
    double bound = 0.9 * std::sqrt(W.nn * W.tt);  // SPD, condition number bounded
    if (mu > 0.0) bound = std::min(bound, W.nn / (2.0 * mu));
    W.nt = bound * sym(rng);
    const double scale_b = std::pow(10.0, 6.0 * unit(rng) - 3.0);
    const double bn = scale_b * sym(rng), bt = scale_b * sym(rng);

    const LocalImpulse P = solve_coulomb_2d(W, bn, bt, mu);
    const Velocity U = velocity(W, bn, bt, P);
    ++counts[static_cast<int>(P.status)];
    // Scales: |U| is a sum of |b| and |W||P| terms; |P| the impulse's size.
    const double wmax = std::max({W.nn, W.tt, std::abs(W.nt)});
    const double p_abs = std::hypot(P.pn, P.pt);
    const double s_u = std::hypot(bn, bt) + 2.0 * wmax * p_abs;
    const double tol_u = eps * s_u, tol_p = eps * p_abs;
    SCOPED_TRACE(::testing::Message() << "sample " << k << ": W = [" << W.nn << ", " << W.nt << "; " << W.nt << ", "
                                      << W.tt << "], b = (" << bn << ", " << bt << "), mu = " << mu);
    // Signorini: P_N >= 0, U_N >= 0, P_N U_N = 0.
    ASSERT_GE(P.pn, 0.0);
    ASSERT_GE(U.un, -tol_u);
    ASSERT_LE(P.pn * std::abs(U.un), tol_u * p_abs);
    // Coulomb: |P_T| <= μ P_N; strictly inside the cone U_T = 0; sliding P_T = −μ P_N sign(U_T).
    ASSERT_LE(std::abs(P.pt), mu * P.pn + tol_p);
    if (std::abs(P.pt) < mu * P.pn - tol_p) {
      ASSERT_LE(std::abs(U.ut), tol_u);
    }
    if (std::abs(U.ut) > tol_u) {
      ASSERT_NEAR(P.pt, -mu * P.pn * (U.ut > 0.0 ? 1.0 : -1.0), tol_p);
    }
    // The status agrees with the impulse and the velocity.
    switch (P.status) {
      case ContactStatus::Open: ASSERT_EQ(p_abs, 0.0); break;
      case ContactStatus::Stick: ASSERT_LE(std::abs(U.ut), tol_u); break;
      case ContactStatus::SlipForward: ASSERT_GE(U.ut, -tol_u); break;
      case ContactStatus::SlipBackward: ASSERT_LE(U.ut, tol_u); break;
    }
  }
  // Every case was exercised many times.
  for (int s = 0; s < 4; ++s) EXPECT_GT(counts[s], 5000) << "status " << s;
}

TEST(Coulomb2dRandom, SolutionsOnTheEdgeOfTheConeAreFound) {
  // 10^5 problems built backwards from a solution on the cone's edge: P = (p, −s μ p) with
  // U = (0, 0) (every third) or U_T a few ulps of the sense s, b = U − W P. There stick and
  // slide coincide and rounding can fail both tests by an ulp; the solve must still return P
  // (an earlier version fell back to frictionless closure, P_T = 0, in ~4 % of these).
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
  for (int k = 0; k < 100000; ++k) {
    Block2 W;
    W.nn = std::pow(10.0, 4.0 * unit(rng) - 2.0);
    W.tt = std::pow(10.0, 4.0 * unit(rng) - 2.0);
    const double mu = 0.01 + 1.49 * unit(rng);
    const double bound = std::min(0.99 * std::sqrt(W.nn * W.tt), 0.999 * W.nn / (2.0 * mu));
    W.nt = bound * sym(rng);
    const double p = std::pow(10.0, 4.0 * unit(rng) - 2.0);
    const double s = sym(rng) > 0.0 ? 1.0 : -1.0;
    const double pn = p, pt = -s * mu * p;
    const double ut = k % 3 == 0 ? 0.0 : s * 1e-17 * W.tt * p * unit(rng);
    const double bn = -(W.nn * pn + W.nt * pt), bt = ut - (W.nt * pn + W.tt * pt);
    const LocalImpulse P = solve_coulomb_2d(W, bn, bt, mu);
    SCOPED_TRACE(::testing::Message() << "sample " << k << ": W = [" << W.nn << ", " << W.nt << "; " << W.nt << ", "
                                      << W.tt << "], b = (" << bn << ", " << bt << "), mu = " << mu);
    ASSERT_NE(P.status, ContactStatus::Open);
    ASSERT_NEAR(P.pn, pn, 1e-9 * p);
    ASSERT_NEAR(P.pt, pt, 1e-9 * p);
    const Velocity U = velocity(W, bn, bt, P);
    const double s_u = std::hypot(bn, bt) + 2.0 * std::max({W.nn, W.tt, std::abs(W.nt)}) * p;
    ASSERT_NEAR(U.un, 0.0, 1e-12 * s_u);
    ASSERT_NEAR(U.ut, 0.0, 1e-9 * s_u);
  }
}

// ---- law shifts -------------------------------------------------------------------------------------

// h = 1 ms, θ = 0.5. Every shift has the horizon h (the next detection, q_m + h u_f), not θ h.
constexpr double kH = 1e-3, kTheta = 0.5;

TEST(LawShift, IqsClbClosesOpenGapsOnly) {
  // s_N = max(0, g) / h: a gap of 0.2 mm may close at 0.2 m/s; an overlap is not pushed out.
  EXPECT_DOUBLE_EQ(iqs_clb_shift(2e-4, kH, kTheta).n, 0.2);
  EXPECT_EQ(iqs_clb_shift(2e-4, kH, kTheta).t, 0.0);
  EXPECT_EQ(iqs_clb_shift(-3e-4, kH, kTheta).n, 0.0);
  EXPECT_EQ(iqs_clb_shift(0.0, kH, kTheta).n, 0.0);
  // the same for θ = 1 (θ h = h there: the two horizons agree).
  EXPECT_DOUBLE_EQ(iqs_clb_shift(2e-4, kH, 1.0).n, 0.2);
}

TEST(LawShift, GapSgrClbPushesOverlapsOut) {
  // s_N = g / h: −3e-4 / 1e-3 = −0.3 (the gap at the next detection must be >= 0), 2e-4 -> 0.2.
  EXPECT_DOUBLE_EQ(gap_sgr_clb_shift(-3e-4, kH, kTheta).n, -0.3);
  EXPECT_DOUBLE_EQ(gap_sgr_clb_shift(2e-4, kH, kTheta).n, 0.2);
  EXPECT_EQ(gap_sgr_clb_shift(-3e-4, kH, kTheta).t, 0.0);
}

// RST_CLB applies Newton's restitution, s = (e_n U_N⁻, e_t U_T⁻), to a contact that is closed at
// the start of the step, g_i = g − (1 − θ) h U_N⁻ <= kClosedGap, or that closes before the next
// detection at its start velocity (an impact), g + h U_N⁻ <= kClosedGap; otherwise IQS_CLB.
TEST(LawShift, RstClbClosedAtTheStartOfTheStepUsesRestitution) {
  const LawSpec law{LawKind::RST_CLB, 0.3, 0.5, 0.2};
  // g = −1e-5, U_N⁻ = +0.01 (separating): g_i = −1e-5 − 5e-6 = −1.5e-5 <= 1e-9: closed
  // -> s = (e_n U_N⁻, e_t U_T⁻) = (0.005, 0.2·0.1 = 0.02).
  LawShift s = rst_clb_shift(law, -1e-5, 0.01, 0.1, kH, kTheta);
  EXPECT_DOUBLE_EQ(s.n, 0.005);
  EXPECT_DOUBLE_EQ(s.t, 0.02);
  // g = 1e-5 > 0 at q_m, but U_N⁻ = +0.1: g_i = 1e-5 − 5e-5 = −4e-5: it was closed at t_i and is
  // separating -> restitution (0.05, 0.2·(−0.3)), not the IQS shift 1e-5 / 1e-3 = 0.01.
  s = rst_clb_shift(law, 1e-5, 0.1, -0.3, kH, kTheta);
  EXPECT_DOUBLE_EQ(s.n, 0.05);
  EXPECT_DOUBLE_EQ(s.t, -0.06);
  // θ = 1: q_m = q_i, g_i = g: an overlap is closed whatever the velocity.
  s = rst_clb_shift(law, -1e-5, 0.2, 0.0, kH, 1.0);
  EXPECT_DOUBLE_EQ(s.n, 0.1);
  EXPECT_EQ(s.t, 0.0);
}

TEST(LawShift, RstClbImpactDuringTheStepUsesRestitution) {
  const LawSpec law{LawKind::RST_CLB, 0.3, 0.5, 0.2};
  // g = −1e-5 at q_m with U_N⁻ = −0.2: g_i = −1e-5 + 1e-4 = 9e-5 (open at t_i), but the next
  // gap at the start velocity is −1e-5 − 2e-4 = −2.1e-4: an impact -> (−0.1, 0.2·0.7 = 0.14).
  LawShift s = rst_clb_shift(law, -1e-5, -0.2, 0.7, kH, kTheta);
  EXPECT_DOUBLE_EQ(s.n, -0.1);
  EXPECT_DOUBLE_EQ(s.t, 0.14);
  // Still apart at q_m: g = 5e-5, U_N⁻ = −0.2: g_i = 1.5e-4, next gap 5e-5 − 2e-4 < 0: impact.
  s = rst_clb_shift(law, 5e-5, -0.2, 0.0, kH, kTheta);
  EXPECT_DOUBLE_EQ(s.n, -0.1);
  EXPECT_EQ(s.t, 0.0);
  // g = 1.5e-4, U_N⁻ = −0.2: the end-of-step gap g + θ h U_N⁻ = 5e-5 stays open, but the next
  // detection would see 1.5e-4 − 2e-4 = −5e-5: an impact (the θ h horizon missed it).
  s = rst_clb_shift(law, 1.5e-4, -0.2, 0.0, kH, kTheta);
  EXPECT_DOUBLE_EQ(s.n, -0.1);
}

TEST(LawShift, RstClbOpenDuringTheWholeStepActsAsIqs) {
  const LawSpec law{LawKind::RST_CLB, 0.3, 0.5, 0.2};
  // g = 3e-4, U_N⁻ = −0.2: g_i = 4e-4, next gap 3e-4 − 2e-4 = 1e-4: open -> IQS 3e-4 / 1e-3 = 0.3,
  // no tangential shift.
  LawShift s = rst_clb_shift(law, 3e-4, -0.2, 0.7, kH, kTheta);
  EXPECT_DOUBLE_EQ(s.n, 0.3);
  EXPECT_EQ(s.t, 0.0);
  // g = 2e-4, U_N⁻ = −0.195: g_i = 2.975e-4, next gap 2e-4 − 1.95e-4 = 5e-6 > 1e-9: open -> 0.2.
  s = rst_clb_shift(law, 2e-4, -0.195, 0.7, kH, kTheta);
  EXPECT_DOUBLE_EQ(s.n, 0.2);
  EXPECT_EQ(s.t, 0.0);
}

TEST(LawShift, RstClbClosedThresholdIsInclusive) {
  const LawSpec law{LawKind::RST_CLB, 0.3, 0.5, 0.2};
  // U_N⁻ = 0 makes g_i = g = the end gap. g = kClosedGap: closed (<=) -> (0, e_t U_T⁻) = (0, 0.2).
  LawShift s = rst_clb_shift(law, kClosedGap, 0.0, 1.0, kH, kTheta);
  EXPECT_EQ(s.n, 0.0);
  EXPECT_DOUBLE_EQ(s.t, 0.2);
  // g = 2 kClosedGap: open -> IQS 2e-9 / 1e-3 = 2e-6, no tangential shift.
  s = rst_clb_shift(law, 2.0 * kClosedGap, 0.0, 1.0, kH, kTheta);
  EXPECT_DOUBLE_EQ(s.n, 2e-6);
  EXPECT_EQ(s.t, 0.0);
}

TEST(LawShift, DispatchMatchesTheKind) {
  const LawSpec iqs{LawKind::IQS_CLB, 0.5, 0.0, 0.0};
  const LawSpec sgr{LawKind::GAP_SGR_CLB, 0.5, 0.0, 0.0};
  const LawSpec rst{LawKind::RST_CLB, 0.5, 0.9, 0.1};
  for (const double g : {-2e-4, 0.0, 3e-4}) {
    for (const double un : {-0.3, 0.0, 0.4}) {
      EXPECT_EQ(law_shift(iqs, g, un, 0.1, kH, kTheta).n, iqs_clb_shift(g, kH, kTheta).n);
      EXPECT_EQ(law_shift(sgr, g, un, 0.1, kH, kTheta).n, gap_sgr_clb_shift(g, kH, kTheta).n);
      const LawShift a = law_shift(rst, g, un, 0.1, kH, kTheta), b = rst_clb_shift(rst, g, un, 0.1, kH, kTheta);
      EXPECT_EQ(a.n, b.n);
      EXPECT_EQ(a.t, b.t);
    }
  }
  // IQS and GAP_SGR differ only on overlaps.
  EXPECT_EQ(law_shift(iqs, -2e-4, 0.0, 0.0, kH, kTheta).n, 0.0);
  EXPECT_DOUBLE_EQ(law_shift(sgr, -2e-4, 0.0, 0.0, kH, kTheta).n, -0.2);
}

}  // namespace
