// nscd/interactions/round_pairs.hpp — the narrow phases of the round contactors (issue #12):
// DISKx (a disk), JONCx (LMGC90's "jonc": a segment of half-length a thickened by a radius b,
// i.e. a capsule, the usual wall of a disk sample) and xKSID (the inside of a ring: a drum),
// against each other and against POLYG. LMGC90's interaction names:
//
//   DKDKx  disk (candidate)    – disk (antagonist)       1 point
//   DKKDx  disk (candidate)    – xKSID ring (antagonist)  1 point, the disk inside the ring
//   DKPLx  disk (candidate)    – POLYG (antagonist)      1 point
//   DKJCx  disk (candidate)    – JONCx (antagonist)      1 point
//   PLJCx  POLYG (candidate)   – JONCx (antagonist)      1 or 2 points (an edge on the flat face)
//   PLKDx  POLYG (candidate)   – xKSID ring (antagonist)  1 or 2 points, the polygon inside the
//          ring (nscd's addition by LMGC90's naming pattern: LMGC90 2D has no polygon in a ring)
//
// Exact geometry, the conventions of shadow_overlap.hpp: the normal n is a unit vector from the
// antagonist toward the candidate, t = perp(n), the gap g is the signed distance between the two
// boundaries along n (negative for an overlap), and the contact point sits halfway between the
// two boundary points, so that the antagonist's boundary point is point − (g/2) n and the
// candidate's is point + (g/2) n. Pairs whose gap exceeds `alert` give count = 0.
//
// Feature ids (the warm-start key within a pair, stable while the same features touch):
//   DKDKx, DKKDx: 0.   DKPLx: the polygon edge k (kind 1) or vertex k (kind 2).
//   DKJCx: 0 / 1 the face on the +perp(axis) / −perp(axis) side, 2 / 3 the round end at −a / +a.
//   PLJCx: polygon vertex i on the jonc (kind 1), jonc end j ∈ {0, 1} on a polygon edge (kind 2).
//   PLKDx: polygon vertex i (kind 1).
#pragma once

#include "nscd/contactors/round_views.hpp"
#include "nscd/core/math.hpp"
#include "nscd/interactions/shadow_overlap.hpp"

namespace nscd {

/// The contact points of one pair, whatever the interaction kind (at most 2).
using PairContacts = ShadowOverlapResult;

PairContacts dkdkx(const DiskView& antagonist, const DiskView& candidate, double alert);
PairContacts dkkdx(const RingView& antagonist, const DiskView& candidate, double alert);
PairContacts dkplx(const ConvexView& antagonist, const DiskView& candidate, double alert);
PairContacts dkjcx(const JoncView& antagonist, const DiskView& candidate, double alert);
PairContacts pljcx(const JoncView& antagonist, const ConvexView& candidate, double alert);
/// A convex polygon inside a ring touches it by vertices only (the distance from the ring's
/// centre is convex, so it is largest at vertices): each vertex within `alert` of the wall is a
/// candidate point; the deepest and the one farthest from it along the wall are kept.
PairContacts plkdx(const RingView& antagonist, const ConvexView& candidate, double alert);

}  // namespace nscd
