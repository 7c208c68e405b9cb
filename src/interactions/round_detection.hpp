// nscd/interactions/round_detection.hpp — the part of the detection that handles the round
// contactors (DISKx, JONCx, xKSID): their world geometry and boxes, the big ones, and the
// narrow-phase dispatch through kCollide[candidate kind][antagonist kind] (interaction_table.hpp).
//
// Box numbering in PlplxDetector::box: polygons [0, P), disks [P, P + D), joncs
// [P + D, P + D + J), rings after. Adding an interaction kind is one function in
// round_pairs.cpp and one line of the table in interaction_table.cpp.
#pragma once

#include <cstdint>

#include "nscd/interactions/plplx.hpp"

namespace nscd {

/// True if the scene holds any DISKx, JONCx or xKSID.
inline bool has_round_contactors(const Registry& reg) {
  return !reg.diskx.empty() || !reg.joncx.empty() || !reg.xksid.empty();
}

/// World geometry and boxes of the round contactors, appended after the polygons' boxes, and
/// det.is_big for every box (the polygons' flags, then a disk or a jonc is big when its
/// radius exceeds big_ratio × the median grain radius — polygons and disks —, a ring always).
void round_world_geometry(const Registry& reg, PlplxDetector& det, const Configuration& q);

/// The contactor of box b.
ContactorId contactor_of_box(const Registry& reg, std::uint32_t b);

/// The body carrying a contactor.
BodyId body_of(const Registry& reg, ContactorId c);

/// Narrow phase of boxes i and j when at least one is round: sets the antagonist and the
/// candidate (LMGC90's roles: the disk is the candidate against a polygon, a jonc or a ring, the
/// polygon against a jonc; between two disks the big one, else box i, is the antagonist) and
/// returns the points; count 0 for pairs with no interaction (jonc–jonc, ...).
PairContacts collide_round(const Registry& reg, const PlplxDetector& det, std::uint32_t i, std::uint32_t j,
                           ContactorId& antagonist, ContactorId& candidate);

}  // namespace nscd
