// tests/unit/test_nlgs_options.cpp — unit tests of the stand-alone NLGS's options (src/solvers/nlgs.hpp)
// on the small FrictionProblem2D of nlgs_problems.hpp, of its names, of the problem dump
// (local_problem.hpp), and of the stepper's solvers made by name (contact_solver.hpp).
//
// Suites: NlgsOptions, NlgsParse, NlgsDump, ContactSolver. The solutions, policies and orders:
// test_nlgs.cpp.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "nscd/core/error.hpp"
#include "nscd/solvers/contact_solver.hpp"
#include "nscd/solvers/local_problem.hpp"
#include "nscd/solvers/nlgs.hpp"
#include "nlgs_problems.hpp"
#include "temp_path.hpp"

namespace {

using namespace nscd;
using namespace nscd::nlgs_problems;

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
