// validation/validation_support.hpp — small helpers shared by the validation cases: scene
// builders (a fixed floor, a rectangular block), a tight NLGS setting, and error measures.
//
// Conventions used by every case:
//   * the floor is a fixed rectangle whose top face is y = 0, wide enough to be classified
//     "big" (antagonist of every contact, normal n = (0, 1), tangent t = perp(n) = (−1, 0));
//   * a block placed "touching" has its bottom face exactly on y = 0 (gap 0);
//   * the solver is run with a tolerance far below the accuracy asserted, so that what is
//     measured is the time-stepping scheme, not the iterative solver.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/core/math.hpp"
#include "nscd/registry/registry.hpp"
#include "nscd/solvers/moreau_jean.hpp"

namespace nscd::validation {

/// Gravity (m/s²) and one degree in radians, for every case (one definition: the cases compile
/// together in a unity build).
inline constexpr double kG = 9.81;
inline constexpr double kDeg = kPi / 180.0;

/// |a − b| / max(|b|, floor): relative error with a floor for expected values near 0.
inline double rel_err(double a, double b, double floor = 1e-300) {
  return std::abs(a - b) / std::max(std::abs(b), floor);
}

/// Stepper options with a solver tolerance far below what the cases assert: the Strict
/// policy bounds every local velocity correction by tol × the mean |W r| of the active
/// contacts, checked after every sweep.
///
/// The executable nscd_validation_newton compiles the same cases with
/// NSCD_VALIDATION_NEWTON defined: the setting is then NEWTON_AC at a natural-map residual of
/// 1e-10 × ‖q‖, so every case checks the stepper with the global solver too. (Not 1e-12: on a
/// hyperstatic pile the rounding of W = H* M⁻¹ H leaves a floor near 1e-12, docs/theory.md.)
inline StepperOptions tight_options(double tol = 1e-12, int max_sweeps = 20000) {
  StepperOptions o;
#ifdef NSCD_VALIDATION_NEWTON
  o.solver = SolverKind::NEWTON_AC;
  o.newton.tol = 1e-10;
  o.newton.max_iterations = 500;
#endif
  o.nlgs.policy = ConvergencePolicy::Strict;
  o.nlgs.tol = tol;
  o.nlgs.check_every = 1;
  o.nlgs.max_sweeps = max_sweeps;
  return o;
}

/// A fixed floor: rectangle `width` × `thickness`, top face on y = 0, centred on x = 0.
inline BodyId add_floor(Registry& reg, MaterialId m, double width = 20.0, double thickness = 1.0) {
  const BodyId floor = add_polygon_body(reg, rectangle(width, thickness), m, {0.0, -0.5 * thickness}, 0.0, "floor");
  fix_body(reg, floor);
  return floor;
}

/// A rectangular block w × h whose bottom face lies on y = bottom, centre at x.
inline BodyId add_block(Registry& reg, MaterialId m, double w, double h, double x, double bottom,
                        const std::string& name = "block") {
  return add_polygon_body(reg, rectangle(w, h), m, {x, bottom + 0.5 * h}, 0.0, name);
}

/// Sum of the contact forces (world frame) that body `antagonist` exerts on the others:
/// R = rn n + rt t per contact point whose antagonist body is `antagonist`.
inline Vec2 reaction_from(const Registry& reg, BodyId antagonist) {
  Vec2 sum;
  const ContactTable& c = reg.contacts;
  for (std::size_t k = 0; k < c.size(); ++k) {
    if (c.an_body[k] != antagonist) continue;
    const Vec2 n = c.normal[k], t = perp(n);
    sum += c.rn[k] * n + c.rt[k] * t;
  }
  return sum;
}

}  // namespace nscd::validation
