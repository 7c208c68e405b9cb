// nscd/core/names.cpp — see names.hpp.
#include "nscd/core/names.hpp"

#include <array>
#include <utility>

#include "nscd/core/error.hpp"

namespace nscd {
namespace {

template <class E, std::size_t N>
using Table = std::array<std::pair<std::string_view, E>, N>;

constexpr Table<ContactorKind, 5> kContactors{{{"POLYG", ContactorKind::POLYG},
                                               {"DISKx", ContactorKind::DISKx},
                                               {"JONCx", ContactorKind::JONCx},
                                               {"xKSID", ContactorKind::xKSID},
                                               {"PT2Dx", ContactorKind::PT2Dx}}};
constexpr Table<InteractionKind, 7> kInteractions{{{"PLPLx", InteractionKind::PLPLx},
                                                   {"PTPT2", InteractionKind::PTPT2},
                                                   {"DKDKx", InteractionKind::DKDKx},
                                                   {"DKKDx", InteractionKind::DKKDx},
                                                   {"DKPLx", InteractionKind::DKPLx},
                                                   {"DKJCx", InteractionKind::DKJCx},
                                                   {"PLJCx", InteractionKind::PLJCx}}};
constexpr Table<LawKind, 4> kLaws{{{"IQS_CLB", LawKind::IQS_CLB},
                                    {"GAP_SGR_CLB", LawKind::GAP_SGR_CLB},
                                    {"RST_CLB", LawKind::RST_CLB},
                                    {"VOIGT_ROD", LawKind::VOIGT_ROD}}};
constexpr Table<SolverKind, 2> kSolvers{{{"NLGS", SolverKind::NLGS}, {"NEWTON_AC", SolverKind::NEWTON_AC}}};

template <class E, std::size_t N>
E parse(const Table<E, N>& table, std::string_view name, std::string_view what) {
  for (const auto& [n, e] : table)
    if (n == name) return e;
  std::string msg = "unknown " + std::string(what) + " name '" + std::string(name) + "'; valid names:";
  for (const auto& entry : table) msg += " " + std::string(entry.first);
  throw Error(msg);
}

template <class E, std::size_t N>
std::string_view name(const Table<E, N>& table, E e) {
  for (const auto& [n, v] : table)
    if (v == e) return n;
  return "?";
}

}  // namespace

ContactorKind parse_contactor_kind(std::string_view n, std::string_view w) { return parse(kContactors, n, w); }
InteractionKind parse_interaction_kind(std::string_view n, std::string_view w) { return parse(kInteractions, n, w); }
LawKind parse_law_kind(std::string_view n, std::string_view w) { return parse(kLaws, n, w); }
SolverKind parse_solver_kind(std::string_view n, std::string_view w) { return parse(kSolvers, n, w); }

std::string_view name_of(ContactorKind k) { return name(kContactors, k); }
std::string_view name_of(InteractionKind k) { return name(kInteractions, k); }
std::string_view name_of(LawKind k) { return name(kLaws, k); }
std::string_view name_of(SolverKind k) { return name(kSolvers, k); }

}  // namespace nscd
