// nscd/contactors/contactor_row.hpp — the table of contactor kinds (kind_table.hpp): the built-in
// rows, the row of a kind, and the kinds and interactions a scene adds.
#pragma once

#include <any>
#include <span>
#include <string>
#include <string_view>

#include "nscd/contactors/kind_table.hpp"
#include "nscd/core/error.hpp"

namespace nscd {

/// The built-in kinds' rows, in ContactorKind order.
std::span<const ContactorKindRow* const> builtin_kind_rows();
/// Kind k's row, built-in or added to reg; null when k is neither.
const ContactorKindRow* kind_row(const Registry& reg, std::uint8_t k);
/// The number of kinds in reg: the built-in ones and the added ones.
std::size_t kind_count(const Registry& reg);
/// Kind k's name, "?" when it has none.
std::string_view kind_name(const Registry& reg, std::uint8_t k);

/// Adds a kind to the scene (its row must outlive the registry, e.g. a static): returns its
/// number. Throws nscd::Error if the row lacks count, body or new_table, if its name is taken,
/// or if the three added kinds' slots are full.
ContactorKind add_contactor_kind(Registry& reg, const ContactorKindRow& row);
/// Adds an interaction between two kinds, at least one of them added. Throws nscd::Error if a
/// kind is unknown, the pair already has a line (in either order), or the name is taken.
void add_interaction(Registry& reg, const AddedInteraction& line);

/// An added kind's table; throws nscd::Error if kind k is not added or holds another type.
std::any& added_table_any(Registry& reg, ContactorKind k);
const std::any& added_table_any(const Registry& reg, ContactorKind k);
template <class Table>
Table& added_table(Registry& reg, ContactorKind k) {
  if (auto* t = std::any_cast<Table>(&added_table_any(reg, k))) return *t;
  throw Error("added_table: kind " + std::to_string(static_cast<int>(k)) + " holds another table type");
}
template <class Table>
const Table& added_table(const Registry& reg, ContactorKind k) {
  if (const auto* t = std::any_cast<Table>(&added_table_any(reg, k))) return *t;
  throw Error("added_table: kind " + std::to_string(static_cast<int>(k)) + " holds another table type");
}

}  // namespace nscd
