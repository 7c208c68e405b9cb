// nscd/interactions/interaction_table.hpp — the one table of interaction kinds: for each pair of
// contactor kinds, its LMGC90 name and its narrow phase (issue #12; Jolt's CollisionDispatch and
// LMGC90's inter_handler are the models).
//
// Adding an interaction between two contactor kinds is its narrow-phase function on the two
// kinds' world views (round_pairs.{hpp,cpp}) and one line of kInteractions in interaction_table.cpp:
// the name, the candidate's and the antagonist's kinds, the function with the two views'
// getters; a scene's own kinds add theirs with add_interaction (contactor_row.hpp). The dispatch
// matrix, the names and the roles derive from that line; the stepper, the solvers, VTK,
// checkpoints and the analysis read the contact table and do not change.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "nscd/contactors/contactor_kind.hpp"
#include "nscd/interactions/plplx.hpp"

namespace nscd {

/// An interaction kind: the candidate's contactor kind, then the antagonist's (DKPLx: a disk on a
/// polygon). PTPT2, the spring links, is {PT2Dx, PT2Dx}.
struct InteractionKind {
  ContactorKind candidate = ContactorKind::POLYG;
  ContactorKind antagonist = ContactorKind::POLYG;
  friend constexpr bool operator==(InteractionKind, InteractionKind) = default;
};

/// Resolve a name ("PLPLx", "DKDKx", …); throws nscd::Error naming the valid choices.
InteractionKind parse_interaction_kind(std::string_view name, std::string_view what = "interaction");
/// The LMGC90 name ("?" for a pair of kinds with no interaction).
std::string_view name_of(InteractionKind k);
/// The names in the table's order (the numbers the VTK contacts file's `interaction` array uses).
std::span<const std::string_view> interaction_names();
/// k's line in the table (its index in interaction_names()), -1 if no line.
int interaction_number(InteractionKind k);
/// The interaction a contact of the table belongs to, from its contactors' kinds.
inline InteractionKind interaction_of(ContactorId candidate, ContactorId antagonist) {
  return {contactor_kind(candidate), contactor_kind(antagonist)};
}

inline constexpr std::size_t kTouchingKinds = 4;  ///< POLYG, DISKx, JONCx, xKSID
/// kCollide[candidate kind][antagonist kind], built from the table; null: no interaction, or
/// PLPLx, which has its own path (plplx.cpp). Collide: kind_table.hpp.
extern const std::array<std::array<Collide, kTouchingKinds>, kTouchingKinds> kCollide;

/// The scene's dispatch: kCollide and the interactions the scene added (add_interaction).
std::array<std::array<Collide, kKindSlots>, kKindSlots> scene_collide(const Registry& reg);
/// The names of the built-in table's lines, then the scene's added ones (the numbers of the VTK
/// contacts file's `interaction` array).
std::vector<std::string_view> interaction_names(const Registry& reg);
/// k's number in interaction_names(reg), -1 if none.
int interaction_number(const Registry& reg, InteractionKind k);
/// k's name, built in or added ("?" if none).
std::string_view name_of(const Registry& reg, InteractionKind k);

/// The world geometry a narrow phase reads, by kind: a scene's own narrow phases (an
/// AddedInteraction's collide) read the built-in kinds through these, their own kind through
/// det.views[kind].get<TheirView>().
ConvexView polygon_view(const Registry& reg, const PlplxDetector& det, std::uint32_t p);
inline const DiskView& disk_view(const PlplxDetector& det, std::uint32_t k) {
  return det.views[static_cast<std::size_t>(ContactorKind::DISKx)].get<DiskView>()[k];
}
inline const JoncView& jonc_view(const PlplxDetector& det, std::uint32_t k) {
  return det.views[static_cast<std::size_t>(ContactorKind::JONCx)].get<JoncView>()[k];
}
inline const RingView& ring_view(const PlplxDetector& det, std::uint32_t k) {
  return det.views[static_cast<std::size_t>(ContactorKind::xKSID)].get<RingView>()[k];
}

}  // namespace nscd
