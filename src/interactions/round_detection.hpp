// nscd/interactions/round_detection.hpp — the part of the detection that handles every kind but
// POLYG (DISKx, JONCx, xKSID and a scene's added kinds): their world geometry and boxes through
// their rows (contactors/contactor_row.hpp), the big ones, and the narrow-phase dispatch through
// PlplxDetector::collide[candidate kind][antagonist kind] (interaction_table.hpp).
//
// Box numbering in PlplxDetector::box: polygons [0, P), then each kind's boxes in kind order,
// kind k's from first_box[k]: disks, joncs, rings, then the added kinds. Adding an interaction
// kind is one function and one line of the table in interaction_table.cpp (or add_interaction).
#pragma once

#include <cstdint>

#include "nscd/interactions/plplx.hpp"

namespace nscd {

/// True if the scene holds any DISKx, JONCx or xKSID, or any contactor of an added kind: any
/// contactor the polygon path does not handle.
inline bool has_round_contactors(const Registry& reg) {
  if (!reg.diskx.empty() || !reg.joncx.empty() || !reg.xksid.empty()) return true;
  for (const ContactorKindRow* row : reg.added.row)
    if (row->count(reg) > 0) return true;
  return false;
}

/// World geometry and boxes of the other kinds, appended after the polygons' boxes, and
/// det.is_big for every box (the polygons' flags, then each row's: a disk or a jonc is big when
/// its size exceeds big_ratio × the median grain radius — polygons and disks —, a ring always);
/// det.first_box and det.collide for this scene.
void round_world_geometry(const Registry& reg, PlplxDetector& det, const Configuration& q);

/// The contactor of box b (after round_world_geometry).
ContactorId contactor_of_box(const PlplxDetector& det, std::uint32_t b);

/// The body carrying a contactor.
BodyId body_of(const Registry& reg, ContactorId c);

/// Narrow phase of boxes i and j when at least one is round: sets the antagonist and the
/// candidate (LMGC90's roles: the disk is the candidate against a polygon, a jonc or a ring, the
/// polygon against a jonc; between two disks the big one, else box i, is the antagonist) and
/// returns the points; count 0 for pairs with no interaction (jonc–jonc, ...).
PairContacts collide_round(const Registry& reg, const PlplxDetector& det, std::uint32_t i, std::uint32_t j,
                           ContactorId& antagonist, ContactorId& candidate);

}  // namespace nscd
