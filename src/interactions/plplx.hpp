// nscd/interactions/plplx.hpp — PLPLx: polygon–polygon interactions (LMGC90's name).
//
// detect_plplx() fills Registry::plplx with every contact point between POLYG contactors
// of different bodies whose gap is at most the alert distance, at a given configuration q
// (the θ-method detects at q_m). Broad phase: bounding boxes on a grid of tiles
// (broad_phase.hpp); narrow phase: shadow overlap (shadow_overlap.hpp).
//
// For each contact point it stores the local frame (n toward the candidate, t = perp(n)),
// the gap, the point, and the lever arms projected on the frame, so that the local relative
// velocity U = H* u and the generalized force r = H R cost a few multiplications
// (solvers/contact_part.hpp).
#pragma once

#include <span>
#include <vector>

#include "nscd/core/registry.hpp"
#include "nscd/interactions/broad_phase.hpp"
#include "nscd/interactions/shadow_overlap.hpp"

namespace nscd {

/// A configuration of all bodies (centre of mass and angle); by default the registry's.
struct Configuration {
  std::span<const double> x, y, angle;
  static Configuration of(const Registry& reg) { return {reg.bodies.x, reg.bodies.y, reg.bodies.angle}; }
};

struct DetectionStats {
  std::size_t candidate_pairs = 0;  ///< pairs passed by the broad phase
  std::size_t contact_pairs = 0;    ///< pairs with at least one contact point
  std::size_t contact_points = 0;
  std::size_t double_contacts = 0;  ///< pairs with two points (edge–edge)
};

/// Reusable detection workspace (world geometry, boxes, grid). Keep one per scene.
struct PlplxDetector {
  /// A polygon whose bounding radius exceeds big_ratio × the median radius stays out of the
  /// grid (walls, floors). Set before the first detection.
  double big_ratio = 8.0;
  /// Threads of the narrow phase (OpenMP; MoreauJean sets it from NlgsOptions::threads). The
  /// contacts come out in the broad phase's order whatever the threads; below 2048 candidate
  /// pairs the narrow phase stays on one thread.
  int threads = 1;

  std::vector<Vec2> world_vertex, world_normal, world_centre;
  std::vector<Aabb> box;
  std::vector<std::uint8_t> is_big;
  BroadPhase broad;
  std::vector<ShadowOverlapResult> narrow;  ///< threads > 1: each candidate pair's result, in pair order
  DetectionStats stats;
};

/// Recomputes which polygons are big (PolygTable::is_big) from their radii.
void classify_big_polygons(Registry& reg, double big_ratio);

/// Detection at configuration q; replaces the content of reg.plplx (forces reset to 0,
/// laws from the contact-law table). Returns the statistics (also in det.stats).
DetectionStats detect_plplx(Registry& reg, PlplxDetector& det, const Configuration& q);
inline DetectionStats detect_plplx(Registry& reg, PlplxDetector& det) {
  return detect_plplx(reg, det, Configuration::of(reg));
}

}  // namespace nscd
