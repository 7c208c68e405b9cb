// nscd/core/parameters.cpp — see parameters.hpp.
#include "nscd/core/parameters.hpp"

#include <cmath>
#include <string>

#include "nscd/core/error.hpp"

namespace nscd {

void validate(const Parameters& p) {
  if (!(p.dt > 0.0) || !std::isfinite(p.dt))
    throw Error("time step dt must be finite and > 0, got " + std::to_string(p.dt));
  if (!(p.theta >= 0.5 && p.theta <= 1.0)) throw Error("theta must lie in [0.5, 1], got " + std::to_string(p.theta));
  if (!(p.alert >= 0.0) || !std::isfinite(p.alert))
    throw Error("alert distance must be finite and >= 0, got " + std::to_string(p.alert));
  if (!std::isfinite(p.gravity.x) || !std::isfinite(p.gravity.y)) throw Error("gravity must be finite");
}

}  // namespace nscd
