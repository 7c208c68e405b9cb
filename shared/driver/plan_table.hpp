// nscd/shared/driver/plan_table.hpp — `scaling --plan-model`, `ballast --plan-model`: what the
// planned sweep of a step's own system allows each thread count, on a model
// (nscd/solvers/nlgs_plan_model.hpp), and the thread counts a driver is given.
#pragma once

#include <string>
#include <vector>

#include "nscd/solvers/contact_system.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "nscd/solvers/nlgs.hpp"

namespace nscd::driver {

/// One row per count of `counts`: the plan `opt` would sweep `sys` by on that many threads, and
/// its model's sweep against one thread's. Prints to stdout.
void print_plan_table(const ContactSystem& sys, const NlgsOptions& opt, const std::vector<int>& counts);

/// The next step of `mj` begun, its contacts detected and its problem prepared, then
/// print_plan_table of that system with mj's NLGS options: for a driver that stops after (the
/// step is left unsolved). Another solver, or an order other than the colored ones, plans
/// nothing: one line says so.
void print_next_step_plan(MoreauJean& mj, const std::vector<int>& counts);

/// "1,2,4": thread counts in [1, 256], each once, at most 8 of them; InputError (naming
/// `option`, e.g. "--threads") otherwise.
std::vector<int> parse_thread_list(const std::string& text, const std::string& option);

}  // namespace nscd::driver
