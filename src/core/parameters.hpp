// nscd/core/parameters.hpp — the global parameters of a run (time step, θ, gravity, alert).
#pragma once

#include "nscd/core/math.hpp"

namespace nscd {

/// Global parameters of a run. Units: SI (m, kg, s); 2D quantities are per unit thickness
/// (mass in kg/m, inertia in kg·m²/m, forces in N/m) — see docs/theory.md.
struct Parameters {
  double dt = 2e-4;             ///< time step h (s)
  double theta = 0.5;           ///< θ of the θ-method, in [0.5, 1]
  Vec2 gravity{0.0, -9.81};     ///< m/s²
  double alert = 1.25e-3;       ///< alert distance: pairs with gap <= alert are reported (m)
};

/// Throws nscd::Error if dt <= 0, theta outside [0.5, 1], alert < 0 or a non-finite value.
void validate(const Parameters& p);

}  // namespace nscd
