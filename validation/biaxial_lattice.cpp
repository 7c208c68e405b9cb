// validation/biaxial_lattice.cpp — the biaxial test on the one packing whose strength is known in
// closed form: equal disks on a hexagonal lattice (shared/biaxial.hpp, hexagonal_biaxial_box),
// frictionless walls, the right wall pushed by σ₃, the top wall moving down at constant speed.
//
// The lattice cannot deform without sliding at its inclined contacts (those at ±β from the
// horizontal, β = 60° at the start), and the horizontal contacts open. Rowe's stress–dilatancy
// analysis of regular packings of rods (Rowe 1962) gives the stress ratio at which they slide:
//
//     σ₁ / σ₃ = tan β · tan(β + φ_μ),   tan φ_μ = μ,
//
// (docs/theory.md §5.4; a lattice with μ >= cot β = 0.577 cannot fail this way). Two checks:
//
//   * frictionless (μ = 0): every inclined contact carries the same force N (a uniform N balances
//     every disk, the end disks against the walls included), so the wall stresses are exact for
//     the finite box of n columns and R rows: F_top = 2 (n − 1) N sin β across a row interface,
//     F_side = (R − 1) N cos β across a vertical cut, hence
//         σ₁ / σ₃ = (F_top / W) / (F_side / H) = 2 (n − 1) tan β H / ((R − 1) W)
//     — the same as the virtual work of the one-degree-of-freedom mechanism;
//   * frictional (μ = 0.1, 0.2, 0.3), rotations fixed (Rowe's particles do not rotate): every
//     inclined contact slides with T = μ N, the same N everywhere again balances every disk, and
//         σ₁ / σ₃ = 2 (n − 1) tan(β + φ_μ) H / ((R − 1) W)   (walls),
//         σ₁ / σ₃ = tan β tan(β + φ_μ)                         (interior: Rowe),
//     the interior being the Love–Weber stress of the disks away from the walls;
//   * frictional with free rotations: the disks can roll instead (a mechanism without sliding
//     exists), and the lattice fails far below Rowe's ratio.
//
// β is measured, not assumed: the mean |angle| of the inclined contacts' normals of the row.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/shared/biaxial.hpp"
#include "validation_support.hpp"

namespace {

using namespace nscd;
using nscd::validation::rel_err;

struct LatticeRun {
  double wall_ratio = 0.0;      ///< ⟨σ₁⟩ / ⟨σ₃⟩ from the walls, time-averaged
  double interior_ratio = 0.0;  ///< major / minor principal value of the interior Love–Weber stress
  double beta = 0.0;            ///< mean inclination of the inclined contacts (rad)
  double open_fraction = 0.0;   ///< share of the horizontal grain–grain contacts without force
  double W = 0.0, H = 0.0;      ///< inner box (m), at the end
};

LatticeRun run_lattice(std::size_t columns, std::size_t rows, double mu, int steps, bool fix_rotations) {
  scenes::HexagonalOptions ho;
  ho.columns = columns;
  ho.rows = rows;
  ho.radius = 5e-3;
  scenes::BiaxialBox box = scenes::hexagonal_biaxial_box(ho);
  Registry& reg = box.reg;
  const double sigma3 = 1e4, dt = 1e-4;
  reg.params.dt = dt;
  reg.params.alert = 0.1 * ho.radius;
  set_contact_law(reg, box.grain_material, box.wall_material, LawSpec{LawKind::IQS_CLB, 0.0});
  set_contact_law(reg, box.grain_material, box.grain_material, LawSpec{LawKind::IQS_CLB, mu});
  if (fix_rotations)
    for (BodyId g : box.grains) fix_dof(reg, g, Dof::Rot);
  scenes::BiaxialBox* p = &box;
  impose_force(reg, box.right, Dof::X, TimeFunction::lambda([p, sigma3](double) { return -sigma3 * scenes::wall_state(*p).height; }));
  // a slow top wall: inertial number I = ε̇ d √(ρ/σ₃) = 1e-4
  const scenes::WallState w0 = scenes::wall_state(box);
  const double rate = 1e-4 / (2.0 * ho.radius * std::sqrt(ho.density / sigma3));
  impose_velocity(reg, box.top, Dof::Y, TimeFunction::constant(-rate * w0.height));
  StepperOptions so = nscd::validation::tight_options(1e-8, 5000);
  MoreauJean mj(reg, so);

  // interior grains: centres at least two radii-rows from every wall
  const double r = ho.radius, margin = 2.0 * std::sqrt(3.0) * r + 2.0 * r;
  scenes::StressAverage avg;
  double sxx = 0.0, syy = 0.0, sxy = 0.0, beta_sum = 0.0;
  std::size_t beta_n = 0, horiz = 0, horiz_open = 0;
  for (int s = 0; s < steps; ++s) {
    mj.step();
    if (s < steps / 4) continue;  // the start-up: the right wall gets its speed
    const scenes::WallState w = scenes::wall_state(box);
    avg.add(dt, w.sigma1, w.sigma3);
    const BodyTable& bt = reg.bodies;
    const ContactTable& c = reg.contacts;
    auto interior = [&](BodyId b) {
      const double x = bt.x[b.index()], y = bt.y[b.index()];
      return x > margin && x < w.width - margin && y > margin && y < w.height - margin;
    };
    auto is_wall = [&](BodyId b) { return b == box.bottom || b == box.top || b == box.left || b == box.right; };
    for (std::size_t k = 0; k < c.size(); ++k) {
      if (is_wall(c.cd_body[k]) || is_wall(c.an_body[k])) continue;
      const Vec2 n = c.normal[k], t = perp(n);
      const Vec2 f = c.rn[k] * n + c.rt[k] * t;  // on the candidate
      if (std::abs(n.y) < 0.5) {
        ++horiz;
        if (c.rn[k] <= 0.0) ++horiz_open;
      } else if (interior(c.cd_body[k]) && interior(c.an_body[k])) {
        beta_sum += std::asin(std::min(1.0, std::abs(n.y))), ++beta_n;
      }
      for (int side = 0; side < 2; ++side) {
        const BodyId b = side == 0 ? c.cd_body[k] : c.an_body[k];
        if (!interior(b)) continue;
        const Vec2 fb = side == 0 ? f : -1.0 * f;
        const Vec2 l{c.point[k].x - bt.x[b.index()], c.point[k].y - bt.y[b.index()]};
        sxx -= fb.x * l.x, syy -= fb.y * l.y, sxy -= 0.5 * (fb.x * l.y + fb.y * l.x);
      }
    }
  }
  LatticeRun out;
  out.wall_ratio = avg.sigma1() / avg.sigma3();
  const scenes::Stress2 in{sxx, syy, sxy};
  out.interior_ratio = in.major() / in.minor();
  out.beta = beta_sum / static_cast<double>(beta_n);
  out.open_fraction = horiz > 0 ? static_cast<double>(horiz_open) / static_cast<double>(horiz) : 1.0;
  const scenes::WallState w = scenes::wall_state(box);
  out.W = w.width, out.H = w.height;
  return out;
}

double rowe(double beta, double mu) { return std::tan(beta) * std::tan(beta + std::atan(mu)); }

/// The exact wall ratio of the finite box when every inclined contact slides with the same N.
double finite_box_ratio(const LatticeRun& r, std::size_t n, std::size_t R, double mu) {
  return 2.0 * static_cast<double>(n - 1) * std::tan(r.beta + std::atan(mu)) * r.H / (static_cast<double>(R - 1) * r.W);
}

constexpr std::size_t kColumns = 8, kRows = 9;
constexpr int kSteps = 200;

TEST(BiaxialLattice, FrictionlessLatticeSlidesAtTheExactStressRatio) {
  const LatticeRun r = run_lattice(kColumns, kRows, 0.0, kSteps, false);
  const double expected = finite_box_ratio(r, kColumns, kRows, 0.0);
  std::printf("mu 0: wall ratio %.5f, finite box %.5f, interior %.5f, tan^2 beta %.5f, beta %.4f deg, horizontal contacts open %.3f\n",
              r.wall_ratio, expected, r.interior_ratio, rowe(r.beta, 0.0), r.beta * 180.0 / kPi, r.open_fraction);
  EXPECT_LT(rel_err(r.wall_ratio, expected), 0.005);
  EXPECT_LT(rel_err(r.interior_ratio, rowe(r.beta, 0.0)), 0.005);
  EXPECT_GT(r.open_fraction, 0.99);
}

TEST(BiaxialLattice, NonRotatingFrictionalLatticeSlidesAtRowesStressRatio) {
  for (double mu : {0.1, 0.2, 0.3}) {
    const LatticeRun r = run_lattice(kColumns, kRows, mu, kSteps, true);
    const double expected = finite_box_ratio(r, kColumns, kRows, mu);
    std::printf("mu %.1f, rotations fixed: wall ratio %.5f, finite box %.5f, interior %.5f, Rowe %.5f, beta %.4f deg, open %.3f\n", mu,
                r.wall_ratio, expected, r.interior_ratio, rowe(r.beta, mu), r.beta * 180.0 / kPi, r.open_fraction);
    EXPECT_LT(rel_err(r.wall_ratio, expected), 0.005) << "mu " << mu;
    EXPECT_LT(rel_err(r.interior_ratio, rowe(r.beta, mu)), 0.005) << "mu " << mu;
    EXPECT_GT(r.open_fraction, 0.99) << "mu " << mu;
  }
}

TEST(BiaxialLattice, RotatingDisksRollAndStayFarBelowRowe) {
  // With free rotations the lattice has a mechanism without sliding: rotation rates growing
  // linearly along each row (ω of disk j of a row = ω₀ − 2 j s / r, s the affine slip rate)
  // make every inclined contact roll. The stepper finds a mix of rolling and sliding: the ratio
  // lies between the frictionless tan²β and Rowe's non-rotating value, much nearer the first
  // (3.3 against 7.3 at μ = 0.3 here). Round grains need rolling resistance or angular shapes to
  // be strong (docs/theory.md §5.4).
  const double mu = 0.3;
  const LatticeRun r = run_lattice(kColumns, kRows, mu, kSteps, false);
  std::printf("mu %.1f, free rotations: interior ratio %.5f, tan^2 beta %.5f, Rowe %.5f\n", mu, r.interior_ratio, rowe(r.beta, 0.0),
              rowe(r.beta, mu));
  EXPECT_GT(r.interior_ratio, 0.99 * rowe(r.beta, 0.0));
  EXPECT_LT(r.interior_ratio, 0.6 * rowe(r.beta, mu));
}

}  // namespace
