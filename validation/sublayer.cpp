// validation/sublayer.cpp — the visco-elastic sublayer (paper §2.9, §4.1) against the answers
// of a one-degree-of-freedom damped oscillator.
//
// The paper calibrates its sublayer by pressing the sleeper directly on the elastomer: each
// VOIGT_ROD spring has k_N = 4100 N/m and ν = 80 N·s/m. Here an aluminium sleeper (ρ = 2700,
// 0.3 m × 0.1 m: M = 2700 × 0.03 = 81 kg/m) is guided vertically (X and Rot fixed) and carries
// gravity plus an imposed force F = −1000 N/m. With n = 5 springs in parallel the vertical
// motion x (up positive, from the start) obeys
//     M ẍ + n ν ẋ + n k x = F − M g,
// so, released at rest with the springs at their rest length,
//     static deflection δ = (|F| + M g)/(n k) = (1000 + 794.61)/20500 = 0.087542 m,
//     ω0 = √(n k / M) = √(20500/81) = 15.909 rad/s,
//     ζ  = n ν / (2 √(n k M)) = 400/(2 √(20500 × 81)) = 0.15521,
//     damped period T = 2π/(ω0 √(1 − ζ²)) = 0.39980 s,
//     successive extrema (of x + δ) alternate in sign with the ratio
//         −exp(−ζ ω0 T/2) = −exp(−π ζ/√(1 − ζ²)) = −0.61044.
// The extrema are located on the sampled positions by a parabola through the three samples
// around each turn (sub-step accuracy). With h = 2e-4 s (hω0 = 3.2e-3) the θ = 0.5 scheme's
// own errors are far below the 1 % asserted: the spring force is taken at the end-of-step
// length L_m + θ h U (voigt_rod.hpp), which adds a numerical damping of about h ω0² / 4 per
// unit time (ζ_num ≈ h ω0 / 4 = 8e-4) and shifts the period by O((h ω0)²).
//
// Then the sleeper rests on five light pads (rectangles 0.04 m × 0.01 m, each on its own
// spring, X and Rot fixed) through PLPLx contacts (IQS_CLB, μ = 0.5): the pads move with the
// sleeper, so the same formulas hold with M replaced by M + 5 m_pad, the pads' weight included
// in the static load.
//
// Last, implicit stability: springs 10^4 and 10^6 times stiffer under pads of 1e-3 kg, where a
// pad alone has h √(k/m_pad) = 40 and 400, far beyond the explicit limit 2. The VOIGT_ROD law
// solved inside the NLGS (the "derived Signorini law") must stay bounded and settle.
//
// Suites: Sublayer (cases 1), Sublayer/SublayerStiffness (case 2, k × 1e4 and k × 1e6).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "nscd/contactors/pt2dx.hpp"
#include "nscd/interactions/ptpt2.hpp"
#include "validation_support.hpp"

namespace {

using namespace nscd;
using nscd::validation::kG;
using nscd::validation::rel_err;
using nscd::validation::tight_options;

constexpr double kK = 4100.0;       // N/m per spring (paper §4.1)
constexpr double kNu = 80.0;        // N·s/m per spring
constexpr int kSprings = 5;
constexpr double kForce = -1000.0;  // imposed on the sleeper (N/m)
constexpr double kL0 = 0.5;         // spring length (m): more than the largest compression, (1 + 0.61) δ = 0.14 m
constexpr double kSleeperW = 0.3, kSleeperH = 0.1, kSleeperRho = 2700.0;
constexpr double kPadW = 0.04, kPadH = 0.01;
// x of the springs (and pads): 0.02 m between pads, more than the alert distance, so pads
// never touch each other
constexpr double kSpringX[kSprings] = {-0.12, -0.06, 0.0, 0.06, 0.12};

struct SublayerScene {
  Registry reg;
  BodyId ground, sleeper;
  std::vector<BodyId> pads;
  double moving_mass = 0.0;  // sleeper + pads (kg/m)
  double load = 0.0;         // |F| + weight of everything the springs carry (N/m)
};

Registry base_registry(double theta) {
  Registry reg;
  reg.params.dt = 2e-4;
  reg.params.theta = theta;
  reg.params.gravity = {0.0, -kG};
  return reg;
}

// The fixed ground that anchors the springs: a body without contactor, at the origin.
BodyId add_ground(Registry& reg) {
  RigidBodySpec g;
  g.name = "ground";
  g.mass = 1.0;
  g.inertia = 1.0;
  const BodyId b = add_body(reg, g);
  fix_body(reg, b);
  return b;
}

// The sleeper, guided vertically, its bottom face on y = bottom, under F.
BodyId add_sleeper(Registry& reg, double bottom) {
  const MaterialId al = add_material(reg, "aluminium", kSleeperRho);
  const BodyId s = add_polygon_body(reg, rectangle(kSleeperW, kSleeperH), al, {0.0, bottom + 0.5 * kSleeperH}, 0.0, "sleeper");
  fix_dof(reg, s, Dof::X);
  fix_dof(reg, s, Dof::Rot);
  impose_force(reg, s, Dof::Y, TimeFunction::constant(kForce));
  return s;
}

// Case 1: the sleeper tied directly to the ground by the five springs (from the ground at
// y = 0 to the sleeper's bottom face at y = L0, so the springs start at their rest length).
SublayerScene direct_springs(double theta, double k) {
  SublayerScene s{base_registry(theta), {}, {}, {}, 0.0, 0.0};
  Registry& reg = s.reg;
  s.ground = add_ground(reg);
  s.sleeper = add_sleeper(reg, kL0);
  for (double x : kSpringX) {
    const PointId top = attach_point_world(reg, s.sleeper, {x, kL0});
    const PointId anchor = attach_point_world(reg, s.ground, {x, 0.0});
    add_spring(reg, top, anchor, VoigtRod{k, kNu, 0.0, 0.0});  // L0 <= 0: the current length
  }
  s.moving_mass = reg.bodies.mass[s.sleeper.index()];
  s.load = -kForce + s.moving_mass * kG;
  return s;
}

// Case 2: the sleeper resting (gap 0) on five pads, each pad on its own spring.
SublayerScene on_pads(double theta, double k, double pad_mass) {
  SublayerScene s{base_registry(theta), {}, {}, {}, 0.0, 0.0};
  Registry& reg = s.reg;
  s.ground = add_ground(reg);
  s.sleeper = add_sleeper(reg, kL0 + kPadH);
  const MaterialId pad_m = add_material(reg, "pad", pad_mass / (kPadW * kPadH));
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.5});
  s.moving_mass = reg.bodies.mass[s.sleeper.index()];
  for (int i = 0; i < kSprings; ++i) {
    const double x = kSpringX[i];
    const BodyId pad = add_polygon_body(reg, rectangle(kPadW, kPadH), pad_m, {x, kL0 + 0.5 * kPadH}, 0.0,
                                        "pad " + std::to_string(i));
    fix_dof(reg, pad, Dof::X);
    fix_dof(reg, pad, Dof::Rot);
    const PointId bottom = attach_point_world(reg, pad, {x, kL0});
    const PointId anchor = attach_point_world(reg, s.ground, {x, 0.0});
    add_spring(reg, bottom, anchor, VoigtRod{k, kNu, kL0, 0.0});
    s.pads.push_back(pad);
    s.moving_mass += reg.bodies.mass[pad.index()];
  }
  s.load = -kForce + s.moving_mass * kG;
  return s;
}

// The oscillator's answers for n springs of stiffness k carrying mass m.
struct Oscillator {
  double omega0, zeta, period, ratio;  // ratio: |x_{m+1}| / |x_m| of successive extrema
};
Oscillator oscillator(double k, double m) {
  Oscillator o;
  o.omega0 = std::sqrt(kSprings * k / m);
  o.zeta = kSprings * kNu / (2.0 * std::sqrt(kSprings * k * m));
  o.period = 2.0 * kPi / (o.omega0 * std::sqrt(1.0 - o.zeta * o.zeta));
  o.ratio = std::exp(-o.zeta * o.omega0 * 0.5 * o.period);
  return o;
}

struct Extremum {
  double t, value;
};

// Turning points of a sampled signal (samples at t = j h), refined by the parabola through
// the three samples around each: with d1 = y_j − y_{j−1}, d2 = y_{j+1} − y_j, c = d2 − d1,
//     t* = t_j − h (d1 + d2)/(2c),   y* = y_j − (d1 + d2)²/(8c).
// Only turns farther than `floor` from `centre` count (the tail of the decay is rounding).
std::vector<Extremum> extrema(const std::vector<double>& y, double h, double centre, double floor) {
  std::vector<Extremum> out;
  for (std::size_t j = 1; j + 1 < y.size(); ++j) {
    const double d1 = y[j] - y[j - 1], d2 = y[j + 1] - y[j];
    if (!((d1 > 0.0 && d2 <= 0.0) || (d1 < 0.0 && d2 >= 0.0))) continue;
    const double c = d2 - d1;
    const Extremum e{h * (static_cast<double>(j) - 0.5 * (d1 + d2) / c), y[j] - (d1 + d2) * (d1 + d2) / (8.0 * c)};
    if (std::abs(e.value - centre) > floor) out.push_back(e);
  }
  return out;
}

struct History {
  std::vector<double> y;         // sleeper's y at every step (index 0: the start)
  double max_speed = 0.0;        // over all bodies and steps
  double late_max_speed = 0.0;   // over all bodies, the last tenth of the run
  int unconverged = 0;           // steps whose NLGS stopped at max_sweeps
  int last_unconverged = 0;      // the last such step (1-based; 0: none)
  StepReport last;               // the last step's report
};

History run(SublayerScene& s, int steps, const StepperOptions& opt) {
  MoreauJean mj(s.reg, opt);
  History r;
  r.y.reserve(static_cast<std::size_t>(steps) + 1);
  r.y.push_back(s.reg.bodies.y[s.sleeper.index()]);
  for (int n = 1; n <= steps; ++n) {
    r.last = mj.step();
    if (!r.last.converged) {
      ++r.unconverged;
      r.last_unconverged = n;
    }
    r.y.push_back(s.reg.bodies.y[s.sleeper.index()]);
    for (std::size_t b = 0; b < s.reg.bodies.size(); ++b) {
      const double speed = std::hypot(s.reg.bodies.vx[b], s.reg.bodies.vy[b]);
      r.max_speed = std::max(r.max_speed, speed);
      if (10 * n > 9 * steps) r.late_max_speed = std::max(r.late_max_speed, speed);
    }
  }
  return r;
}

double spring_force_sum(const Registry& reg) {
  double sum = 0.0;
  for (double rn : reg.links.rn) sum += rn;
  return sum;
}

// Checks the period and decay ratio over the first half periods of a run.
void expect_oscillation(const History& r, double h, double y_eq, double deflection, const Oscillator& o,
                        const std::string& what) {
  const std::vector<Extremum> e = extrema(r.y, h, y_eq, 1e-3 * deflection);
  ASSERT_GE(e.size(), 8u) << what;
  for (std::size_t m = 0; m + 1 < 8; ++m) {
    const double half_period = e[m + 1].t - e[m].t;
    const double ratio = (e[m + 1].value - y_eq) / (e[m].value - y_eq);
    EXPECT_LT(rel_err(2.0 * half_period, o.period), 0.01) << what << ", half period " << m;
    EXPECT_LT(rel_err(-ratio, o.ratio), 0.01) << what << ", half period " << m;
    if (m == 0)
      std::printf("[ %s ] period %.6f s (1-dof %.6f), decay ratio %.6f (1-dof %.6f)\n", what.c_str(), 2.0 * half_period,
                  o.period, -ratio, o.ratio);
  }
  // the first turn is the lowest point: released at rest at δ above the equilibrium, the
  // sleeper first overshoots to y_eq − ratio δ
  EXPECT_LT(rel_err(y_eq - e[0].value, o.ratio * deflection), 0.01) << what;
}

// ---- 1. the sleeper on its springs ------------------------------------------------------------

TEST(Sublayer, DirectSpringsGiveTheStaticDeflectionPeriodAndDecay) {
  SublayerScene s = direct_springs(0.5, kK);
  const double M = s.moving_mass;
  ASSERT_NEAR(M, 81.0, 1e-12);
  const double deflection = s.load / (kSprings * kK);  // (1000 + 81 g)/20500 = 0.087542 m
  const double y0 = s.reg.bodies.y[s.sleeper.index()], y_eq = y0 - deflection;
  const Oscillator o = oscillator(kK, M);
  // 10 s: the oscillation decays as exp(−ζ ω0 t) = exp(−2.47 t), 1.9e-11 at the end
  const History r = run(s, 50000, tight_options(1e-12));
  EXPECT_EQ(r.unconverged, 0);
  expect_oscillation(r, s.reg.params.dt, y_eq, deflection, o, "direct springs, theta 0.5");
  EXPECT_LT(rel_err(y0 - r.y.back(), deflection), 1e-9);
  EXPECT_LT(rel_err(spring_force_sum(s.reg), s.load), 1e-9);  // the springs carry the load
  std::printf("[ direct springs ] deflection %.12f m, expected %.12f m\n", y0 - r.y.back(), deflection);
}

TEST(Sublayer, DirectSpringsWithThetaOneReachTheSameStaticDeflection) {
  // θ = 1 dissipates more per step (a larger numerical damping) but its fixed point is the
  // same: at rest L_f = L_m and the law reads R_N = −k (L − L0).
  SublayerScene s = direct_springs(1.0, kK);
  const double deflection = s.load / (kSprings * kK);
  const double y0 = s.reg.bodies.y[s.sleeper.index()];
  const History r = run(s, 50000, tight_options(1e-12));
  EXPECT_EQ(r.unconverged, 0);
  EXPECT_LT(rel_err(y0 - r.y.back(), deflection), 1e-9);
  EXPECT_LT(rel_err(spring_force_sum(s.reg), s.load), 1e-9);
}

TEST(Sublayer, SleeperOnPadsGivesTheStaticDeflectionAndPeriod) {
  // pads of 0.04 kg/m each: 5 × 0.04 = 0.2 kg/m, 0.25 % of the sleeper
  SublayerScene s = on_pads(0.5, kK, 0.04);
  const double M = s.moving_mass;
  ASSERT_NEAR(M, 81.2, 1e-9);
  const double deflection = s.load / (kSprings * kK);  // (1000 + 81.2 g)/20500
  const double y0 = s.reg.bodies.y[s.sleeper.index()], y_eq = y0 - deflection;
  const Oscillator o = oscillator(kK, M);
  const History r = run(s, 40000, tight_options(1e-12));
  EXPECT_EQ(r.unconverged, 0);
  expect_oscillation(r, s.reg.params.dt, y_eq, deflection, o, "sleeper on pads");
  EXPECT_LT(rel_err(y0 - r.y.back(), deflection), 1e-6);
  EXPECT_LT(rel_err(spring_force_sum(s.reg), s.load), 1e-6);
  // every pad went down with the sleeper, and each pad's spring carries a fifth of the load
  for (BodyId p : s.pads) {
    const std::size_t i = p.index();
    EXPECT_LT(rel_err(s.reg.bodies.y0[i] - s.reg.bodies.y[i], deflection), 1e-6);
  }
  for (double rn : s.reg.links.rn) EXPECT_LT(rel_err(rn, s.load / kSprings), 1e-6);
  // the pads carry the sleeper: 10 contact points (an edge on an edge, 2 per pad) whose
  // normal forces (n = (0, 1)) add up to |F| + M_sleeper g
  EXPECT_EQ(r.last.contacts, 10u);
  double contact_sum = 0.0;
  for (double rn : s.reg.contacts.rn) contact_sum += rn;
  EXPECT_LT(rel_err(contact_sum, -kForce + s.reg.bodies.mass[s.sleeper.index()] * kG), 1e-6);
  std::printf("[ sleeper on pads ] deflection %.12f m, expected %.12f m\n", y0 - r.y.back(), deflection);
}

// ---- 2. implicit stability --------------------------------------------------------------------
//
// Springs 10^4 and 10^6 times stiffer (k = 4.1e7 and 4.1e9 N/m) under pads of 1e-3 kg. A pad
// alone on its spring has h √(k/m_pad) = 40 and 400: an explicit spring force would multiply
// the pad's motion by about (h ω)² = 1600 to 160,000 per step. Released from rest as in case 1:
//   * nothing blows up, and no body ever moves faster than the larger of ω0 δ (the energy
//     bound of the released undamped oscillator; the scheme only dissipates) and h (|F| + M g)/M
//     (one step of free fall, for h ω0 = 3.2 when k × 1e6, where the step no longer resolves
//     the oscillation): 1.4e-2 m/s for k × 1e4, 4.4e-3 m/s for k × 1e6;
//   * the static answer is reached: the springs carry |F| + (M + 5 m_pad) g, the pads have gone
//     down by δ = (|F| + (M + 5 m_pad) g)/(5 k) (8.75e-6 m and 8.75e-8 m) on average, and all is
//     at rest (each pad by δ exactly when the contacts keep no overlap: see below).
// The mass ratio sleeper/pad is 8.1e4, and each pad is held by a link of its own Delassus
// scalar w = 1/m_pad with h b w = 820 and 82,000: the NLGS contraction per sweep on the chain
// sleeper–contact–pad–link is about M/(M + m_pad) × h b w/(1 + h b w), 1 − 1.2e-3 and
// 1 − 2.4e-5. With k × 1e4 the solver still converges at every step (a few hundred sweeps); with
// k × 1e6 the first ~50 steps of the impact stop at max_sweeps, the sleeper sinks into the pads
// by a few 1e-7 m there, and IQS_CLB, which never pushes an overlap out, keeps it. Its
// deflection is then δ plus the mean overlap (3.1e-7 m, 3.6 δ), bounded here by 1e-6 m (1e-3 of
// the alert distance); the unequal overlaps also share the load slightly unequally between
// the stiff springs (pads within 2.4e-5 δ of each other).
struct StiffCase {
  double factor;
  double tol;
  bool converges_from_the_start;
};

class SublayerStiffness : public ::testing::TestWithParam<StiffCase> {};

TEST_P(SublayerStiffness, StiffSpringsUnderLightPadsStayBoundedAndSettle) {
  const StiffCase c = GetParam();
  const double k = kK * c.factor;
  const double pad_mass = 1e-3;
  SublayerScene s = on_pads(0.5, k, pad_mass);
  const double h = s.reg.params.dt;
  ASSERT_GE(h * std::sqrt(k / pad_mass), 40.0 - 1e-9);  // 20 × the explicit limit, or more
  const double M = s.reg.bodies.mass[s.sleeper.index()];
  const double deflection = s.load / (kSprings * k);
  const double y0 = s.reg.bodies.y[s.sleeper.index()];
  constexpr int kSteps = 10000;
  const History r = run(s, kSteps, tight_options(c.tol));
  for (double y : r.y) ASSERT_TRUE(std::isfinite(y));

  const Oscillator o = oscillator(k, s.moving_mass);
  const double speed_bound = std::max(o.omega0 * deflection, h * s.load / M);
  std::printf("[ k x %.0e ] max speed %.3e m/s (bound %.3e), sleeper deflection %.6e m, expected %.6e m, "
              "overlap %.3e m, %d unconverged steps\n",
              c.factor, r.max_speed, speed_bound, y0 - r.y.back(), deflection, r.last.max_overlap, r.unconverged);
  EXPECT_LT(r.max_speed, speed_bound);
  EXPECT_LT(r.late_max_speed, 1e-8);  // at rest over the last 1,000 steps
  EXPECT_LT(rel_err(spring_force_sum(s.reg), s.load), 1e-7);
  // Pads and sleeper at rest: pad i is compressed by c_i with Σ k c_i = Σ R_N = load, so the
  // pads' mean deflection is δ; the sleeper sits on each pad with overlap o_i = −g_i, so its
  // deflection is c_i + o_i for every i, i.e. δ + mean(o).
  double mean_pad = 0.0;
  for (BodyId p : s.pads) mean_pad += (s.reg.bodies.y0[p.index()] - s.reg.bodies.y[p.index()]) / kSprings;
  double mean_overlap = 0.0;
  for (double g : s.reg.contacts.gap) mean_overlap -= g / static_cast<double>(s.reg.contacts.size());
  EXPECT_LT(rel_err(mean_pad, deflection), 1e-6);
  EXPECT_LT(rel_err(y0 - r.y.back(), deflection + mean_overlap), 1e-6);
  // The solver converges at every step once the impact is over.
  EXPECT_LT(r.last_unconverged, 100);
  EXPECT_EQ(r.last.contacts, 10u);
  if (c.converges_from_the_start) {
    EXPECT_EQ(r.unconverged, 0);
    EXPECT_LT(rel_err(y0 - r.y.back(), deflection), 1e-6);
    for (BodyId p : s.pads)
      EXPECT_LT(rel_err(s.reg.bodies.y0[p.index()] - s.reg.bodies.y[p.index()], deflection), 1e-6);
  } else {
    // the overlap left from the impact stays far below the alert distance
    EXPECT_LT(r.last.max_overlap, 1e-6);
  }
  std::printf("[ k x %.0e ] mean pad deflection %.9e m, mean overlap %.3e m\n", c.factor, mean_pad, mean_overlap);
}

INSTANTIATE_TEST_SUITE_P(Sublayer, SublayerStiffness,
                         ::testing::Values(StiffCase{1e4, 1e-11, true}, StiffCase{1e6, 1e-12, false}),
                         [](const ::testing::TestParamInfo<StiffCase>& i) {
                           return i.param.factor == 1e4 ? std::string("k_times_1e4") : std::string("k_times_1e6");
                         });

}  // namespace
