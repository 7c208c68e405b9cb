// tests/unit/test_dump_problem.cpp — the contact problem dumped by the Moreau–Jean stepper
// (MoreauJean::local_problem) is the problem the scene solves: the stand-alone NLGS on the
// assembled W reproduces the scene's impulses, and so does the problem written to a file and
// read back.
//
// Scene: a fixed floor, three boxes stacked on it and four pentagons (on the floor, against the
// stack, on top of the stack, on another pentagon), each overlapping its support by 0.2–0.5 mm;
// default law IQS_CLB, μ = 0.5; one step from rest, cold start (no warm start).
//
// Suite: DumpProblem.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "nscd/registry/registry.hpp"
#include "nscd/solvers/local_problem.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "nscd/solvers/nlgs.hpp"
#include "temp_path.hpp"

namespace {

using namespace nscd;

// A regular pentagon of circumscribed radius R = 0.1 with orientation −54° has a horizontal
// bottom edge at y = −R cos 36° = −0.0809 and side vertices (±R sin 72° = ±0.0951, R sin 18°
// = 0.0309) in its own frame (vertices at −54°, 18°, 90°, 162°, 234°).
constexpr double kDumpR = 0.1;
constexpr double kPentaAngle = -0.3 * kPi;
const double kApothem = kDumpR * std::cos(0.2 * kPi);  // 0.0809
const double kSide = kDumpR * std::sin(0.4 * kPi);     // 0.0951

void build_scene(Registry& reg) {
  const MaterialId rock = add_material(reg, "rock", 2000.0);
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.5, 0.0, 0.0});
  const BodyId floor = add_polygon_body(reg, rectangle(3.0, 0.2), rock, {0.0, -0.1}, 0.0, "floor");
  fix_body(reg, floor);
  // Three 0.2 m boxes stacked at x = 0.05, each sinking 0.5 mm into its support.
  double top = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double y = top + 0.1 - 5e-4;
    add_polygon_body(reg, rectangle(0.2, 0.2), rock, {0.05, y}, 0.0, "box " + std::to_string(k));
    top = y + 0.1;
  }
  const Polygon penta = regular_polygon(5, 2.0 * kDumpR, kPentaAngle);
  // On the floor, its left vertex 0.3 mm inside the bottom box's right face (x = 0.15).
  add_polygon_body(reg, penta, rock, {0.15 + kSide - 3e-4, kApothem - 2e-4}, 0.0, "penta against the stack");
  // On top of the stack.
  add_polygon_body(reg, penta, rock, {0.07, top + kApothem - 3e-4}, 0.0, "penta on top");
  // On the floor alone, and a second one whose bottom edge rests on the first one's top vertex
  // (at y = y_1 + R), 2 cm off its axis, 0.3 mm deep.
  const double y1 = kApothem - 4e-4;
  add_polygon_body(reg, penta, rock, {-0.5, y1}, 0.0, "penta on the floor");
  add_polygon_body(reg, penta, rock, {-0.48, y1 + kDumpR + kApothem - 3e-4}, 0.0, "penta on a penta");
}

StepperOptions options() {
  StepperOptions o;
  o.warm_start = false;
  o.nlgs.policy = ConvergencePolicy::Quad;
  o.nlgs.tol = 1e-6;
  o.nlgs.max_sweeps = 10000;
  o.nlgs.order = SweepOrder::Fixed;
  return o;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

TEST(DumpProblem, StandAloneSolveReproducesTheScene) {
  Registry reg;
  build_scene(reg);
  const StepperOptions opt = options();
  MoreauJean mj(reg, opt);
  mj.begin_step();
  mj.detect();
  mj.prepare();
  const FrictionProblem2D problem = mj.local_problem();
  // Every support is in contact, edge–edge contacts giving 2 points each: box–floor 2, box–box
  // 2 × 2, penta–floor 2 × 2, penta on top–box 2, penta–box side (vertex) 1, penta–penta
  // (vertex) 1: 14 points.
  ASSERT_GE(problem.nc, 10u);
  EXPECT_EQ(problem.nc, 14u);
  EXPECT_EQ(problem.nc, reg.contacts.size());
  for (double m : problem.mu) EXPECT_EQ(m, 0.5);

  // 1. The stand-alone solve, with the scene's own options.
  std::vector<double> r;
  const NlgsResult res = nlgs_solve(problem, r, opt.nlgs);
  ASSERT_TRUE(res.converged);
  // 2. The scene's solve.
  mj.solve();
  ASSERT_TRUE(mj.report().converged);
  const std::vector<double> scene_r = mj.impulses();
  ASSERT_EQ(scene_r.size(), r.size());
  EXPECT_EQ(mj.report().sweeps, res.sweeps);
  // Same impulses to 1e-9 relative (only the rounding of the two backends differs).
  const double scale = max_abs(scene_r);
  ASSERT_GT(scale, 0.0);
  for (std::size_t k = 0; k < r.size(); ++k) EXPECT_NEAR(r[k], scene_r[k], 1e-9 * scale) << "entry " << k;
  // The scene's impulses solve the dumped problem.
  EXPECT_LT(natural_map_error(problem, scene_r).relative_q, 1e-5);
  // Every body rests on its supports: every contact point carries a normal impulse.
  for (std::size_t a = 0; a < problem.nc; ++a) EXPECT_GT(scene_r[2 * a], 0.0) << "contact " << a;
  double max_diff = 0.0;
  for (std::size_t k = 0; k < r.size(); ++k) max_diff = std::max(max_diff, std::abs(r[k] - scene_r[k]));
  RecordProperty("sweeps", res.sweeps);
  RecordProperty("max_relative_difference", (::testing::Message() << max_diff / scale).GetString());

  // 3. Through a file: write, read, solve again: the same impulses (the file is exact).
  const auto file = nscd::testing_support::unique_temp_path("test_dump_problem").concat(".txt");
  write_problem(file, problem, scene_r);
  std::vector<double> r_file;
  const FrictionProblem2D read = read_problem(file, &r_file);
  std::filesystem::remove(file);
  EXPECT_EQ(r_file, scene_r);
  EXPECT_EQ(read.q, problem.q);
  std::vector<double> r2;
  const NlgsResult res2 = nlgs_solve(read, r2, opt.nlgs);
  EXPECT_EQ(res2.sweeps, res.sweeps);
  EXPECT_EQ(r2, r);  // bit for bit: the same problem, the same arithmetic
  for (std::size_t k = 0; k < r.size(); ++k) EXPECT_NEAR(r2[k], scene_r[k], 1e-9 * scale) << "entry " << k;

  mj.end_step();
}

TEST(DumpProblem, AssembledWIsSymmetricWithSpdDiagonalBlocks) {
  // W = H* M⁻¹ H assembled body by body is symmetric; its diagonal blocks are positive definite.
  Registry reg;
  build_scene(reg);
  MoreauJean mj(reg, options());
  mj.begin_step();
  mj.detect();
  mj.prepare();
  const FrictionProblem2D p = mj.local_problem();
  std::vector<double> ei(2 * p.nc, 0.0), ej(2 * p.nc, 0.0), wi, wj;
  for (std::size_t i = 0; i < 2 * p.nc; ++i) {
    ei.assign(2 * p.nc, 0.0);
    ei[i] = 1.0;
    p.multiply(ei, wi);
    for (std::size_t j = 0; j < i; ++j) {
      ej.assign(2 * p.nc, 0.0);
      ej[j] = 1.0;
      p.multiply(ej, wj);
      EXPECT_NEAR(wi[j], wj[i], 1e-12 * (std::abs(wi[i]) + std::abs(wj[j]))) << i << " " << j;
    }
  }
  for (std::size_t a = 0; a < p.nc; ++a) {
    const auto& b = p.block[p.diag[a]];
    EXPECT_GT(b[0], 0.0);
    EXPECT_GT(b[0] * b[3] - b[1] * b[2], 0.0);
  }
  // local_problem() before prepare() throws.
  Registry reg2;
  build_scene(reg2);
  MoreauJean mj2(reg2, options());
  EXPECT_THROW(mj2.local_problem(), Error);
}

}  // namespace
