// nscd/solvers/nlgs_colored.hpp — NLGS swept colour by colour, on one thread or several, with a
// result that does not depend on the number of threads.
//
// Colouring (greedy, in contact order, as Box2D's constraint_graph.c): a contact takes the
// lowest colour not yet taken at either of its *dynamic* bodies (kinematic bodies are never
// written, so any number of contacts of a colour may touch the floor). Colours 0 … 62 are swept
// in parallel; contacts that find none free go to an overflow colour swept on one thread. Inside
// a colour no two contacts share a dynamic body, so visiting them in any order, on any thread,
// gives the same numbers; the convergence sums are recorded per contact and added up in one
// fixed order after the sweep. The order differs from `fixed` (Gauss–Seidel in colour order),
// so sweeps to convergence differ too — docs/theory.md §9.5.
#pragma once

#include "nscd/solvers/contact_system.hpp"
#include "nscd/solvers/nlgs.hpp"
#include "nscd/solvers/nlgs_sweep.hpp"

namespace nscd {

/// Colours the contacts of `sys` (fills ws.order and ws.color_start; the last colour is the
/// overflow). Returns the number of colours used, the overflow included if non-empty.
std::size_t color_contacts(const ContactSystem& sys, NlgsWorkspace& ws);

/// NLGS on the scene's system with SweepOrder::Colored on `opt.threads` threads.
NlgsResult nlgs_iterate_colored(ContactSystem& sys, const NlgsOptions& opt, NlgsWorkspace& ws);

}  // namespace nscd
