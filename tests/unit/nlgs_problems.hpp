// tests/unit/nlgs_problems.hpp — small FrictionProblem2D built by hand, for the tests of the
// stand-alone NLGS (test_nlgs.cpp, test_nlgs_options.cpp), and the tight options they are
// solved with. W and q are written out below, the solutions computed by hand:
//   one contact              NLGS = the exact local solve after one sweep
//   two decoupled contacts   each contact its own local solve
//   block on two points      a rigid block resting on two supports: W 4×4 from its H, weight in q
//   frictionless chain       three bodies stacked on a floor, normal and tangential decoupled
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "nscd/solvers/local_problem.hpp"
#include "nscd/solvers/nlgs.hpp"

namespace nscd::nlgs_problems {

/// Builds a problem from a dense 2nc×2nc W (row-major), keeping its non-zero entries as
/// triplets (the diagonal entries always, so that every diagonal block exists).
inline FrictionProblem2D from_dense(std::size_t nc, const std::vector<double>& W, std::vector<double> q,
                                    std::vector<double> mu) {
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
inline NlgsOptions tight(ConvergencePolicy p = ConvergencePolicy::Quad) {
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
inline FrictionProblem2D one_contact() { return from_dense(1, {2.0, 0.5, 0.5, 2.0}, {-1.75, 2.0}, {0.5}); }

// Two decoupled contacts: contact 0 as above; contact 1 W = diag(2, 4), q = (−2, 0.4), μ = 0.5:
// stick, P = (1, −0.1).
inline FrictionProblem2D two_decoupled() {
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
inline FrictionProblem2D block_on_two_points(double mu = 0.5) {
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
inline FrictionProblem2D chain(double mu, std::array<double, 3> qt) {
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

}  // namespace nscd::nlgs_problems
