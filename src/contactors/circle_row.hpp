// nscd/contactors/circle_row.hpp — the row operations (kind_table.hpp) that DISKx and xKSID
// share: both tables hold a body, a centre offset in the body frame and a radius per contactor
// (round_tables.hpp). Their world geometry and drawing differ and stay in their own files.
#pragma once

#include <cstdint>
#include <string_view>

#include "nscd/contactors/kind_table.hpp"
#include "nscd/contactors/round_shapes.hpp"

namespace nscd {

/// The count, body, save and load of a row whose table is reg.*table (DiskxTable or XksidTable),
/// its contactors attached by attach (attach_diskx or attach_xksid). A checkpoint holds the
/// numbers `params` names, in that order.
template <auto table, auto attach>
struct CircleRow {
  static constexpr std::string_view params[] = {"offset x", "offset y", "radius"};

  static std::size_t count(const Registry& reg) { return (reg.*table).size(); }
  static BodyId body(const Registry& reg, std::uint32_t i) { return (reg.*table).body[i]; }
  static void save(const Registry& reg, std::uint32_t i, double* n) {
    const auto& t = reg.*table;
    n[0] = t.offset[i].x, n[1] = t.offset[i].y, n[2] = t.radius[i];
  }
  static void load(Registry& reg, BodyId b, const double* n) { attach(reg, b, {n[0], n[1]}, n[2]); }

  /// The kind's row: these shared operations with its own name, tag, world geometry and drawing.
  static constexpr ContactorKindRow row(std::string_view name, std::string_view tag,
                                        decltype(ContactorKindRow::world) world,
                                        decltype(ContactorKindRow::draw) draw) {
    return {.name = name,
            .tag = tag,
            .params = params,
            .count = count,
            .body = body,
            .world = world,
            .draw = draw,
            .save = save,
            .load = load};
  }
};

}  // namespace nscd
