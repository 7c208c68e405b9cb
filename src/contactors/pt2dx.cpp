// nscd/contactors/pt2dx.cpp — see pt2dx.hpp.
#include "nscd/contactors/pt2dx.hpp"

#include <cmath>
#include <string>

#include "nscd/core/error.hpp"

namespace nscd {

PointId attach_point(Registry& reg, BodyId body, Vec2 p) {
  if (!body.valid() || body.index() >= reg.bodies.size()) throw Error("attach_point: unknown body id");
  if (!std::isfinite(p.x) || !std::isfinite(p.y))
    throw Error("PT2Dx of body " + std::to_string(body.index()) + ": point is not finite");
  reg.points.body.push_back(body);
  reg.points.point.push_back(p);
  return PointId(static_cast<std::uint32_t>(reg.points.size() - 1));
}

PointId attach_point_world(Registry& reg, BodyId body, Vec2 w) {
  if (!body.valid() || body.index() >= reg.bodies.size()) throw Error("attach_point_world: unknown body id");
  const std::size_t b = body.index();
  const Rot2 r = Rot2::of(reg.bodies.angle[b]);
  return attach_point(reg, body, r.apply_inverse(w - Vec2{reg.bodies.x[b], reg.bodies.y[b]}));
}

Vec2 point_position(const Registry& reg, PointId p, double x, double y, double angle) {
  return Vec2{x, y} + Rot2::of(angle).apply(reg.points.point[p.index()]);
}

// The PT2Dx row (contactor_row.hpp): points anchor the PTPT2 links and never touch, so the
// detection and VTK's bodies skip them; the links' file and checkpoint section are their own.
namespace {
std::size_t pt2dx_count(const Registry& reg) { return reg.points.size(); }
BodyId pt2dx_body(const Registry& reg, std::uint32_t i) { return reg.points.body[i]; }
}  // namespace

extern const ContactorKindRow kPt2dxRow;
const ContactorKindRow kPt2dxRow{.name = "PT2Dx", .tag = "pt", .count = pt2dx_count, .body = pt2dx_body};

}  // namespace nscd
