// nscd/interactions/shadow_overlap.hpp — J.J. Moreau's shadow-overlap detection between two
// convex polygons (Saussine et al. 2006, §2.3), the narrow phase of PLPLx.
//
// The shadow overlap along a unit direction V is
//     shov(V) = max_{a in A} a·V − min_{b in B} b·V,
// the overlap of the two polygons' orthogonal projections ("shadows") on V. Starting from
// V = G_A G_B / |G_A G_B|, V rotates toward decreasing shov until the critical vertices (those
// achieving the max / min) change; each such change happens at an edge normal of A or B.
// The walk stops at a local minimum: V is then the outward normal of an edge of one polygon
// and the critical vertex of the other is the intruding corner. A second intruding corner
// (the corner's neighbour within the alert distance) makes an edge–edge contact, described
// by the two extremities of the contact segment.
//
// Conventions: A is the antagonist, B the candidate; the normal n points toward the
// candidate (n = V at the end of the walk; for each extremity of an edge–edge contact, the
// normal of the edge its vertex faces: A's outward normal under a vertex of B, minus B's under
// a vertex of A); the tangent is t = perp(n); the gap g is negative for an overlap; the contact
// point sits at half the penetration between the two boundaries.
#pragma once

#include <cstdint>

#include "nscd/core/math.hpp"

namespace nscd {

/// A convex polygon in world coordinates: counter-clockwise vertices and the outward unit
/// normal of each edge k = (v_k, v_{k+1}).
struct ConvexView {
  const Vec2* vertex = nullptr;
  const Vec2* normal = nullptr;
  std::uint32_t count = 0;
};

struct ContactPoint {
  double gap = 0.0;
  Vec2 normal;              ///< unit, from the antagonist toward the candidate
  Vec2 point;               ///< world contact point
  std::uint32_t feature = 0;
};

/// Feature ids: which vertices and edges touch (stable from one step to the next, used to
/// warm-start the solver). Layout: bits 30–31 kind, bit 24 extremity, bits 12–23 first index,
/// bits 0–11 second index.
enum class FeatureKind : std::uint32_t {
  CandidateVertexOnAntagonistEdge = 1,
  AntagonistVertexOnCandidateEdge = 2,
  EdgeEdge = 3
};
constexpr std::uint32_t make_feature(FeatureKind k, std::uint32_t i, std::uint32_t j, std::uint32_t extremity = 0) {
  return (static_cast<std::uint32_t>(k) << 30) | (extremity << 24) | ((i & 0xFFFu) << 12) | (j & 0xFFFu);
}
constexpr FeatureKind feature_kind(std::uint32_t f) { return static_cast<FeatureKind>(f >> 30); }

struct ShadowOverlapResult {
  int count = 0;            ///< 0, 1 (vertex–edge) or 2 (edge–edge)
  ContactPoint points[2];
  int rotations = 0;        ///< number of critical-vertex changes walked (diagnostics)
};

/// Detects contact between antagonist A (reference point gA) and candidate B (gB). Pairs whose
/// gap exceeds `alert` give count = 0. The reported gap of a separated pair is the shadow
/// separation along an edge normal, a lower bound of the true distance.
ShadowOverlapResult shadow_overlap(const ConvexView& A, Vec2 gA, const ConvexView& B, Vec2 gB, double alert);

}  // namespace nscd
