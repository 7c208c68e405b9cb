// validation/extremes/runner.cpp — runs one scenario and judges it (extremes.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "extremes.hpp"
#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"

namespace nscd::extremes {

const char* name_of(Verdict v) {
  switch (v) {
    case Verdict::Holds: return "holds";
    case Verdict::Warned: return "warned";
    case Verdict::Reported: return "reported";
    case Verdict::Silent: return "SILENT";
  }
  return "?";
}

StepperOptions setting(SolverKind solver) {
  StepperOptions o;
  o.solver = solver;
  o.nlgs.policy = ConvergencePolicy::QM16;
  o.nlgs.tol = 1.666e-4;
  o.nlgs.max_sweeps = 1000;
  o.newton.tol = 1e-8;
  o.newton.max_iterations = 500;
  o.residual_check_every = 1;
  o.residual_flag = 1e-3;
  return o;
}

std::string g3(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

namespace {

// Lowest vertex and horizontal extent of a body's polygons.
struct Extent {
  double ymin = kNone, xmin = kNone, xmax = -kNone;
};
Extent extent_of(const Registry& reg, BodyId b) {
  Extent e;
  for (std::uint32_t p = 0; p < reg.polyg.size(); ++p) {
    if (reg.polyg.body[p] != b) continue;
    for (const Vec2& v : world_polygon(reg, PolygId(p))) {
      e.ymin = std::min(e.ymin, v.y);
      e.xmin = std::min(e.xmin, v.x);
      e.xmax = std::max(e.xmax, v.x);
    }
  }
  return e;
}

}  // namespace

Outcome run(Scenario s, const StepperOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  Outcome o;
  Registry& reg = s.reg;
  const Expect& x = s.expect;
  std::vector<double> x0, y0;
  for (BodyId b : s.watched) {
    x0.push_back(reg.bodies.x[b.index()]);
    y0.push_back(reg.bodies.y[b.index()]);
  }
  const auto energy = [&] { return s.energy ? s.energy(reg) : total_energy(reg); };
  const double e0 = energy();
  std::string own;  // the family's own check: its first failure
  const auto check = [&](bool last) {
    if (!s.check) return;
    const std::string f = s.check(reg, last);
    if (own.empty()) own = f;
  };
  const auto finite = [&] {
    const BodyTable& b = reg.bodies;
    for (std::size_t i = 0; i < b.size(); ++i)
      if (!std::isfinite(b.x[i]) || !std::isfinite(b.y[i]) || !std::isfinite(b.angle[i]) || !std::isfinite(b.vx[i]) ||
          !std::isfinite(b.vy[i]) || !std::isfinite(b.spin[i]))
        return false;
    return true;
  };
  o.refused = s.refused;
  if (o.refused.empty()) try {
    MoreauJean mj(reg, options);
    for (std::int64_t n = 0; n < s.steps; ++n) {
      const StepReport r = mj.step();
      if (!finite()) o.non_finite = true;
      ++o.steps;
      o.unconverged += r.converged ? 0 : 1;
      o.false_converged += r.false_converged ? 1 : 0;
      o.alert_skips += r.alert_skips > 0 ? 1 : 0;
      o.coarse += r.coarse_positions ? 1 : 0;
      o.max_overlap = std::max(o.max_overlap, r.max_overlap);
      if (r.residual_checked) o.max_residual = std::max(o.max_residual, r.residual);
      if (x.max_drift < kNone)
        for (std::size_t k = 0; k < s.watched.size(); ++k) {
          const std::size_t i = s.watched[k].index();
          o.max_drift = std::max(o.max_drift, std::hypot(reg.bodies.x[i] - x0[k], reg.bodies.y[i] - y0[k]));
        }
      if (x.energy_slack < kNone) o.energy_gain = std::max(o.energy_gain, energy() - e0);
      check(n + 1 == s.steps || o.non_finite);
      if (o.non_finite) break;  // nothing after a NaN means anything
    }
  } catch (const Error& e) {
    o.refused = e.what();
    check(true);
  }
  std::string failed;
  const auto fail = [&](const std::string& what) { failed += (failed.empty() ? "" : ", ") + what; };
  if (!o.refused.empty()) fail(s.refused.empty() ? "step refused" : "scene refused");
  if (o.non_finite) fail("NaN or infinite positions or velocities");
  if (!own.empty()) fail(own);
  if (!(o.max_overlap <= x.max_overlap)) fail("overlap " + g3(o.max_overlap) + " m > " + g3(x.max_overlap));
  if (!(o.max_drift <= x.max_drift)) fail("drift " + g3(o.max_drift) + " m > " + g3(x.max_drift));
  if (!(o.energy_gain <= x.energy_slack)) fail("energy created " + g3(o.energy_gain) + " J/m");
  if (x.no_tunnelling && o.refused.empty()) {
    int out = 0;
    for (BodyId b : s.watched) {
      const Extent e = extent_of(reg, b);
      const double tol = std::min(x.max_overlap, 1e-2);
      if (!(e.ymin >= x.floor_y - tol && e.xmin >= x.x_left - tol && e.xmax <= x.x_right + tol)) ++out;
    }
    if (out > 0) fail(std::to_string(out) + " bodies through the floor or walls");
  }
  o.failed = failed;
  if (s.note) o.note = s.note();
  const bool reported =
      !o.refused.empty() || o.unconverged > 0 || o.false_converged > 0 || o.alert_skips > 0 || o.coarse > 0;
  o.verdict = failed.empty() ? (reported ? Verdict::Warned : Verdict::Holds) : (reported ? Verdict::Reported : Verdict::Silent);
  o.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return o;
}

}  // namespace nscd::extremes
