// nscd/contactors/kind_table.hpp — a contactor kind as one row of a table: its name and its
// operations (the body that carries a contactor, the world geometry and boxes the detection
// needs, the outline VTK draws, the numbers a checkpoint saves). The stepper, the detection, VTK
// and checkpoints loop over the rows and know no kind by name.
//
// The built-in kinds are the rows of contactor_row.cpp (POLYG and PT2Dx fill only what they use:
// POLYG has its own detection path and checkpoint section, PT2Dx never touches). A scene adds a
// kind of its own with add_contactor_kind — its row, its table (any type: only the row's
// functions read it) — and its interactions with add_interaction; nothing in src/ changes
// (tests/unit/test_added_kind.cpp adds a half-plane that way). docs/contributing.md §2 says how.
#pragma once

#include <any>
#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "nscd/contactors/contactor_kind.hpp"
#include "nscd/core/error.hpp"
#include "nscd/core/ids.hpp"
#include "nscd/core/math.hpp"

namespace nscd {

struct Registry;
struct Configuration;
struct PlplxDetector;        // interactions/plplx.hpp: named here only by the narrow phases' type
struct ShadowOverlapResult;  // interactions/shadow_overlap.hpp: the points of one pair

inline constexpr std::size_t kKindSlots = 8;       ///< kind numbers 0–7 (ids.hpp: 3 bits)
inline constexpr std::uint8_t kFirstAddedKind = 5;  ///< after the built-in kinds (ContactorKind)

/// One kind's contactors in world coordinates, as its narrow phases read them: a vector of the
/// kind's own view type, which the detection holds without knowing it.
class KindViews {
 public:
  /// The views, emptied, as a vector of View (made on first use).
  template <class View>
  std::vector<View>& reset() {
    auto* v = std::any_cast<std::vector<View>>(&data_);
    if (v == nullptr) {
      data_ = std::vector<View>{};
      v = std::any_cast<std::vector<View>>(&data_);
    }
    v->clear();
    return *v;
  }
  /// The views as filled by reset<View>() (a pointer compare checks the type).
  template <class View>
  const std::vector<View>& get() const {
    const auto* v = std::any_cast<std::vector<View>>(&data_);
    if (v == nullptr) throw Error("KindViews: the views hold another type than the one asked for");
    return *v;
  }

 private:
  std::any data_;
};

/// Where a kind's world geometry goes: each contactor's box, in the kind's table order, enlarged
/// by half the alert distance, and whether it stays out of the broad phase's grid (a wall).
struct KindBoxes {
  std::vector<Aabb>& box;
  std::vector<std::uint8_t>& is_big;
  double half_alert = 0.0;
  double big = 0.0;  ///< a contactor larger than this is big (0: none is, by its size)
  void push(Vec2 lo, Vec2 hi, bool big_one) {
    box.push_back({lo.x - half_alert, lo.y - half_alert, hi.x + half_alert, hi.y + half_alert});
    is_big.push_back(big_one ? 1 : 0);
  }
  void push_circle(Vec2 c, double r, bool big_one) { push({c.x - r, c.y - r}, {c.x + r, c.y + r}, big_one); }
  bool is_big_size(double size) const { return big > 0.0 && size > big; }
};

/// A contactor's drawing for VTK: one or more closed outlines, in the body frame.
struct KindOutline {
  std::vector<Vec2> points;
  std::vector<std::size_t> cell_end;  ///< points[cell_end[c-1] .. cell_end[c]) is cell c
  void put(Vec2 v) { points.push_back(v); }
  void end_cell() { cell_end.push_back(points.size()); }
};

/// A contactor kind's row. A null function: the kind does not take part in that operation.
struct ContactorKindRow {
  std::string_view name;  ///< LMGC90's name (five characters: "DISKx")
  std::string_view tag;   ///< the tag of its checkpoint records ("dk")
  std::span<const std::string_view> params{};  ///< what the numbers of save/load are, in order
  std::size_t (*count)(const Registry&) = nullptr;
  BodyId (*body)(const Registry&, std::uint32_t i) = nullptr;
  /// World geometry at q: every contactor's views (in views) and box (pushed to boxes).
  void (*world)(const Registry&, const Configuration& q, KindViews& views, KindBoxes& boxes) = nullptr;
  /// Contactor i's outline(s) in its body's frame.
  void (*draw)(const Registry&, std::uint32_t i, KindOutline& out) = nullptr;
  /// Contactor i's numbers (params.size() of them), relative to its body.
  void (*save)(const Registry&, std::uint32_t i, double* numbers) = nullptr;
  /// Attaches a contactor from saved numbers, bit for bit; throws nscd::Error on bad numbers.
  void (*load)(Registry&, BodyId body, const double* numbers) = nullptr;
  /// An empty table of the kind (added kinds only: the built-in tables are Registry members).
  std::any (*new_table)() = nullptr;
};

/// A narrow phase: the contact points of an antagonist and a candidate (rows of their kinds'
/// tables), from the detector's world geometry.
using Collide = ShadowOverlapResult (*)(const Registry&, const PlplxDetector&, std::uint32_t antagonist,
                                        std::uint32_t candidate, double alert);

/// An interaction a scene adds (one involving an added kind): as a line of the built-in table.
struct AddedInteraction {
  std::string_view name;  ///< LMGC90-style: candidate's two letters, antagonist's two, "x"
  ContactorKind candidate, antagonist;
  Collide collide = nullptr;
};

/// The kinds and interactions a scene adds to the built-in ones (kind kFirstAddedKind + k).
struct AddedKinds {
  std::vector<const ContactorKindRow*> row;
  std::vector<std::any> table;  ///< row k's table, of the type its functions know
  std::vector<AddedInteraction> interactions;
  std::size_t size() const { return row.size(); }
};

}  // namespace nscd
