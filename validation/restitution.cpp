// validation/restitution.cpp — Newton restitution (RST_CLB) of a box on a fixed floor.
//
// RST_CLB imposes Signorini on the weighted mean (U⁺ + e_n U⁻)/(1 + e_n) of an impacting
// contact (paper §2.8): U⁺_N + e_n U⁻_N >= 0, P_N >= 0, complementary. A box hitting the
// floor flat (two contact points, the ends of its bottom face, symmetric: no rotation) at
// speed v therefore leaves at exactly e_n v.
//
// Suite: Restitution
//   * Touching: bottom face on y = 0 (gap 0), velocity −v0, no gravity. After one step
//     u_y = +e v0 (to the solver's tolerance), for e = 0 (no bounce), 0.5 and 1 (the rebound
//     speed is conserved), for θ = 0.5 and 1.
//   * Bounces: dropped from rest at a height H_0 with gravity; the apex heights satisfy
//     H_{k+1} = e² H_k for an exact impact (the rebound speed e v_k, v_k = √(2 g H_k), rises to
//     (e v_k)²/(2g) = e² H_k). The time-stepping error bound is derived above BouncesDecayByESquared.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "validation_support.hpp"

namespace {

using namespace nscd;
using nscd::validation::add_block;
using nscd::validation::add_floor;
using nscd::validation::rel_err;
using nscd::validation::tight_options;

constexpr double kW = 0.2, kH = 0.1;

struct BoxOnFloor {
  Registry reg;
  BodyId floor, box;
};

BoxOnFloor make_scene(double e_n, double theta, double dt, Vec2 gravity, double bottom) {
  BoxOnFloor s;
  s.reg.params.dt = dt;
  s.reg.params.theta = theta;
  s.reg.params.gravity = gravity;
  const MaterialId m = add_material(s.reg, "rubber", 1100.0);
  LawSpec law{LawKind::RST_CLB, 0.3};
  law.e_n = e_n;
  set_default_contact_law(s.reg, law);
  s.floor = add_floor(s.reg, m);
  s.box = add_block(s.reg, m, kW, kH, 0.0, bottom);
  return s;
}

// Touching at gap 0 with u⁻ = −v0, no gravity: in the first step q_m overlaps the floor by
// (1−θ) h v0, the start-of-step gap is 0 (closed), so the law is U⁺ + e U⁻ >= 0 with
// U⁻ = −v0 and the free velocity U_free = −v0 < e v0: the contact is active and U⁺ = e v0.
// Afterwards the box flies off at e v0 (no gravity), the contact opens and stays open.
TEST(Restitution, TouchingBoxLeavesWithEV0AfterOneStep) {
  constexpr double v0 = 1.5;
  for (const double theta : {0.5, 1.0}) {
    for (const double e : {0.0, 0.5, 1.0}) {
      BoxOnFloor s = make_scene(e, theta, 1e-3, {0.0, 0.0}, 0.0);
      const std::size_t i = s.box.index();
      s.reg.bodies.vy[i] = -v0;
      MoreauJean mj(s.reg, tight_options());
      const StepReport r = mj.step();
      ASSERT_EQ(r.contacts, 2u);
      ASSERT_TRUE(r.converged);
      const double err = std::abs(s.reg.bodies.vy[i] - e * v0) / v0;
      EXPECT_LT(err, 1e-10) << "e " << e << " theta " << theta << ": u_y " << s.reg.bodies.vy[i];
      EXPECT_LT(std::abs(s.reg.bodies.vx[i]), 1e-12);
      EXPECT_LT(std::abs(s.reg.bodies.spin[i]), 1e-10);
      // the floor's impulse: m (e v0 + v0) over the step, i.e. Σ R_N = m (1 + e) v0 / h
      double rn = 0.0;
      for (double f : s.reg.contacts.rn) rn += f;
      const double mass = s.reg.bodies.mass[i];
      EXPECT_LT(rel_err(rn, mass * (1.0 + e) * v0 / s.reg.params.dt), 1e-10) << "e " << e;
      std::printf("[ measured ] restitution touching theta=%.2f e=%.2f: |u_y - e v0|/v0 = %.3e\n", theta, e, err);
      // then it keeps e v0 (free flight) and, for e > 0, separates
      for (int n = 0; n < 100; ++n) mj.step();
      EXPECT_LT(std::abs(s.reg.bodies.vy[i] - e * v0) / v0, 1e-10) << "e " << e;
      if (e > 0.0) {
        EXPECT_EQ(s.reg.contacts.size(), 0u) << "e " << e << ": the box should have left the floor";
      }
    }
  }
}

// Dropped from rest with its bottom face at H_0 = 0.2 m, g = 9.81, h = 1e-4, θ ∈ {0.5, 0.75, 1}.
// Error bound for one bounce, from the step size. The impact happens within the step where the
// contact is found closing: the box turns round somewhere in that step, at most one step's
// travel |v| h above the floor (it does not go down to y = 0), and its start-of-step velocity
// U⁻ differs from the true impact speed by at most g h (gravity during one step). Its rebound
// speed e|U⁻| thus differs from e v by <= e g h, its rebound height by <= |v| h, and
//     |H_{k+1} − e² H_k| <= |v| h + e² (2 v g h)/(2 g) = (1 + e²) v_k h.
// For θ ≠ 1/2 the free flight itself is off the parabola by h² g (θ − 1/2) per step, i.e. by
// (θ − 1/2) g h t over a time t: (θ − 1/2) v_k h for the fall (t = v_k/g) and (θ − 1/2) e v_k h
// for the rise. The apex is sampled at discrete steps (<= g h²/2). Asserted:
//     |H_{k+1} − e² H_k| <= (1 + e² + (θ − 1/2)(1 + e)) v_k h + g h²,   v_k = √(2 g H_k)
// (θ = 1/2, e = 0.5, H = 0.2 m: 2.5e-4 m, 0.5 % of H_1 = 0.05 m). A law that stops the box
// at the floor and restitutes the left-over speed instead misses by O(1).
TEST(Restitution, BouncesDecayByESquared) {
  constexpr double H0 = 0.2, g = 9.81, h = 1e-4;
  for (const double theta : {0.5, 0.75, 1.0}) {
    for (const double e : {0.5, 0.8}) {
      BoxOnFloor s = make_scene(e, theta, h, {0.0, -g}, H0);
      const std::size_t i = s.box.index();
      MoreauJean mj(s.reg, tight_options());
      std::vector<double> apex{H0};
      double high = -1.0;
      bool rising = false;
      // three bounces: flight times 2 e^k √(2 H0/g) sum to < 1.6 s; 2 s = 20,000 steps
      for (int n = 0; n < 20000 && apex.size() < 4; ++n) {
        mj.step();
        const double bottom = s.reg.bodies.y[i] - 0.5 * kH, vy = s.reg.bodies.vy[i];
        if (vy > 0.0) rising = true;
        if (rising) high = std::max(high, bottom);
        if (rising && vy <= 0.0) {  // past the apex
          apex.push_back(high);
          rising = false;
          high = -1.0;
        }
      }
      ASSERT_EQ(apex.size(), 4u) << "e " << e << ": expected three bounces";
      for (std::size_t k = 0; k + 1 < apex.size(); ++k) {
        const double v = std::sqrt(2.0 * g * apex[k]);
        const double bound = (1.0 + e * e + (theta - 0.5) * (1.0 + e)) * v * h + g * h * h;
        const double miss = std::abs(apex[k + 1] - e * e * apex[k]);
        std::printf("[ measured ] restitution theta=%.2f e=%.2f bounce %zu: H=%.6f -> %.6f, ratio %.5f (e^2 %.5f), "
                    "|miss| %.2e m (bound %.2e)\n",
                    theta, e, k + 1, apex[k], apex[k + 1], apex[k + 1] / apex[k], e * e, miss, bound);
        EXPECT_LE(miss, bound) << "theta " << theta << ", e " << e << ", bounce " << k + 1 << ": H " << apex[k]
                               << " -> " << apex[k + 1];
      }
    }
  }
}

// e = 1 from a height: every rebound leaves at the speed it arrived with, so the apex stays
// H_0 bounce after bounce, within the bound above (2 v h per bounce for e = 1, θ = 1/2,
// added up over the bounces; measured: 1e-14 m, θ = 1/2 with e = 1 is time-reversible); e = 0: the box lands and stays (no
// bounce at all, the velocity never turns upward after the first contact).
TEST(Restitution, PerfectAndPlasticImpactsFromAHeight) {
  constexpr double H0 = 0.1, g = 9.81, h = 1e-4;
  {
    BoxOnFloor s = make_scene(1.0, 0.5, h, {0.0, -g}, H0);
    const std::size_t i = s.box.index();
    MoreauJean mj(s.reg, tight_options());
    double high = -1.0;
    int apexes = 0;
    bool rising = false;
    for (int n = 0; n < 6000; ++n) {  // 0.6 s: the period is 2√(2 H0/g) = 0.286 s
      mj.step();
      const double bottom = s.reg.bodies.y[i] - 0.5 * kH, vy = s.reg.bodies.vy[i];
      if (vy > 0.0) rising = true;
      if (rising) high = std::max(high, bottom);
      if (rising && vy <= 0.0) {
        ++apexes;
        const double bound = 2.0 * std::sqrt(2.0 * g * H0) * h * apexes;
        std::printf("[ measured ] restitution e=1 apex %d: %.6f (H0 %.6f, |miss| %.2e, bound %.2e)\n", apexes, high, H0,
                    std::abs(high - H0), bound);
        EXPECT_LE(std::abs(high - H0), bound) << "apex " << apexes;
        rising = false;
        high = -1.0;
      }
    }
    EXPECT_EQ(apexes, 2);
  }
  {
    BoxOnFloor s = make_scene(0.0, 0.5, h, {0.0, -g}, H0);
    const std::size_t i = s.box.index();
    MoreauJean mj(s.reg, tight_options());
    bool touched = false;
    for (int n = 0; n < 3000; ++n) {
      mj.step();
      if (!s.reg.contacts.empty()) touched = true;
      if (touched) {
        ASSERT_LE(s.reg.bodies.vy[i], 1e-9) << "e = 0 must not bounce, step " << n;
      }
    }
    EXPECT_TRUE(touched);
    EXPECT_LT(std::abs(s.reg.bodies.vy[i]), 1e-9);         // at rest at the end
    EXPECT_LT(std::abs(s.reg.bodies.y[i] - 0.5 * kH), 1e-4);  // on the floor (within g h² scales)
  }
}

}  // namespace
