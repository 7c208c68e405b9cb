// nscd/core/names.hpp — the one explicit table of the 5-letter names used in config
// files and on the command line (LMGC90's vocabulary), and their enums.
//
// Every name a user can type resolves here; an unknown name is an Error that lists the
// valid ones. See docs/glossary.md.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace nscd {

/// Contactor kinds. The first four can touch (their contacts share one table, keyed by
/// ContactorId, whose top bits hold the kind); PT2Dx only anchors links.
enum class ContactorKind : std::uint8_t { POLYG = 0, DISKx = 1, JONCx = 2, xKSID = 3, PT2Dx = 4 };
/// Interaction kinds: the candidate's contactor first (DKPLx: a disk on a polygon).
enum class InteractionKind : std::uint8_t { PLPLx, PTPT2, DKDKx, DKKDx, DKPLx, DKJCx, PLJCx };
enum class LawKind : std::uint8_t { IQS_CLB, GAP_SGR_CLB, RST_CLB, VOIGT_ROD };
enum class SolverKind : std::uint8_t { NLGS, NEWTON_AC };

/// Resolve a name; throws nscd::Error naming the valid choices. `what` names the option
/// in the message (e.g. "--law").
ContactorKind parse_contactor_kind(std::string_view name, std::string_view what = "contactor");
InteractionKind parse_interaction_kind(std::string_view name, std::string_view what = "interaction");
LawKind parse_law_kind(std::string_view name, std::string_view what = "contact law");
SolverKind parse_solver_kind(std::string_view name, std::string_view what = "solver");

std::string_view name_of(ContactorKind k);
std::string_view name_of(InteractionKind k);
std::string_view name_of(LawKind k);
std::string_view name_of(SolverKind k);

}  // namespace nscd
