// examples/scaling/plan_table.hpp — `scaling --plan-model`: what the planned sweep of the step's
// own system allows each thread count, on a model (nscd/solvers/nlgs_plan_model.hpp).
#pragma once

#include <vector>

#include "nscd/solvers/contact_system.hpp"
#include "nscd/solvers/nlgs.hpp"

namespace scaling {

/// One row per count of `counts`: the plan `opt` would sweep `sys` by on that many threads, and
/// its model's sweep against one thread's. Prints to stdout.
void print_plan_table(const nscd::ContactSystem& sys, const nscd::NlgsOptions& opt, const std::vector<int>& counts);

}  // namespace scaling
