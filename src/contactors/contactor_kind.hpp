// nscd/contactors/contactor_kind.hpp — the contactor kinds and their LMGC90 names.
//
// The kinds that can touch (POLYG, DISKx, JONCx, xKSID) share one contact table; their number
// is the kind stored in the top bits of a ContactorId (core/ids.hpp). PT2Dx only anchors links.
// A new contactor kind adds its enum value and name here, its table beside polyg_table.hpp, and
// one member in registry/registry.hpp.
#pragma once

#include <cstdint>
#include <string_view>

#include "nscd/core/ids.hpp"

namespace nscd {

enum class ContactorKind : std::uint8_t { POLYG = 0, DISKx = 1, JONCx = 2, xKSID = 3, PT2Dx = 4 };

/// Resolve a name ("POLYG", "DISKx", …); throws nscd::Error naming the valid choices.
ContactorKind parse_contactor_kind(std::string_view name, std::string_view what = "contactor");
std::string_view name_of(ContactorKind k);

constexpr ContactorId make_contactor(ContactorKind kind, std::uint32_t index) {
  return make_contactor(static_cast<std::uint8_t>(kind), index);
}
constexpr ContactorKind contactor_kind(ContactorId c) { return static_cast<ContactorKind>(contactor_kind_bits(c)); }

}  // namespace nscd
