// tests/support/compressed_field.hpp — a field of n pentagons squeezed towards its centre,
// without gravity: many pressed contacts, a few hundred sweeps a step (the colored-sweep tests').
#pragma once

#include <cstddef>

#include "nscd/shared/samples.hpp"

namespace nscd::testing_support {

inline scenes::Scene compressed_field(std::size_t n) {
  scenes::Scene s = scenes::pentagon_field(n, 0.01, 0.009);
  s.reg.params.gravity = {0.0, 0.0};
  scenes::converge_to_centroid(s.reg, 0.1);
  return s;
}

}  // namespace nscd::testing_support
