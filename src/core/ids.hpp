// nscd/core/ids.hpp — small typed indices into the registry's tables.
//
// An id is a value (an index), never a pointer: tables may grow and move. Each kind of id
// is its own type, so a BodyId cannot be passed where a MaterialId is expected. The ids of a
// module's own rows are declared with its table (PolygId in contactors/polyg_table.hpp, …).
#pragma once

#include <cstdint>
#include <functional>
#include <limits>

namespace nscd {

template <class Tag>
struct Id {
  static constexpr std::uint32_t kInvalid = std::numeric_limits<std::uint32_t>::max();
  std::uint32_t value = kInvalid;

  constexpr Id() = default;
  constexpr explicit Id(std::uint32_t v) : value(v) {}
  constexpr bool valid() const { return value != kInvalid; }
  constexpr std::uint32_t index() const { return value; }
  friend constexpr bool operator==(Id a, Id b) { return a.value == b.value; }
  friend constexpr auto operator<=>(Id a, Id b) { return a.value <=> b.value; }
};

using BodyId = Id<struct BodyTag>;         ///< a rigid body (a row of every body's state)
using MaterialId = Id<struct MaterialTag>; ///< a row of the material table

/// Any contactor that can touch, as one number: its kind (a small number, 0–7, that the
/// contactors module assigns) in the top 3 bits and its row in that kind's table below. Kind 0's
/// ContactorId equals its row, so the contact table and the warm-start keys of a scene of kind 0
/// alone are those of a one-kind code.
using ContactorId = Id<struct ContactorTag>;
inline constexpr unsigned kContactorKindShift = 29;
inline constexpr std::uint32_t kContactorIndexMask = (1u << kContactorKindShift) - 1;
constexpr ContactorId make_contactor(std::uint8_t kind, std::uint32_t index) {
  return ContactorId((std::uint32_t(kind) << kContactorKindShift) | index);
}
constexpr std::uint8_t contactor_kind_bits(ContactorId c) {
  return static_cast<std::uint8_t>(c.value >> kContactorKindShift);
}
constexpr std::uint32_t contactor_index(ContactorId c) { return c.value & kContactorIndexMask; }

}  // namespace nscd

template <class Tag>
struct std::hash<nscd::Id<Tag>> {
  std::size_t operator()(nscd::Id<Tag> id) const noexcept { return std::hash<std::uint32_t>{}(id.value); }
};
