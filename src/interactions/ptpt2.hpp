// nscd/interactions/ptpt2.hpp — PTPT2: spring links between two PT2Dx points (LMGC90's name),
// used for the visco-elastic sublayer (paper §2.9). A link is always active; its frame is
// the unit vector n from the antagonist point to the candidate point, at q_m.
#pragma once

#include <span>

#include "nscd/registry/registry.hpp"

namespace nscd {

/// Adds a VOIGT_ROD spring. A law.L0 <= 0 takes the current distance between the points.
/// Throws nscd::Error on k < 0, nu < 0, non-finite values, coincident points, or unknown ids.
LinkId add_spring(Registry& reg, PointId candidate, PointId antagonist, VoigtRod law);

/// The geometry of one link at a configuration: length, normal and lever arms cross(r, n).
struct LinkFrame {
  double length = 0.0;
  Vec2 n;
  double cd_rn = 0.0, an_rn = 0.0;
};
LinkFrame link_frame(const Registry& reg, LinkId link, std::span<const double> x, std::span<const double> y,
                     std::span<const double> angle);

}  // namespace nscd
