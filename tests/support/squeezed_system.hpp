// tests/support/squeezed_system.hpp — a field of pentagons squeezed toward its centre, without
// gravity: the system of its first step, as the solve finds it (detected, prepared, laid out
// for `order`). Many contacts from the first step on, on strips or cells: the colored sweep's
// and its plan's test system.
#pragma once

#include <cstddef>

#include "nscd/shared/samples.hpp"
#include "nscd/solvers/moreau_jean.hpp"

namespace nscd::testing_support {

inline ContactSystem squeezed_system(std::size_t grains, SweepOrder order) {
  scenes::Scene s = scenes::pentagon_field(grains, 0.01, 0.009);
  s.reg.params.gravity = {0.0, 0.0};
  scenes::converge_to_centroid(s.reg, 0.1);
  StepperOptions o;
  o.nlgs.order = order;
  MoreauJean mj(s.reg, o);
  mj.begin_step();
  mj.detect();
  mj.prepare();
  return mj.system();
}

}  // namespace nscd::testing_support
