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
// (docs/theory.md §5.4; a lattice with μ >= cot β = 0.577 cannot fail this way). Three checks:
//
//   * frictionless (μ = 0): every inclined contact carries the same force N (a uniform N balances
//     every disk, the end disks against the walls included), so the wall stresses are exact for
//     the finite box of n columns and R rows: F_top = 2 (n − 1) N sin β across a row interface,
//     F_side = (R − 1) N cos β across a vertical cut, hence
//         σ₁ / σ₃ = (F_top / W) / (F_side / H) = 2 (n − 1) tan β H / ((R − 1) W)
//     — the same as the virtual work of the one-degree-of-freedom mechanism;
//   * frictional (μ = 0.1, 0.2, 0.3), rotations fixed (Rowe's particles do not rotate): every
//     inclined contact slides with T = μ N, the same N everywhere again balances every disk (the
//     four corner disks' friction couple taken by their rotation constraint), and
//         σ₁ / σ₃ = 2 (n − 1) tan(β + φ_μ) H / ((R − 1) W)   (walls),
//         σ₁ / σ₃ = tan β tan(β + φ_μ)                         (interior: Rowe),
//     the interior being the Love–Weber stress of the disks away from the walls;
//   * frictional with free rotations: the disks can roll instead (a mechanism without sliding
//     exists), and the lattice fails far below Rowe's ratio.
//
// β is measured, not assumed: at every step, the mean |angle| of the interior inclined contacts'
// normals; the finite-box ratio is evaluated with each step's β and box and averaged as the wall
// stresses are (weighted by σ₃).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/shared/biaxial.hpp"
#include "validation_support.hpp"

namespace {

using namespace nscd;
using nscd::validation::rel_err;

struct LatticeRun {
  double wall_ratio = 0.0;      ///< ⟨σ₁⟩ / ⟨σ₃⟩ from the walls, time-averaged
  double finite_box = 0.0;      ///< the exact finite-box ratio of each step (its β, W, H), averaged as σ₃ weighs it
  double interior_ratio = 0.0;  ///< major / minor principal value of the interior Love–Weber stress
  double beta = 0.0;            ///< mean inclination of the interior inclined contacts (rad)
  double open_fraction = 0.0;   ///< share of the horizontal grain–grain contacts without force
};

/// The exact wall ratio of the finite box (n columns, R rows, inner box W × H) when every
/// inclined contact, at β from the horizontal, slides with the same N.
double finite_box_ratio(double beta, double W, double H, std::size_t n, std::size_t R, double mu) {
  return 2.0 * static_cast<double>(n - 1) * std::tan(beta + std::atan(mu)) * H / (static_cast<double>(R - 1) * W);
}

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
  scenes::Stress2 interior_sum;  // Σ over the steps of the interior grains' Love–Weber stress
  std::vector<std::uint8_t> interior_mask(reg.bodies.size(), 0);
  double beta_sum = 0.0, s3_expected = 0.0, s3_sum = 0.0;
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
    double step_beta = 0.0;
    std::size_t step_n = 0;
    for (std::size_t k = 0; k < c.size(); ++k) {
      if (is_wall(c.cd_body[k]) || is_wall(c.an_body[k])) continue;
      const Vec2 n = c.normal[k];
      if (std::abs(n.y) < 0.5) {
        ++horiz;
        if (c.rn[k] <= 0.0) ++horiz_open;
      } else if (interior(c.cd_body[k]) && interior(c.an_body[k])) {
        step_beta += std::asin(std::min(1.0, std::abs(n.y))), ++step_n;
      }
    }
    for (BodyId g : box.grains) interior_mask[g.index()] = interior(g) ? 1 : 0;
    const scenes::Stress2 in = scenes::internal_stress(box, w, &interior_mask);
    interior_sum.xx += in.xx, interior_sum.yy += in.yy, interior_sum.xy += in.xy;
    // this step's exact finite-box ratio, with this step's β and box
    if (step_n == 0) continue;
    beta_sum += step_beta, beta_n += step_n;
    s3_expected += w.sigma3 * finite_box_ratio(step_beta / static_cast<double>(step_n), w.width, w.height, columns, rows, mu);
    s3_sum += w.sigma3;
  }
  LatticeRun out;
  EXPECT_GT(horiz, 0u);  // the horizontal contacts are detected (and must open)
  EXPECT_GT(beta_n, 0u);
  if (beta_n == 0 || !(s3_sum > 0.0)) return out;
  out.wall_ratio = avg.sigma1() / avg.sigma3();
  out.finite_box = s3_expected / s3_sum;  // Σ σ₁ = Σ ratio_k σ₃,k: the ratio σ₃-weighted
  out.interior_ratio = interior_sum.major() / interior_sum.minor();
  out.beta = beta_sum / static_cast<double>(beta_n);
  out.open_fraction = horiz > 0 ? static_cast<double>(horiz_open) / static_cast<double>(horiz) : 0.0;
  return out;
}

double rowe(double beta, double mu) { return std::tan(beta) * std::tan(beta + std::atan(mu)); }

constexpr std::size_t kColumns = 8, kRows = 9;
constexpr int kSteps = 200;

TEST(BiaxialLattice, FrictionlessLatticeSlidesAtTheExactStressRatio) {
  const LatticeRun r = run_lattice(kColumns, kRows, 0.0, kSteps, false);
  const double expected = r.finite_box;
  std::printf("mu 0: wall ratio %.5f, finite box %.5f, interior %.5f, tan^2 beta %.5f, beta %.4f deg, horizontal contacts open %.3f\n",
              r.wall_ratio, expected, r.interior_ratio, rowe(r.beta, 0.0), r.beta * 180.0 / kPi, r.open_fraction);
  EXPECT_LT(rel_err(r.wall_ratio, expected), 1e-4);
  EXPECT_LT(rel_err(r.interior_ratio, rowe(r.beta, 0.0)), 1e-4);
  EXPECT_GT(r.open_fraction, 0.99);
}

TEST(BiaxialLattice, NonRotatingFrictionalLatticeSlidesAtRowesStressRatio) {
  for (double mu : {0.1, 0.2, 0.3}) {
    const LatticeRun r = run_lattice(kColumns, kRows, mu, kSteps, true);
    const double expected = r.finite_box;
    std::printf("mu %.1f, rotations fixed: wall ratio %.5f, finite box %.5f, interior %.5f, Rowe %.5f, beta %.4f deg, open %.3f\n", mu,
                r.wall_ratio, expected, r.interior_ratio, rowe(r.beta, mu), r.beta * 180.0 / kPi, r.open_fraction);
    EXPECT_LT(rel_err(r.wall_ratio, expected), 1e-4) << "mu " << mu;
    EXPECT_LT(rel_err(r.interior_ratio, rowe(r.beta, mu)), 1e-4) << "mu " << mu;
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
