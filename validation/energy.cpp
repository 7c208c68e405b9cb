// validation/energy.cpp — the energy the stepper reports as dissipated (StepReport::
// contact_dissipation, damper_dissipation; docs/theory.md §7.1) against analytic answers and
// the scheme's exact energy balance.
//
// The balance of one θ-method step (docs/theory.md §7.1): with U_θ = (1 − θ) U⁻ + θ U⁺ and
// Δq = h u_θ,
//     ΔKE = (work of every force over Δq) − (θ − ½) Δuᵀ M Δu,
// so that with gravity (potential m g y), the contact dissipation D_c = −Σ P·U_θ and, for a
// VOIGT_ROD link, its viscous part D_v = Σ h ν U⁺ U_θ and the elastic energy ½ k (L − L_r)²,
//     KE + PE + E_el + D_c + D_v + D_θ + D_k = E_0,
//     D_θ = (θ − ½) Σ Δuᵀ M Δu   (the θ-scheme's damping, 0 at θ = ½),
//     D_k = ½ k Σ (ΔL)²          (the implicit spring's damping, L_f = L_m + θ h U⁺),
// exact in exact arithmetic whatever the solver's answer (u⁺ is computed from P), and exact
// for D_k when the link keeps its direction (a vertical spring on a vertical guide). Each case
// checks it to rounding (1e-10 of the initial energy over a few thousand steps), then its
// analytic answer:
//   (a) a block sliding on a horizontal floor (μ = 0.5, v0 = 1 m/s): while it slides
//       D_c = μ m g d (d the distance travelled); once stopped D_c = ½ m v0² − D_θ;
//   (b) a tilted block dropped on the floor (IQS_CLB, e = 0): lands on a corner, rocks, rests;
//       KE + PE + D_c + D_θ = E_0 at every step, D_c = E_0 − PE at rest;
//   (c) a mass hanging on one VOIGT_ROD spring, released at the rest length: D_v against
//       ∫ ν ẋ² dt of the damped oscillator's closed form; two masses in series (an iterated
//       link between two moving bodies) for the balance alone.
// Every case runs with NLGS and (nscd_validation_newton) NEWTON_AC.
//
// Suite: Energy.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "nscd/contactors/pt2dx.hpp"
#include "nscd/interactions/ptpt2.hpp"
#include "validation_support.hpp"

namespace {

using namespace nscd;
using nscd::validation::kG;
using nscd::validation::add_block;
using nscd::validation::add_floor;
using nscd::validation::rel_err;
using nscd::validation::tight_options;


// Σ m Δv² + I Δω² over the bodies, for D_θ (velocities before and after a step).
struct Velocities {
  std::vector<double> vx, vy, w;
  explicit Velocities(const Registry& reg) : vx(reg.bodies.vx), vy(reg.bodies.vy), w(reg.bodies.spin) {}
};
double delta_u_energy(const Registry& reg, const Velocities& before) {
  const BodyTable& b = reg.bodies;
  double e = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b.inv_mass_x[i] == 0.0 && b.inv_mass_y[i] == 0.0 && b.inv_inertia[i] == 0.0) continue;
    const double dx = b.vx[i] - before.vx[i], dy = b.vy[i] - before.vy[i], dw = b.spin[i] - before.w[i];
    e += b.mass[i] * (dx * dx + dy * dy) + b.inertia[i] * dw * dw;
  }
  return e;
}
double potential_energy(const Registry& reg) {
  const BodyTable& b = reg.bodies;
  double e = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b.inv_mass_y[i] != 0.0) e += b.mass[i] * kG * b.y[i];
  return e;
}

// (a) A block 0.2 m × 0.05 m (27 kg/m) on the floor at v0 = 1 m/s; μ g = 4.905 m/s², it stops
// after t = v0/(μ g) = 0.204 s, having travelled v0²/(2 μ g) = 0.1019 m.
TEST(Energy, SlidingBlockDissipatesItsKineticEnergyByFriction) {
  for (const double theta : {0.5, 1.0}) {
    Registry reg;
    reg.params.dt = 1e-3;
    reg.params.theta = theta;
    reg.params.gravity = {0.0, -kG};
    const MaterialId m = add_material(reg, "granite", 2700.0);
    constexpr double kMu = 0.5, kV0 = 1.0;
    set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, kMu});
    add_floor(reg, m);
    const BodyId block = add_block(reg, m, 0.2, 0.05, 0.0, 0.0);
    const std::size_t i = block.index();
    reg.bodies.vx[i] = kV0;
    const double mass = reg.bodies.mass[i], x0 = reg.bodies.x[i];
    const double e0 = kinetic_energy(reg) + potential_energy(reg);
    MoreauJean mj(reg, tight_options());
    double d_c = 0.0, d_theta = 0.0, worst_slide = 0.0, worst_balance = 0.0, last_dx = 0.0;
    int sliding_steps = 0;
    for (int n = 1; n <= 300; ++n) {
      const Velocities before(reg);
      const double x_before = reg.bodies.x[i];
      const StepReport r = mj.step();
      ASSERT_TRUE(r.converged) << "theta " << theta << " step " << n;
      d_c += r.contact_dissipation;
      d_theta += (theta - 0.5) * delta_u_energy(reg, before);
      const double balance = kinetic_energy(reg) + potential_energy(reg) + d_c + d_theta - e0;
      worst_balance = std::max(worst_balance, std::abs(balance) / e0);
      ASSERT_LT(std::abs(balance), 1e-10 * e0) << "theta " << theta << " step " << n;
      if (reg.bodies.vx[i] > 1e-9) {  // still sliding at the end of the step: friction is μ R_N throughout
        ++sliding_steps;
        const double slide = mass * kG * kMu * (reg.bodies.x[i] - x0);
        worst_slide = std::max(worst_slide, rel_err(d_c, slide));
        ASSERT_LT(rel_err(d_c, slide), 1e-9) << "theta " << theta << " step " << n;
      } else if (last_dx == 0.0) {
        last_dx = reg.bodies.x[i] - x_before;  // the step in which it stops
      }
    }
    // stopped: all of ½ m v0² went into friction (less the θ-scheme's own damping)
    EXPECT_LT(std::abs(reg.bodies.vx[i]), 1e-9);
    EXPECT_EQ(sliding_steps, 203) << "t_stop = v0/(μ g) = 0.2039 s";
    EXPECT_LT(rel_err(d_c, 0.5 * mass * kV0 * kV0 - d_theta), 1e-10);
    if (theta == 0.5) {
      EXPECT_EQ(d_theta, 0.0);
    }
    // in the stopping step the friction is below μ R_N: D_c lies between μ m g (d − last) and μ m g d
    const double d = reg.bodies.x[i] - x0;
    EXPECT_LE(d_c, kMu * mass * kG * d * (1.0 + 1e-9));
    EXPECT_GE(d_c, kMu * mass * kG * (d - last_dx) * (1.0 - 1e-9));
    std::printf("[ measured ] sliding block theta=%.1f: D_c %.12f J/m, 1/2 m v0^2 %.12f, D_theta %.3e, mu m g d %.12f, "
                "slide rel err %.2e, balance %.2e\n",
                theta, d_c, 0.5 * mass * kV0 * kV0, d_theta, kMu * mass * kG * d, worst_slide, worst_balance);
  }
}

// (b) The same block, tilted by 0.3 rad, dropped from 0.1 m: free fall (D_c = 0), an impact on
// a corner, rocking, rest. e = 0 (IQS_CLB), μ = 0.5.
TEST(Energy, DroppedBlockBalancesKineticPotentialAndDissipated) {
  for (const double theta : {0.5, 1.0}) {
    Registry reg;
    reg.params.dt = 1e-3;
    reg.params.theta = theta;
    reg.params.gravity = {0.0, -kG};
    const MaterialId m = add_material(reg, "granite", 2700.0);
    set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.5});
    add_floor(reg, m);
    const BodyId block = add_polygon_body(reg, rectangle(0.2, 0.05), m, {0.0, 0.2}, 0.3, "block");
    const std::size_t i = block.index();
    const double e0 = kinetic_energy(reg) + potential_energy(reg);
    MoreauJean mj(reg, tight_options());
    double d_c = 0.0, d_theta = 0.0, worst = 0.0, first_contact_time = -1.0;
    for (int n = 1; n <= 2000; ++n) {
      const Velocities before(reg);
      const StepReport r = mj.step();
      ASSERT_TRUE(r.converged) << "theta " << theta << " step " << n;
      if (r.active == 0 && first_contact_time < 0.0) {
        ASSERT_EQ(r.contact_dissipation, 0.0) << "free fall, step " << n;
      }
      if (r.active > 0 && first_contact_time < 0.0) first_contact_time = reg.time;
      d_c += r.contact_dissipation;
      d_theta += (theta - 0.5) * delta_u_energy(reg, before);
      const double balance = kinetic_energy(reg) + potential_energy(reg) + d_c + d_theta - e0;
      worst = std::max(worst, std::abs(balance) / e0);
      ASSERT_LT(std::abs(balance), 1e-10 * e0) << "theta " << theta << " step " << n;
      ASSERT_GT(d_c, -1e-12 * e0) << "the contacts never give energy back overall, step " << n;
    }
    EXPECT_GT(first_contact_time, 0.1) << "a fall of about 0.14 m takes about 0.17 s";
    EXPECT_LT(kinetic_energy(reg), 1e-9 * e0) << "at rest after 2 s";
    const double lost = e0 - potential_energy(reg);  // the drop of potential energy, all dissipated
    EXPECT_GT(lost, 0.0);
    EXPECT_LT(rel_err(d_c + d_theta, lost), 1e-9);
    std::printf("[ measured ] dropped block theta=%.1f: E0 %.9f J/m, D_c %.9f, D_theta %.3e, rest angle %.6f rad, "
                "worst balance %.2e of E0\n",
                theta, e0, d_c, d_theta, reg.bodies.angle[i], worst);
  }
}

// (c) A body of mass m (no contactor) guided vertically, hanging from the fixed ground by one
// VOIGT_ROD (k, ν), released at rest with the spring at its rest length L0 = 0.5 m. Up
// positive, x from the start, δ = m g / k, ω0 = √(k/m), ζ = ν/(2√(k m)), a = ζ ω0,
// ω_d = ω0 √(1 − ζ²):  x(t) = −δ + δ e^{−a t} (cos ω_d t + (a/ω_d) sin ω_d t),
// ẋ(t) = −δ (ω0²/ω_d) e^{−a t} sin ω_d t, and the viscous dissipation to time t is the energy
// lost, ∫₀ᵗ ν ẋ² = −(½ m ẋ² + ½ k x² + m g x).
struct Spring1D {
  Registry reg;
  BodyId ground;
  std::vector<BodyId> masses;
};

BodyId add_point_mass(Registry& reg, double mass, double y, const char* name) {
  RigidBodySpec s;
  s.name = name;
  s.mass = mass;
  s.inertia = 1.0;
  s.position = {0.0, y};
  const BodyId b = add_body(reg, s);
  fix_dof(reg, b, Dof::X);
  fix_dof(reg, b, Dof::Rot);
  return b;
}

// masses hang one under the other, each on a spring of length L0 from the one above
Spring1D hanging_chain(int n, double mass, double k, double nu, double L0) {
  Spring1D s;
  s.reg.params.dt = 2e-4;
  s.reg.params.theta = 0.5;
  s.reg.params.gravity = {0.0, -kG};
  RigidBodySpec g;
  g.name = "ground";
  g.mass = 1.0;
  g.inertia = 1.0;
  s.ground = add_body(s.reg, g);
  fix_body(s.reg, s.ground);
  BodyId above = s.ground;
  for (int j = 1; j <= n; ++j) {
    const double y = -L0 * j;
    const BodyId b = add_point_mass(s.reg, mass, y, "mass");
    const PointId p = attach_point_world(s.reg, b, {0.0, y});
    const PointId q = attach_point_world(s.reg, above, {0.0, y + L0});
    add_spring(s.reg, p, q, VoigtRod{k, nu, L0, 0.0});
    s.masses.push_back(b);
    above = b;
  }
  return s;
}

// Elastic energy from the bodies' positions (vertical links: L = y_above − y_below).
double elastic_energy(const Spring1D& s, double k, double L0) {
  double e = 0.0, above = 0.0;
  for (BodyId b : s.masses) {
    const double L = above - s.reg.bodies.y[b.index()];
    e += 0.5 * k * (L - L0) * (L - L0);
    above = s.reg.bodies.y[b.index()];
  }
  return e;
}

double spring_numerical_damping(const Spring1D& s, const std::vector<double>& y_before, double k) {
  double e = 0.0, prev_above = 0.0, above = 0.0;
  for (std::size_t j = 0; j < s.masses.size(); ++j) {
    const double y = s.reg.bodies.y[s.masses[j].index()];
    const double dL = (above - y) - (prev_above - y_before[j]);
    e += 0.5 * k * dL * dL;
    prev_above = y_before[j];
    above = y;
  }
  return e;
}

TEST(Energy, DamperDissipationMatchesTheDampedOscillator) {
  constexpr double kMass = 10.0, kK = 4100.0, kNu = 80.0, kL0 = 0.5;
  Spring1D s = hanging_chain(1, kMass, kK, kNu, kL0);
  const std::size_t i = s.masses[0].index();
  const double y0 = s.reg.bodies.y[i];
  const double delta = kMass * kG / kK, w0 = std::sqrt(kK / kMass), zeta = kNu / (2.0 * std::sqrt(kK * kMass));
  const double a = zeta * w0, wd = w0 * std::sqrt(1.0 - zeta * zeta);
  MoreauJean mj(s.reg, tight_options());
  double d_v = 0.0, d_k = 0.0, worst_balance = 0.0, worst_analytic = 0.0, worst_total = 0.0, last_rel = 0.0;
  const double h = s.reg.params.dt;
  const double total = 0.5 * kMass * kG * delta;  // all the oscillator ever loses (t → ∞)
  for (int n = 1; n <= 5000; ++n) {  // 1 s: 3.2 periods, the amplitude down to e^{-a} = 1.9 %
    const std::vector<double> y_before = {s.reg.bodies.y[i]};
    const StepReport r = mj.step();
    ASSERT_TRUE(r.converged);
    ASSERT_EQ(r.contact_dissipation, 0.0);
    d_v += r.damper_dissipation;
    d_k += spring_numerical_damping(s, y_before, kK);
    const double x = s.reg.bodies.y[i] - y0;
    const double balance = kinetic_energy(s.reg) + elastic_energy(s, kK, kL0) + kMass * kG * x + d_v + d_k;
    const double e_scale = kMass * kG * delta;  // m g δ = 2 × the energy finally dissipated
    worst_balance = std::max(worst_balance, std::abs(balance) / e_scale);
    ASSERT_LT(std::abs(balance), 1e-10 * e_scale) << "step " << n;
    if (n % 250 == 0) {
      const double t = n * h;
      const double xa = -delta + delta * std::exp(-a * t) * (std::cos(wd * t) + a / wd * std::sin(wd * t));
      const double va = -delta * w0 * w0 / wd * std::exp(-a * t) * std::sin(wd * t);
      const double exact = -(0.5 * kMass * va * va + 0.5 * kK * xa * xa + kMass * kG * xa);
      // viscous alone: short of ∫ ν ẋ² by the implicit spring's share D_k, about k h / (2 ν) = 0.5 %;
      // with D_k: the discrete trajectory's own error, largest early (the scheme's extra damping
      // ζ_num ≈ h ω0 / 4 shifts the motion), 1.7e-3 of the total at t = 0.15 s, 1.4e-5 at 1 s
      worst_analytic = std::max(worst_analytic, std::abs(d_v - exact) / total);
      worst_total = std::max(worst_total, std::abs(d_v + d_k - exact) / total);
      ASSERT_LT(std::abs(d_v - exact), 6e-3 * total) << "t " << t;
      ASSERT_LT(std::abs(d_v + d_k - exact), 2.5e-3 * total) << "t " << t;
      if (n == 5000) {
        EXPECT_LT(rel_err(d_v + d_k, exact), 5e-5);
        EXPECT_NEAR((exact - d_v) / exact, kK * h / (2.0 * kNu), 0.1 * kK * h / (2.0 * kNu));
        last_rel = rel_err(d_v, exact);
      }
    }
  }
  // at the end almost all of the energy the oscillator ever loses, ½ m g δ, is gone
  EXPECT_LT(rel_err(d_v + d_k, total), 2e-3);
  std::printf("[ measured ] damped spring: D_v %.9f J/m, D_k %.3e, at t = 1 s D_v is %.2e short of the analytic; worst error "
              "over the run (of 1/2 m g delta) of D_v %.2e, of D_v + D_k %.2e; worst balance %.2e\n",
              d_v, d_k, last_rel, worst_analytic, worst_total, worst_balance);
}

TEST(Energy, TwoMassesInSeriesBalanceWithAnIteratedLink) {
  constexpr double kMass = 5.0, kK = 4100.0, kNu = 80.0, kL0 = 0.5;
  Spring1D s = hanging_chain(2, kMass, kK, kNu, kL0);
  const double pe0 = potential_energy(s.reg);
  MoreauJean mj(s.reg, tight_options());
  double d_v = 0.0, d_k = 0.0, worst = 0.0;
  for (int n = 1; n <= 3000; ++n) {
    std::vector<double> y_before;
    for (BodyId b : s.masses) y_before.push_back(s.reg.bodies.y[b.index()]);
    const StepReport r = mj.step();
    ASSERT_TRUE(r.converged);
    d_v += r.damper_dissipation;
    d_k += spring_numerical_damping(s, y_before, kK);
    const double balance = kinetic_energy(s.reg) + elastic_energy(s, kK, kL0) + potential_energy(s.reg) - pe0 + d_v + d_k;
    worst = std::max(worst, std::abs(balance) / (kMass * kG * 0.05));
    ASSERT_LT(std::abs(balance), 1e-10 * kMass * kG * 0.05) << "step " << n;
  }
  EXPECT_GT(d_v, 0.0);
  std::printf("[ measured ] two masses: D_v %.9f J/m, D_k %.3e, worst balance %.2e\n", d_v, d_k, worst);
}

}  // namespace
