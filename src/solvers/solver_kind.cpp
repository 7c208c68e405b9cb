// nscd/solvers/solver_kind.cpp — see solver_kind.hpp.
#include "nscd/solvers/solver_kind.hpp"

#include "nscd/core/name_table.hpp"

namespace nscd {
namespace {

constexpr NameTable<SolverKind, 2> kSolvers{{{"NLGS", SolverKind::NLGS}, {"NEWTON_AC", SolverKind::NEWTON_AC}}};

}  // namespace

SolverKind parse_solver_kind(std::string_view n, std::string_view w) { return parse_name(kSolvers, n, w); }
std::string_view name_of(SolverKind k) { return name_in(kSolvers, k); }

}  // namespace nscd
