// nscd/contactors/pt2dx.hpp — PT2Dx: point contactors, the anchors of PTPT2 springs
// (LMGC90's name). A point is attached to a body and given in the body frame.
#pragma once

#include "nscd/registry/registry.hpp"

namespace nscd {

/// Attaches a point given in the body frame (origin = the body's centre of mass).
PointId attach_point(Registry& reg, BodyId body, Vec2 point_body_frame);
/// Attaches a point given in world coordinates at the body's current configuration.
PointId attach_point_world(Registry& reg, BodyId body, Vec2 point_world);
/// World position of a point at configuration (x, y, angle) of its body.
Vec2 point_position(const Registry& reg, PointId p, double x, double y, double angle);

}  // namespace nscd
