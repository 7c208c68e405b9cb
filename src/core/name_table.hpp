// nscd/core/name_table.hpp — a fixed table of the names a user may type (LMGC90's 5-letter
// vocabulary) and the enum each stands for.
//
// Each module declares its own table next to its enum (contactors/contactor_kind.hpp,
// interactions/interaction_table.hpp, laws/law_table.hpp, solvers/solver_kind.hpp): core knows no
// contactor, interaction, law or solver by name. An unknown name is an Error that lists the
// valid ones. See docs/glossary.md.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <utility>

#include "nscd/core/error.hpp"

namespace nscd {

template <class E, std::size_t N>
using NameTable = std::array<std::pair<std::string_view, E>, N>;

/// The enum named `name`; throws nscd::Error naming the valid choices. `what` names the option
/// in the message (e.g. "--law").
template <class E, std::size_t N>
E parse_name(const NameTable<E, N>& table, std::string_view name, std::string_view what) {
  for (const auto& [n, e] : table)
    if (n == name) return e;
  std::string msg = "unknown " + std::string(what) + " name '" + std::string(name) + "'; valid names:";
  for (const auto& entry : table) msg += " " + std::string(entry.first);
  throw Error(msg);
}

/// The name of `e` ("?" if the table lacks it).
template <class E, std::size_t N>
constexpr std::string_view name_in(const NameTable<E, N>& table, E e) {
  for (const auto& [n, v] : table)
    if (v == e) return n;
  return "?";
}

}  // namespace nscd
