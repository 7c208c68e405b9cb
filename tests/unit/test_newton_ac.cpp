// tests/unit/test_newton_ac.cpp — the solver seam (ContactSystem: exports, set_impulses) and
// the global solver NEWTON_AC: agreement with NLGS on small problems (velocities and
// statuses), a hyperstatic column where plain semismooth Newton stalls, the Siconos granular
// problems to 1e-8, bad input, and the clear error of a build without SuiteSparse.
//
// Suites: ContactSystem, NewtonAC, NewtonACUnavailable.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "error_assertions.hpp"
#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "nscd/solvers/newton_ac.hpp"
#include "nscd/solvers/nlgs.hpp"

namespace {

using namespace nscd;
using nscd::testing_support::Contains;
using nscd::testing_support::error_message;
namespace fs = std::filesystem;

#define SKIP_WITHOUT_NEWTON()                                                              \
  do {                                                                                     \
    if (!newton_ac_available()) GTEST_SKIP() << "NEWTON_AC not in this build (no SuiteSparse)"; \
  } while (0)

/// A small scene: a fixed floor, three blocks of different sizes side by side, a block
/// across two of them (face–face: hyperstatic), a tilted pentagon on top, all moving.
Registry small_scene(double mu) {
  Registry reg;
  reg.params.dt = 1e-3;
  const MaterialId m = add_material(reg, "stone", 2000.0);
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, mu});
  const BodyId floor = add_polygon_body(reg, rectangle(4.0, 0.5), m, {0.0, -0.25}, 0.0, "floor");
  fix_body(reg, floor);
  add_polygon_body(reg, rectangle(0.2, 0.1), m, {-0.15, 0.05}, 0.0, "a");
  add_polygon_body(reg, rectangle(0.1, 0.1), m, {0.05, 0.05}, 0.0, "b");
  add_polygon_body(reg, rectangle(0.3, 0.05), m, {-0.05, 0.125}, 0.0, "top");
  add_polygon_body(reg, regular_polygon(5, 0.08, 0.3), m, {0.0, 0.19}, 0.0, "pentagon");
  for (std::size_t i = 1; i < reg.bodies.size(); ++i) {
    reg.bodies.vx[i] = 0.3 * std::sin(double(i));
    reg.bodies.vy[i] = -0.2 - 0.1 * double(i);
    reg.bodies.spin[i] = 0.5 * std::cos(double(i));
  }
  return reg;
}

/// A column of n square blocks (side a) on a fixed floor, exactly touching: two contact
/// points per interface, so W is rank-deficient (3 dofs per block, 4 rows per interface).
Registry block_column(int n, double a = 0.1, double mu = 0.5) {
  Registry reg;
  reg.params.dt = 1e-3;
  const MaterialId m = add_material(reg, "stone", 2000.0);
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, mu});
  const BodyId floor = add_polygon_body(reg, rectangle(2.0, 0.5), m, {0.0, -0.25}, 0.0, "floor");
  fix_body(reg, floor);
  for (int k = 0; k < n; ++k) add_polygon_body(reg, rectangle(a, a), m, {0.0, (k + 0.5) * a}, 0.0, "block");
  return reg;
}

/// Runs the first three calls of a step and returns the stepper, ready for solve().
void prepare(MoreauJean& mj) {
  mj.begin_step();
  mj.detect();
  mj.prepare();
}

std::vector<double> velocities(const FrictionProblem2D& p, const std::vector<double>& r) {
  std::vector<double> u;
  p.multiply(r, u);
  for (std::size_t k = 0; k < u.size(); ++k) u[k] += p.q[k];
  return u;
}

double norm(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

// ---- the seam --------------------------------------------------------------------------------

TEST(ContactSystem, GlobalFormGivesTheLocalForm) {
  Registry reg = small_scene(0.4);
  MoreauJean mj(reg);
  prepare(mj);
  const ContactSystem& sys = mj.system();
  ASSERT_GE(sys.contacts.size(), 8u);
  const FrictionProblem2D local = sys.local_problem();
  const GlobalProblem g = sys.global_problem();
  // W = H* M⁻¹ H and q = H* M⁻¹ f + b, entry by entry
  Eigen::SparseMatrix<double> Minv = g.M;
  for (int k = 0; k < Minv.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(Minv, k); it; ++it) it.valueRef() = 1.0 / it.value();
  const Eigen::MatrixXd W = Eigen::MatrixXd(Eigen::SparseMatrix<double>(g.H.transpose() * Minv * g.H));
  const Eigen::VectorXd q = g.H.transpose() * (Minv * g.f) + g.b;
  std::vector<double> e(2 * local.nc, 0.0), col;
  double worst = 0.0;
  for (std::size_t j = 0; j < 2 * local.nc; ++j) {
    std::fill(e.begin(), e.end(), 0.0);
    e[j] = 1.0;
    local.multiply(e, col);
    for (std::size_t i = 0; i < 2 * local.nc; ++i)
      worst = std::max(worst, std::abs(col[i] - W(Eigen::Index(i), Eigen::Index(j))) / std::abs(W(0, 0)));
  }
  EXPECT_LT(worst, 1e-13);
  for (std::size_t i = 0; i < 2 * local.nc; ++i) EXPECT_NEAR(q[Eigen::Index(i)], local.q[i], 1e-13) << i;
  // block rows: columns strictly increasing, diag[i] the block of column i
  for (std::size_t i = 0; i < local.nc; ++i) {
    for (std::uint32_t k = local.row_start[i] + 1; k < local.row_start[i + 1]; ++k) EXPECT_LT(local.col[k - 1], local.col[k]);
    EXPECT_EQ(local.col[local.diag[i]], i);
  }
  // the floor is kinematic: none of its dofs is an unknown
  EXPECT_EQ(g.M.rows(), Eigen::Index(3 * (reg.bodies.size() - 1)));
}

TEST(ContactSystem, SetImpulsesReproducesTheSolversVelocities) {
  Registry reg = small_scene(0.4);
  MoreauJean mj(reg);
  prepare(mj);
  mj.solve();
  ContactSystem sys = mj.system();
  const std::vector<SolverBody> solved = sys.bodies;
  sys.set_impulses(sys.impulses(false), false);
  for (std::size_t i = 0; i < solved.size(); ++i) {
    EXPECT_NEAR(sys.bodies[i].vx, solved[i].vx, 1e-12);
    EXPECT_NEAR(sys.bodies[i].vy, solved[i].vy, 1e-12);
    EXPECT_NEAR(sys.bodies[i].w, solved[i].w, 1e-12);
  }
}

// ---- NEWTON_AC against NLGS --------------------------------------------------------------------

TEST(NewtonAC, AgreesWithNlgsOnSmallProblems) {
  SKIP_WITHOUT_NEWTON();
  for (const double mu : {0.0, 0.3, 0.8}) {
    Registry reg = small_scene(mu);
    MoreauJean mj(reg);
    prepare(mj);
    const FrictionProblem2D p = mj.local_problem();
    std::vector<double> r_nlgs, r_newton;
    NlgsOptions no;
    no.policy = ConvergencePolicy::Strict;
    no.tol = 1e-15;
    no.check_every = 1;
    no.max_sweeps = 200000;
    nlgs_solve(p, r_nlgs, no);
    NewtonOptions o;
    o.tol = 1e-10;
    const NewtonResult res = newton_ac_solve(p, r_newton, o);
    ASSERT_TRUE(res.converged) << "mu " << mu << ": " << res.failure;
    EXPECT_LE(natural_map_error(p, r_newton).relative_q, 1e-10);
    EXPECT_LE(natural_map_error(p, r_nlgs).relative_q, 1e-9) << "the reference must be tight, mu " << mu;
    // The velocities agree: they are unique, and equal velocities mean the two impulses differ
    // by a vector of W's kernel only. The impulses themselves need not agree: on this scene W
    // is rank-deficient (the top block rests on two blocks by four points), and with μ = 0 one
    // solver's answer carries the top's weight on two of those points, the other's on four.
    // So the statuses compared are the ones the velocities decide: a contact that separates
    // (u_N > 0) is open in both answers, one that slides (u_N = 0, u_T ≠ 0) slides in both;
    // and each answer is complementary (an impulse only where u_N = 0).
    const std::vector<double> ua = velocities(p, r_nlgs), ub = velocities(p, r_newton);
    const double scale = norm(p.q);
    for (std::size_t k = 0; k < ua.size(); ++k) EXPECT_NEAR(ua[k], ub[k], 1e-8 * scale) << "mu " << mu << " row " << k;
    for (std::size_t i = 0; i < p.nc; ++i) {
      const bool separates = ua[2 * i] > 1e-8 * scale;
      EXPECT_EQ(separates, ub[2 * i] > 1e-8 * scale) << "contact " << i;
      for (const std::vector<double>* r : {&r_nlgs, &r_newton}) {
        if (separates) {
          EXPECT_LE((*r)[2 * i], 1e-9 * scale) << "an impulse on a separating contact " << i;
        }
        if ((*r)[2 * i] > 1e-9 * scale) {
          EXPECT_LT(std::abs(ua[2 * i]), 1e-8 * scale) << "contact " << i;
        }
      }
      const bool slides = !separates && std::abs(ua[2 * i + 1]) > 1e-8 * scale;
      if (slides && mu > 0.0) {  // sliding: both answers on the cone's edge, opposing u_T
        for (const std::vector<double>* r : {&r_nlgs, &r_newton}) {
          EXPECT_NEAR(std::abs((*r)[2 * i + 1]), mu * (*r)[2 * i], 1e-8 * scale) << "contact " << i;
          EXPECT_LE((*r)[2 * i + 1] * ua[2 * i + 1], 0.0) << "contact " << i;
        }
      }
    }
    std::printf("[ measured ] small scene mu=%.1f: %zu contacts, NEWTON_AC %d iterations, residual %.2e\n", mu, p.nc,
                res.iterations, res.residual);
  }
}

TEST(NewtonAC, HyperstaticColumnConvergesInFewIterations) {
  SKIP_WITHOUT_NEWTON();
  Registry reg = block_column(40);
  MoreauJean mj(reg);
  prepare(mj);
  const FrictionProblem2D p = mj.local_problem();
  ASSERT_EQ(p.nc, 80u);  // two points per face–face interface: W is rank-deficient
  NewtonOptions o;
  o.tol = 1e-8;
  std::vector<double> r;
  const NewtonResult b = newton_ac_solve(p, r, o);
  ASSERT_TRUE(b.converged) << b.failure;
  EXPECT_LE(b.iterations, 50);
  // the column carries its weight: the floor's two contacts take 40 m g h in all
  const double m = reg.bodies.mass[1], h = reg.params.dt, g = 9.81;
  double floor_pn = 0.0;
  const ContactSystem& sys = mj.system();
  for (std::size_t i = 0; i < p.nc; ++i)
    if (sys.contacts[i].an == 0) floor_pn += r[2 * i];
  EXPECT_NEAR(floor_pn, 40.0 * m * g * h, 1e-6 * 40.0 * m * g * h);
}

TEST(NewtonAC, GranularPileWherePlainNewtonStallsConverges) {
  SKIP_WITHOUT_NEWTON();
  // The Siconos 2020-contact granular flow: hyperstatic, and 6-digit data make its sticking
  // subsystems slightly inconsistent, so the solution is reached only by letting the forces
  // drift along W's kernel until a contact changes status (docs/theory.md).
  const FrictionProblem2D p = read_siconos_fc2d(fs::path(NSCD_TEST_DATA_DIR) / "siconos-fc2d" /
                                                "fc2d_granularflowonwall_02020_00213.dat");
  NewtonOptions plain;  // semismooth Newton with a vanishing proximal term
  plain.tol = 1e-8;
  plain.max_iterations = 300;
  plain.prox_initial = plain.prox_min = plain.prox_max = 1e-12;
  std::vector<double> r_plain;
  const NewtonResult a = newton_ac_solve(p, r_plain, plain);
  NewtonOptions o;
  o.tol = 1e-8;
  o.max_iterations = 1000;
  std::vector<double> r;
  const NewtonResult b = newton_ac_solve(p, r, o);
  std::printf("[ measured ] 2020 contacts: plain Newton %s at %.2e after %d iterations; NEWTON_AC %.2e in %d\n",
              a.converged ? "converged" : "stalled", a.residual, a.iterations, b.residual, b.iterations);
  EXPECT_FALSE(a.converged);
  EXPECT_TRUE(b.converged) << b.failure;
  EXPECT_LE(natural_map_error(p, r).relative_q, 1e-8);
}

TEST(NewtonAC, ReusingAnUnchangedFactorisationChangesNothing) {
  SKIP_WITHOUT_NEWTON();
  // On the 2020-contact Siconos flow to 1e-8 some iterations start from the pieces of the last
  // one (the line search cut its step short) with the same η: the matrix is the one factored
  // last. Solving with those factors must give the same iterates, bit for bit.
  const FrictionProblem2D p = read_siconos_fc2d(fs::path(NSCD_TEST_DATA_DIR) / "siconos-fc2d" /
                                                "fc2d_granularflowonwall_02020_00213.dat");
  NewtonOptions o;
  o.tol = 1e-8;
  o.max_iterations = 1000;
  std::vector<double> r_reuse, r_fresh;
  const NewtonResult a = newton_ac_solve(p, r_reuse, o);
  o.reuse_factorization = false;
  const NewtonResult b = newton_ac_solve(p, r_fresh, o);
  std::printf("[ measured ] 2020 contacts to 1e-8: %d iterations, %d factorisations reused\n", a.iterations,
              a.reused_factorizations);
  EXPECT_GT(a.reused_factorizations, 0);
  EXPECT_EQ(b.reused_factorizations, 0);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.residual, b.residual);
  ASSERT_EQ(r_reuse.size(), r_fresh.size());
  for (std::size_t k = 0; k < r_reuse.size(); ++k) ASSERT_EQ(r_reuse[k], r_fresh[k]) << k;
}

TEST(NewtonAC, GivingUpStalledSubproblemsEarlySavesIterations) {
  SKIP_WITHOUT_NEWTON();
  // The 7002-contact Siconos flow: some proximal subproblems make no headway (the line search
  // crawls). Giving them up after stall_inner = 3 iterations (more proximal weight) instead of
  // running each to max_inner = 10 reaches the same tolerance in fewer iterations.
  const FrictionProblem2D p = read_siconos_fc2d(fs::path(NSCD_TEST_DATA_DIR) / "siconos-fc2d" /
                                                "fc2d_granularflowonwall_07002_00801.dat");
  NewtonOptions o;
  o.tol = 1e-8;
  o.max_iterations = 1000;
  std::vector<double> r_stall, r_full;
  const NewtonResult a = newton_ac_solve(p, r_stall, o);
  o.stall_inner = 0;
  const NewtonResult b = newton_ac_solve(p, r_full, o);
  std::printf("[ measured ] 7002 contacts to 1e-8: %d iterations giving up stalled subproblems, %d without\n",
              a.iterations, b.iterations);
  ASSERT_TRUE(a.converged) << a.failure;
  ASSERT_TRUE(b.converged) << b.failure;
  EXPECT_LE(natural_map_error(p, r_stall).relative_q, 1e-8);
  EXPECT_LT(a.iterations, b.iterations);
}

TEST(NewtonAC, OpenContactsStayOutOfTheFactorisation) {
  SKIP_WITHOUT_NEWTON();
  // The 2020-contact Siconos flow with every third contact pulled apart (q_N raised well above
  // the problem's velocities): those contacts are open at the solution, their rows of J are
  // the identity's, and the LU need not see them. Both ways must solve the problem to 1e-8
  // with the same iterations, up to rounding, the eliminating one on fewer rows.
  FrictionProblem2D p = read_siconos_fc2d(fs::path(NSCD_TEST_DATA_DIR) / "siconos-fc2d" /
                                          "fc2d_granularflowonwall_02020_00213.dat");
  double qmax = 0.0;
  for (double v : p.q) qmax = std::max(qmax, std::abs(v));
  std::size_t pulled = 0;
  for (std::size_t i = 0; i < p.nc; i += 3, ++pulled) p.q[2 * i] += 10.0 * qmax;
  NewtonOptions o;
  o.tol = 1e-8;
  o.max_iterations = 1000;
  std::vector<double> r_elim, r_all;
  const NewtonResult a = newton_ac_solve(p, r_elim, o);
  o.eliminate_open = false;
  const NewtonResult b = newton_ac_solve(p, r_all, o);
  const double rows_a = double(a.factored_rows) / a.iterations, rows_b = double(b.factored_rows) / b.iterations;
  std::printf("[ measured ] 2020 contacts, %zu pulled apart, to 1e-8: %d iterations on %.0f rows (open ones "
              "eliminated, %d analyses), %d on %.0f rows (all)\n",
              pulled, a.iterations, rows_a, a.analyses, b.iterations, rows_b);
  ASSERT_TRUE(a.converged) << a.failure;
  ASSERT_TRUE(b.converged) << b.failure;
  EXPECT_LE(natural_map_error(p, r_elim).relative_q, 1e-8);
  EXPECT_EQ(rows_b, double(2 * p.nc));
  EXPECT_EQ(b.analyses, 1);
  EXPECT_LE(rows_a, 2.0 * double(p.nc - pulled));  // the pulled contacts were never factorised
  EXPECT_NEAR(a.iterations, b.iterations, 0.1 * b.iterations + 2);
  for (std::size_t i = 0; i < p.nc; i += 3) EXPECT_EQ(r_elim[2 * i], 0.0) << i;  // open: no impulse
  // the other LU back end takes the same reduced rows
  o.eliminate_open = true;
  o.linear_solver = LinearSolver::UMFPACK;
  std::vector<double> r_umf;
  const NewtonResult c = newton_ac_solve(p, r_umf, o);
  ASSERT_TRUE(c.converged) << c.failure;
  EXPECT_LE(double(c.factored_rows) / c.iterations, 2.0 * double(p.nc - pulled));
  EXPECT_LE(natural_map_error(p, r_umf).relative_q, 1e-8);
}

TEST(NewtonAC, StepsTheColumnAtRest) {
  SKIP_WITHOUT_NEWTON();
  Registry reg = block_column(10);
  StepperOptions so;
  so.solver = SolverKind::NEWTON_AC;
  so.newton.tol = 1e-10;
  MoreauJean mj(reg, so);
  double worst = 0.0;
  for (int n = 0; n < 200; ++n) {
    const StepReport rep = mj.step();
    ASSERT_TRUE(rep.converged) << "step " << n << ": residual " << rep.residual;
    EXPECT_EQ(rep.solver, SolverKind::NEWTON_AC);
    EXPECT_GE(rep.residual, 0.0);
    for (std::size_t i = 1; i < reg.bodies.size(); ++i) worst = std::max(worst, std::abs(reg.bodies.vy[i]));
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(NewtonAC, HybridGivesTheSameStepAsPureNewton) {
  SKIP_WITHOUT_NEWTON();
  std::vector<double> v[2];
  for (int hybrid = 0; hybrid < 2; ++hybrid) {
    Registry reg = small_scene(0.4);
    StepperOptions so;
    so.solver = SolverKind::NEWTON_AC;
    so.newton.tol = 1e-12;
    so.newton.presweeps = hybrid ? 30 : 0;
    MoreauJean mj(reg, so);
    const StepReport rep = mj.step();
    ASSERT_TRUE(rep.converged) << "hybrid " << hybrid << ": residual " << rep.residual;
    EXPECT_EQ(rep.presweeps > 0, hybrid == 1);
    for (std::size_t i = 1; i < reg.bodies.size(); ++i)
      for (const double x : {reg.bodies.vx[i], reg.bodies.vy[i], reg.bodies.spin[i]}) v[hybrid].push_back(x);
  }
  // velocities are unique (impulses need not be): the two answers agree to the tolerance
  for (std::size_t k = 0; k < v[0].size(); ++k) EXPECT_NEAR(v[0][k], v[1][k], 1e-9) << k;
}

TEST(NewtonAC, SolvesTheSiconosGranularProblemsTo1e8) {
  SKIP_WITHOUT_NEWTON();
  const fs::path dir = fs::path(NSCD_TEST_DATA_DIR) / "siconos-fc2d";
  for (const char* name : {"FC2D_SliderCrankLagrangian00000.dat", "fc2d_granularflowonwall_00667_00000.dat",
                           "fc2d_granularflowonwall_02020_00213.dat", "fc2d_granularflowonwall_07002_00801.dat"}) {
    const FrictionProblem2D p = read_siconos_fc2d(dir / name);
    std::vector<double> r;
    NewtonOptions o;
    o.tol = 1e-8;
    o.max_iterations = 1000;
    const NewtonResult res = newton_ac_solve(p, r, o);
    EXPECT_TRUE(res.converged) << name << ": " << res.failure << ", residual " << res.residual;
    EXPECT_LE(natural_map_error(p, r).relative_q, 1e-8) << name;
    std::printf("[ measured ] %s: %d iterations (%d subproblems), residual %.2e\n", name, res.iterations,
                res.outer_iterations, res.residual);
  }
}

TEST(NewtonAC, RejectsBadOptionsAndNeverReturnsNaN) {
  SKIP_WITHOUT_NEWTON();
  NewtonOptions bad;
  bad.tol = 0.0;
  EXPECT_TRUE(Contains(error_message([&] { validate(bad); }), "tolerance"));
  bad = {};
  bad.max_iterations = 0;
  EXPECT_TRUE(Contains(error_message([&] { validate(bad); }), "max_iterations"));
  bad = {};
  bad.stall_inner = -1;
  EXPECT_TRUE(Contains(error_message([&] { validate(bad); }), "stall_inner"));
  // a problem with a non-finite q: the solver says so and leaves r finite
  Registry reg = block_column(3);
  MoreauJean mj(reg);
  prepare(mj);
  FrictionProblem2D p = mj.local_problem();
  p.q[1] = std::nan("");
  std::vector<double> r;
  const NewtonResult res = newton_ac_solve(p, r, NewtonOptions{});
  EXPECT_FALSE(res.converged);
  EXPECT_FALSE(res.failure.empty());
  for (double v : r) EXPECT_TRUE(std::isfinite(v));
}

TEST(NewtonACUnavailable, AskingForItWithoutSuiteSparseIsAClearError) {
  if (newton_ac_available()) GTEST_SKIP() << "this build has NEWTON_AC";
  Registry reg = block_column(2);
  StepperOptions so;
  so.solver = SolverKind::NEWTON_AC;
  EXPECT_TRUE(Contains(error_message([&] { MoreauJean mj(reg, so); }), "SuiteSparse"));
}

}  // namespace
