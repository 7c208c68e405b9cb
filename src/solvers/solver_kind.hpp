// nscd/solvers/solver_kind.hpp — the contact solvers a run may choose, and their names.
#pragma once

#include <cstdint>
#include <string_view>

namespace nscd {

enum class SolverKind : std::uint8_t { NLGS, NEWTON_AC };

/// Resolve a name ("NLGS", "NEWTON_AC"); throws nscd::Error naming the valid choices.
SolverKind parse_solver_kind(std::string_view name, std::string_view what = "solver");
std::string_view name_of(SolverKind k);

}  // namespace nscd
