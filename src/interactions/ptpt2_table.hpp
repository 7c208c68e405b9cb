// nscd/interactions/ptpt2_table.hpp — the PTPT2 table: spring links between two PT2Dx points
// (the sublayer). The functions are in ptpt2.hpp.
#pragma once

#include <vector>

#include "nscd/contactors/pt2dx_table.hpp"
#include "nscd/core/math.hpp"
#include "nscd/laws/law_table.hpp"

namespace nscd {

using LinkId = Id<struct LinkTag>;  ///< a PTPT2 spring link

/// PTPT2 links: one VOIGT_ROD spring between two PT2Dx points. Always active (bilateral);
/// the frame and forces are refreshed each step at q_m.
struct Ptpt2Table {
  std::vector<PointId> candidate, antagonist;
  std::vector<VoigtRod> law;
  std::vector<double> length;  ///< L at the last detection (q_m)
  std::vector<Vec2> normal;    ///< unit, from the antagonist point to the candidate point
  std::vector<double> rn;      ///< force along n on the candidate (N/m); < 0 pulls it back
  std::size_t size() const { return candidate.size(); }
  bool empty() const { return candidate.empty(); }
};

}  // namespace nscd
