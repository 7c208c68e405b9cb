// nscd/interactions/contact_table.hpp — the one contact table of every interaction kind.
//
// Detection (plplx.hpp) fills it at q_m with every contact point, whatever the pair of contactors
// (PLPLx, DKDKx, DKKDx, DKPLx, DKJCx, PLJCx: the kinds are in the ContactorIds, the interaction
// of a row is interaction_of(candidate, antagonist), interaction_table.hpp); the solvers, the VTK
// writer, checkpoints and the analysis read it without knowing which pairs made it.
#pragma once

#include <cstdint>
#include <vector>

#include "nscd/core/ids.hpp"
#include "nscd/core/math.hpp"

namespace nscd {

/// Status of a contact point after the solve.
enum class ContactStatus : std::uint8_t { Open = 0, Stick = 1, SlipForward = 2, SlipBackward = 3 };

/// The contact table. n points from the antagonist toward the candidate; t = perp(n). The gap g
/// is negative for an overlap. Forces are in N/m (per unit thickness); the impulse over a step
/// is h·R. The points of one pair are consecutive.
struct ContactTable {
  std::vector<ContactorId> candidate, antagonist;
  std::vector<BodyId> cd_body, an_body;
  std::vector<std::uint32_t> feature;      ///< which vertices / edges touch (warm-start key)
  std::vector<double> gap;
  std::vector<Vec2> normal, point;
  /// Lever arms projected on the frame: cross(r, n) and cross(r, t), r = point − centre.
  std::vector<double> cd_rn, cd_rt, an_rn, an_rt;
  std::vector<double> rn, rt;              ///< contact force components (N/m)
  std::vector<ContactStatus> status;
  std::vector<std::int32_t> law;           ///< index into ContactLawTable::laws
  std::vector<double> mu;                  ///< friction of this contact (may differ per contact)

  std::size_t size() const { return candidate.size(); }
  bool empty() const { return candidate.empty(); }
  void clear() { resize(0); }
  void resize(std::size_t n) {
    candidate.resize(n);
    antagonist.resize(n);
    cd_body.resize(n);
    an_body.resize(n);
    feature.resize(n);
    gap.resize(n);
    normal.resize(n);
    point.resize(n);
    cd_rn.resize(n);
    cd_rt.resize(n);
    an_rn.resize(n);
    an_rt.resize(n);
    rn.resize(n);
    rt.resize(n);
    status.resize(n);
    law.resize(n);
    mu.resize(n);
  }
};

}  // namespace nscd
