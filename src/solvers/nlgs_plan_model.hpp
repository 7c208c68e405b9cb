// nscd/solvers/nlgs_plan_model.hpp — what a planned sweep (nlgs_plan.hpp) allows its threads,
// on a model: for a thread count no machine at hand has.
//
// Each share sweeps its steps on a clock of its own, a bundle a unit (half a unit where lanes
// 4–7 are idle: the AVX2 sweep skips them and costs about half), share 0's tail `tail` units, and
// waits at its stops as sweep_planned does, until the share it waits for has published the step
// it needs. The model leaves out what the plan does not decide: the cache lines that cross
// between cores (but for a `latency` at each wait not met when reached), the checked sweeps' and
// the mixings' barriers, and the step around the solve.
#pragma once

#include <vector>

#include "nscd/solvers/nlgs_plan.hpp"

namespace nscd {

struct PlanModel {
  std::vector<double> work;  ///< each share's units a sweep (its bundles, share 0's tail)
  double total = 0.0;  ///< every share's units a sweep
  double sweep = 0.0;  ///< a sweep's time in units, over the last half of the sweeps modelled
  double waits = 0.0;  ///< waits not met when reached, a sweep, every share's
  double idle = 0.0;  ///< time the shares wait, a sweep, every share's (units)
};

/// `sweeps` (≥ 2) sweeps of `plan` in a row, on the model above. Throws nscd::Error where the
/// shares would wait for each other in a cycle (a plan that deadlocks).
PlanModel model_plan(const LanePlan& plan, double tail = 0.0, int sweeps = 16, double latency = 0.0);

/// Share `s`'s cost of its bundles 0 … b−1 for every b ≤ s.bundles, in units (the model's).
std::vector<double> bundle_costs(const SharePlan& s);

}  // namespace nscd
