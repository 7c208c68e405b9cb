// nscd/contactors/round_views.hpp — the round contactors in world coordinates, as the DISKx,
// JONCx and xKSID rows place them (diskx_kind.cpp, joncx_kind.cpp, xksid_kind.cpp) and their narrow phases read them
// (interactions/round_pairs.hpp).
#pragma once

#include "nscd/core/math.hpp"

namespace nscd {

/// A disk in world coordinates.
struct DiskView {
  Vec2 centre;
  double radius = 0.0;
};

/// A JONCx in world coordinates: the segment centre ± half_length · axis (axis a unit vector),
/// thickened by half_thickness (round ends).
struct JoncView {
  Vec2 centre;
  Vec2 axis{1.0, 0.0};
  double half_length = 0.0;
  double half_thickness = 0.0;
};

/// An xKSID in world coordinates: the disk-shaped hole of a ring (the candidate stays inside).
struct RingView {
  Vec2 centre;
  double radius = 0.0;
};

/// The world position of a point at `offset` in the frame of a body at (x, y, angle).
inline Vec2 world_point(double x, double y, double angle, Vec2 offset) {
  return Vec2{x, y} + Rot2::of(angle).apply(offset);
}

}  // namespace nscd
