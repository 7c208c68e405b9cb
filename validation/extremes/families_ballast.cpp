// validation/extremes/families_ballast.cpp — families on a reduced loaded ballast sample
// (shared/ballast.hpp: box 0.2 m, 14 graded pentagons, 10 pads on VOIGT_ROD springs, the
// sleeper with its bars) and at rest for 10^5 steps:
//   * the sublayer's stiffness k × 1 … × 10⁶ and k × 0.5 … × 10⁻² under a static load (paper
//     §2.9, §4.1–4.2);
//   * the step length 10⁻⁶ … 5·10⁻² s under the paper's cyclic load (paper §4.1);
//   * bodies at rest for 10⁵ steps (a stack of blocks, the ballast sample under its sleeper).
// The sample is deposited and its sleeper settled once per process (NLGS, h = 2e-4 s); every
// run starts from a copy of it.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "extremes.hpp"
#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/interactions/ptpt2.hpp"
#include "nscd/shared/ballast.hpp"

namespace nscd::extremes {
namespace {

constexpr double kMean = -1000.0;      // A (N/m): the paper's mean load (§4.1)
constexpr double kAmplitude = -500.0;  // B (N/m)
constexpr double kFrequency = 20.0;    // f (Hz)
constexpr double kPhase = -3.14159265358979323846;

scenes::BallastOptions reduced_options() {
  scenes::BallastOptions o;
  o.box_width = 0.2;
  o.grading_fraction = 0.02;  // round(0.02 × 361, 242, 121) = 7, 5, 2 grains of 1, 1.5, 2 cm
  o.pads = 10;                // the paper's 50 pads per metre
  return o;
}

// Steps until the bodies' rms speed stays below 1e-3 m/s for 0.05 s, or t_max.
void settle(Registry& reg, const std::vector<BodyId>& bodies, double t_max) {
  StepperOptions opt = setting(SolverKind::NLGS);
  opt.residual_check_every = 0;
  MoreauJean mj(reg, opt);
  const double t0 = reg.time;
  int calm = 0;
  while (reg.time - t0 < t_max && calm < 250) {
    mj.step();
    double s2 = 0.0;
    for (BodyId b : bodies) s2 += reg.bodies.vx[b.index()] * reg.bodies.vx[b.index()] + reg.bodies.vy[b.index()] * reg.bodies.vy[b.index()];
    calm = (reg.time - t0 > 0.05 && std::sqrt(s2 / static_cast<double>(bodies.size())) < 1e-3) ? calm + 1 : 0;
  }
}

// The reduced sample, deposited and with its sleeper settled (no load), prepared once.
const scenes::BallastScene& prepared() {
  static const scenes::BallastScene sample = [] {
    const scenes::BallastOptions o = reduced_options();
    scenes::BallastScene b = scenes::ballast_sample(o);
    Registry& reg = b.scene.reg;
    reg.params.dt = 2e-4;
    settle(reg, b.scene.grains, 1.0);
    scenes::place_sleeper(b, o);
    std::vector<BodyId> moving = b.scene.grains;
    moving.push_back(b.sleeper);
    settle(reg, moving, 0.6);
    return b;
  }();
  return sample;
}

// The springs' elastic compression forces k (L0 (1 + ε0) − L), summed, and their energy.
double spring_force(const Registry& reg) {
  double sum = 0.0;
  for (std::uint32_t l = 0; l < reg.links.size(); ++l) {
    const VoigtRod& law = reg.links.law[l];
    sum += law.k * (law.L0 * (1.0 + law.eps0) - link_frame(reg, LinkId(l), reg.bodies.x, reg.bodies.y, reg.bodies.angle).length);
  }
  return sum;
}
double spring_energy(const Registry& reg) {
  double e = 0.0;
  for (std::uint32_t l = 0; l < reg.links.size(); ++l) {
    const VoigtRod& law = reg.links.law[l];
    const double s = link_frame(reg, LinkId(l), reg.bodies.x, reg.bodies.y, reg.bodies.angle).length - law.L0 * (1.0 + law.eps0);
    e += 0.5 * law.k * s * s;
  }
  return e;
}
double mean_y(const Registry& reg, const std::vector<BodyId>& bodies) {
  double s = 0.0;
  for (BodyId b : bodies) s += reg.bodies.y[b.index()];
  return s / static_cast<double>(bodies.size());
}
// The weight the springs carry at rest: every body that moves vertically (N/m).
double weight(const Registry& reg) {
  double w = 0.0;
  for (BodyId b : all_dynamic(reg)) w += reg.bodies.mass[b.index()] * -reg.params.gravity.y;
  return w;
}
// Below the pads: a grain whose centre lies below the lowest pad's top face has passed through
// or between the pads (a resting grain's centre is at least 0.4 d = 4 mm above what carries
// it); `deepest` is how far the lowest grain vertex lies below that face (a vertex may dip
// into the 2 mm gaps between pads, or beside the edge pads, without anything wrong).
struct BelowPads {
  int centres = 0;
  double deepest = 0.0;
};
BelowPads below_pads(const Registry& reg, const std::vector<BodyId>& grains, const std::vector<BodyId>& pads, double pad_height) {
  double pad_top = kNone;
  for (BodyId p : pads) pad_top = std::min(pad_top, reg.bodies.y[p.index()] + 0.5 * pad_height);
  BelowPads out;
  for (BodyId g : grains) {
    if (reg.bodies.y[g.index()] < pad_top) ++out.centres;
    for (std::uint32_t k = 0; k < reg.polyg.size(); ++k)
      if (reg.polyg.body[k] == g)
        for (const Vec2& v : world_polygon(reg, PolygId(k))) out.deepest = std::max(out.deepest, pad_top - v.y);
  }
  return out;
}
std::string below_pads_text(const BelowPads& b) {
  return (b.centres > 0 ? std::to_string(b.centres) + " grains through the pads, " : std::string()) + "lowest vertex " +
         g3(b.deepest) + " m below the lowest pad top";
}

}  // namespace

// The reduced sample under a static load F = −1000 N/m on its sleeper, springs k × factor
// (scale_sublayer_stiffness keeps their forces, so nothing jumps), 1 s at h = 2e-4 s. stiff:
// k × 1 … 10⁶; soft: k × 1 … 10⁻², where the springs squeezed to zero length carry less than
// the load and the scene is refused (as the ballast driver refuses such a load).
Family sublayer_family(bool stiff) {
  Family f;
  f.name = std::string(stiff ? "stiff" : "soft") + " sublayer under a loaded sleeper (14 grains, 10 pads), k x";
  f.holds = "static F = -1000 N/m, frictionless walls, 1 s at h = 2e-4: no NaN, overlap <= 0.5 mm, no grain centre below the lowest pad top, none out of the walls, pads' mean "
            "deflection <= 2x static (+1 um) and within 2 % (+1 nm) of the static (F + W - R0)/(n k) (F, W: the load and the weight, in magnitude) at the end, no energy "
            "created (0.1 % of F x static deflection)";
  const std::vector<double> factors = stiff ? std::vector<double>{1.0, 1e2, 1e4, 1e6} : std::vector<double>{1.0, 0.5, 0.3, 0.1, 0.01};
  for (double factor : factors) {
    if (!stiff && factor == 1.0) continue;  // in the stiff family
    Point p;
    p.value = "k x " + g3(factor);
    p.quick = factor == 1e-2 || factor == 1e4;
    p.must_hold = factor == 1.0;
    p.build = [=] {
      scenes::BallastScene b = prepared();
      scenes::scale_sublayer_stiffness(b, factor);
      Registry& reg = b.scene.reg;
      const scenes::BallastOptions o = reduced_options();
      const double n = static_cast<double>(b.springs.size()), k = reg.links.law[0].k;
      const double load = -kMean + weight(reg), capacity = n * k * o.spring_length;
      Scenario s;
      if (!(load <= capacity))
        s.refused = "the load |F| + W = " + g3(load) + " N/m exceeds what the sublayer can carry (n k L0 = " + g3(capacity) +
                    " N/m, the springs squeezed to zero length)";
      // frictionless walls: the springs alone carry the load (no silo effect)
      for (MaterialId m : {b.scene.grain_material, b.sleeper_material, b.pad_material})
        set_contact_law(reg, b.scene.wall_material, m, LawSpec{LawKind::IQS_CLB, 0.0, 0.0, 0.0});
      impose_force(reg, b.sleeper, Dof::Y, TimeFunction::constant(kMean));
      const double delta = (load - spring_force(reg)) / (n * k);
      const double pad_y0 = mean_y(reg, b.pads);
      const BodyId sleeper = b.sleeper;
      const std::vector<BodyId> pads = b.pads, grains = b.scene.grains;
      s.watched = b.scene.grains;
      s.watched.push_back(sleeper);
      s.steps = 5000;
      s.expect.max_overlap = 5e-4;
      s.expect.no_tunnelling = true;
      s.expect.x_left = 0.0;
      s.expect.x_right = o.box_width;
      s.energy = [sleeper](const Registry& r) { return total_energy(r) + spring_energy(r) + kMean * -r.bodies.y[sleeper.index()]; };
      s.expect.energy_slack = 1e-3 * -kMean * std::abs(delta);
      auto seen = std::make_shared<std::pair<double, double>>(0.0, 0.0);  // deepest, last
      auto below = std::make_shared<BelowPads>();
      auto spread = std::make_shared<std::pair<double, double>>(kNone, -kNone);  // pads' least and most deflection at the end
      std::vector<double> pad_start;
      for (BodyId p : b.pads) pad_start.push_back(reg.bodies.y[p.index()]);
      s.check = [=](const Registry& r, bool last) -> std::string {
        const double d = pad_y0 - mean_y(r, pads);
        seen->first = std::max(seen->first, d);
        seen->second = d;
        if (!last) return "";
        std::string failed;
        if (!(seen->first <= 2.0 * delta + 1e-6)) failed = "deflection reached " + g3(seen->first) + " m > 2 x static " + g3(delta);
        else if (!(std::abs(d - delta) <= 0.02 * delta + 1e-9))
          failed = "deflection " + g3(d) + " m, static " + g3(delta) + " m";
        *below = below_pads(r, grains, pads, o.pad_height);
        if (below->centres > 0) failed += (failed.empty() ? "" : ", ") + std::to_string(below->centres) + " grains through the pads";
        for (std::size_t i = 0; i < pads.size(); ++i) {
          const double di = pad_start[i] - r.bodies.y[pads[i].index()];
          spread->first = std::min(spread->first, di);
          spread->second = std::max(spread->second, di);
        }
        return failed;
      };
      const bool refused = !s.refused.empty();
      s.note = [=] {
        if (refused) return "static deflection " + g3(delta) + " m, spring length " + g3(o.spring_length) + " m";
        return "deflection " + g3(seen->second) + " m (static " + g3(delta) + " m, deepest " + g3(seen->first) + " m, pads " +
               g3(spread->first) + " ... " + g3(spread->second) + " m), " + below_pads_text(*below);
      };
      s.reg = std::move(reg);
      return s;
    };
    f.points.push_back(p);
  }
  return f;
}

// The reduced sample under the paper's load F = A + B cos(2π f t − φ) (1-cycle ramp), over
// 0.1 s (two cycles) or 10,000 steps, whichever is shorter, at step h.
Family ballast_step_family(bool full) {
  Family f;
  f.name = "loaded ballast sample (14 grains, 10 pads), step h";
  f.holds = "F = -1000 - 500 cos(2 pi 20 t + pi) N/m, 0.1 s or 10^4 steps: no NaN, overlap <= 0.5 mm (5 % of d_min), no grain "
            "centre below the lowest pad top, none out of the walls, sleeper within 2 mm above and 2 (A + B)/(n k) + 5 mm (A, B in magnitude) below its start";
  std::vector<double> steps{1e-4, 2e-4, 1e-3, 2e-3, 5e-3, 1e-2, 2e-2, 5e-2};
  if (full) steps.insert(steps.begin(), {1e-6, 1e-5});
  for (double h : steps) {
    Point p;
    p.value = "h " + g3(h);
    p.quick = h == 1e-3;
    p.must_hold = h == 2e-4;
    p.build = [=] {
      scenes::BallastScene b = prepared();
      Registry& reg = b.scene.reg;
      reg.params.dt = h;
      const scenes::BallastOptions o = reduced_options();
      const double n = static_cast<double>(b.springs.size()), k = reg.links.law[0].k;
      impose_force(reg, b.sleeper, Dof::Y, TimeFunction::cosine(kMean, kAmplitude, kFrequency, kPhase, 1.0 / kFrequency, reg.time));
      const double down = 2.0 * (std::abs(kMean) + std::abs(kAmplitude)) / (n * k) + 5e-3, up = 2e-3;
      const double y0 = reg.bodies.y[b.sleeper.index()];
      const BodyId sleeper = b.sleeper;
      const std::vector<BodyId> pads = b.pads, grains = b.scene.grains;
      Scenario s;
      s.watched = b.scene.grains;
      s.watched.push_back(sleeper);
      s.steps = std::min<std::int64_t>(std::llround(0.1 / h), 10000);
      s.expect.max_overlap = 5e-4;
      s.expect.no_tunnelling = true;
      s.expect.x_left = 0.0;
      s.expect.x_right = o.box_width;
      auto range = std::make_shared<std::pair<double, double>>(0.0, 0.0);  // lowest, highest displacement
      auto below = std::make_shared<BelowPads>();
      s.check = [=](const Registry& r, bool last) -> std::string {
        const double d = r.bodies.y[sleeper.index()] - y0;
        range->first = std::min(range->first, d);
        range->second = std::max(range->second, d);
        if (!last) return "";
        std::string failed;
        if (!(range->first >= -down && range->second <= up))
          failed = "sleeper moved " + g3(range->first) + " ... +" + g3(range->second) + " m";
        *below = below_pads(r, grains, pads, o.pad_height);
        if (below->centres > 0) failed += (failed.empty() ? "" : ", ") + std::to_string(below->centres) + " grains through the pads";
        return failed;
      };
      s.note = [=] { return "sleeper moved " + g3(range->first) + " ... +" + g3(range->second) + " m, " + below_pads_text(*below); };
      s.reg = std::move(reg);
      return s;
    };
    f.points.push_back(p);
  }
  return f;
}

// Bodies at rest for 10^5 steps: a stack of 10 blocks 0.2 × 0.1 m (h = 1e-3 s, 100 s) and the
// reduced ballast sample under its sleeper, no load (h = 2e-4 s, 20 s).
Family rest_family() {
  Family f;
  f.name = "at rest for 1e5 steps";
  f.holds = "no NaN, drift <= 0.1 mm, overlap <= 0.1 mm (stack) or 0.5 mm (sample), no energy created (1e-6 of E in magnitude)";
  for (int which : {0, 1}) {
    Point p;
    p.value = which == 0 ? "stack of 10, h 1e-3" : "ballast sample, h 2e-4";
    p.quick = false;
    p.build = [=] {
      Scenario s;
      s.steps = 100000;
      if (which == 0) {
        s.reg = base_registry(1e-3);
        s.watched = add_stack(s.reg, 10, 1.0, true);
        s.expect.max_overlap = 1e-4;
      } else {
        scenes::BallastScene b = prepared();
        s.watched = b.scene.grains;
        s.watched.push_back(b.sleeper);
        s.reg = std::move(b.scene.reg);
        s.expect.max_overlap = 5e-4;
        s.energy = [](const Registry& r) { return total_energy(r) + spring_energy(r); };
      }
      s.expect.max_drift = 1e-4;
      s.expect.energy_slack = 1e-6 * std::abs(s.energy ? s.energy(s.reg) : total_energy(s.reg));
      return s;
    };
    f.points.push_back(p);
  }
  return f;
}

}  // namespace nscd::extremes
