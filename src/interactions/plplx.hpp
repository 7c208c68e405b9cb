// nscd/interactions/plplx.hpp — the detection of contacts: PLPLx (polygon–polygon, LMGC90's
// name) and, when the scene holds round contactors, DKDKx, DKKDx, DKPLx, DKJCx and PLJCx.
//
// detect_plplx() fills Registry::contacts (the one contact table) with every contact point between
// contactors of different bodies whose gap is at most the alert distance, at a given
// configuration q (the θ-method detects at q_m). Broad phase: bounding boxes of every contactor
// on a grid of tiles (broad_phase.hpp); narrow phase: shadow overlap (shadow_overlap.hpp) for
// two polygons, round_pairs.hpp through the dispatch table of round_detection.cpp otherwise.
// A polygon-only scene takes exactly the polygon path: the round kinds cost it nothing.
//
// For each contact point it stores the local frame (n toward the candidate, t = perp(n)),
// the gap, the point, and the lever arms projected on the frame, so that the local relative
// velocity U = H* u and the generalized force r = H R cost a few multiplications
// (solvers/contact_part.hpp).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "nscd/registry/registry.hpp"
#include "nscd/interactions/broad_phase.hpp"
#include "nscd/interactions/round_pairs.hpp"
#include "nscd/interactions/shadow_overlap.hpp"

namespace nscd {

struct DetectionStats {
  std::size_t candidate_pairs = 0;  ///< pairs passed by the broad phase
  std::size_t contact_pairs = 0;    ///< pairs with at least one contact point
  std::size_t contact_points = 0;
  std::size_t double_contacts = 0;  ///< pairs with two points (edge–edge)
  std::size_t kept_pairs = 0;       ///< candidate pairs whose narrow phase was kept from the last detection
};

/// Reusable detection workspace (world geometry, boxes, grid). Keep one per scene.
struct PlplxDetector {
  /// A polygon whose bounding radius exceeds big_ratio × the median radius stays out of the
  /// grid (walls, floors). Set before the first detection.
  double big_ratio = 8.0;
  /// Threads of the world geometry, the still test, the broad phase's reuse and the narrow phase
  /// (OpenMP; MoreauJean sets it from StepperOptions::threads). The contacts come out in the
  /// broad phase's order whatever the threads; below 256 polygons or candidate pairs a loop
  /// stays on one thread.
  int threads = 1;

  std::vector<Vec2> world_vertex, world_normal, world_centre;
  std::vector<Aabb> box;
  std::vector<std::uint8_t> is_big;
  BroadPhase broad;
  std::vector<ShadowOverlapResult> narrow;  ///< threads > 1: each candidate pair's result, in pair order
  DetectionStats stats;
  /// The other kinds' contactors in world coordinates, by kind (round_detection.hpp: each kind's
  /// row fills its own). Their boxes follow the polygons' in `box`, kind after kind:
  /// first_box[k] is kind k's first box, first_box[k + 1] its end; unused in a polygon-only scene.
  std::array<KindViews, kKindSlots> views;
  std::array<std::uint32_t, kKindSlots + 1> first_box{};
  std::vector<std::uint32_t> box_body;  ///< the body of each box's contactor (a scene with other kinds)
  /// The scene's narrow phases, collide[candidate kind][antagonist kind]: the built-in table's and
  /// the scene's added ones (interaction_table.hpp: scene_collide); null: no interaction.
  std::array<std::array<Collide, kKindSlots>, kKindSlots> collide{};
  std::vector<std::pair<ContactorId, ContactorId>> narrow_roles;  ///< threads > 1: (antagonist, candidate) per pair
  std::vector<std::size_t> narrow_rows;  ///< threads > 1: each thread's first contact row
  /// threads > 1: each thread's counts of the narrow phase (a cache line each: they are
  /// counted pair after pair)
  struct alignas(64) ThreadCounts {
    std::size_t reused = 0, contact_pairs = 0, double_contacts = 0;
  };
  std::vector<ThreadCounts> thread_counts;
  double grain_median = 0.0;            ///< grain_median_radius, cached for the round contactors
  std::size_t grain_median_count = 0;   ///< the polygon + disk count it was computed for
  std::size_t classified_count = 0;     ///< polygon + disk count when is_big was last classified (MoreauJean)

  /// The narrow phase kept for pairs of polygons that have not moved (detect_plplx): a pair of
  /// two polygons whose world geometry, body and kinematic state are, bit for bit, those of the
  /// last detection, and whose result was computed or kept at that detection, takes that result
  /// again. The result is a function of exactly these inputs (and the alert distance, also
  /// compared): the same contacts as computing it. Indexed by the broad phase's kept list.
  struct Kept {
    std::vector<Vec2> vertex, normal, centre;  ///< the last detection's world geometry
    std::vector<double> q;                     ///< its bodies' (x, y, angle), per polygon
    std::vector<std::uint32_t> body;           ///< … and each polygon's body
    std::vector<std::uint8_t> kinematic;       ///< … and whether that body was kinematic
    std::vector<std::uint8_t> still;           ///< this detection: the polygon is as at the last one
    std::vector<ShadowOverlapResult> result;   ///< per entry of broad.near
    std::vector<std::pair<ContactorId, ContactorId>> roles;
    std::vector<std::uint64_t> stamp;          ///< the detection that computed or kept it
    std::uint64_t detections = 1;              ///< detections so far, plus 1
    std::size_t rebuilds = ~std::size_t{0};    ///< broad.rebuilds when `result` was sized
    double alert = 0.0;
  } kept;
};

/// The median bounding radius of the grains: polygons and disks together.
double grain_median_radius(const Registry& reg);

/// Recomputes which polygons are big (PolygTable::is_big): radius > big_ratio × the median
/// grain radius (polygons and disks).
void classify_big_polygons(Registry& reg, double big_ratio);

/// Detection at configuration q; replaces the content of reg.contacts (forces reset to 0,
/// laws from the contact-law table). Returns the statistics (also in det.stats).
DetectionStats detect_plplx(Registry& reg, PlplxDetector& det, const Configuration& q);
inline DetectionStats detect_plplx(Registry& reg, PlplxDetector& det) {
  return detect_plplx(reg, det, Configuration::of(reg));
}

}  // namespace nscd
