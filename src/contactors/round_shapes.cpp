// nscd/contactors/round_shapes.cpp — see round_shapes.hpp.
#include "nscd/contactors/round_shapes.hpp"

#include <cmath>
#include <string>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/core/error.hpp"
#include "nscd/core/math.hpp"

namespace nscd {
namespace {

void require(bool ok, const char* what, double value) {
  if (!ok) throw Error(std::string(what) + ", got " + std::to_string(value));
}

}  // namespace

RoundMass diskx_mass(double radius, double rho) {
  require(std::isfinite(radius) && radius > 0.0, "DISKx: the radius must be > 0", radius);
  require(std::isfinite(rho) && rho > 0.0, "DISKx: the density must be > 0", rho);
  const double m = rho * kPi * radius * radius;
  return {m, 0.5 * m * radius * radius};
}

RoundMass joncx_mass(double a, double b, double rho) {
  require(std::isfinite(a) && a >= 0.0, "JONCx: the half-length must be >= 0", a);
  require(std::isfinite(b) && b > 0.0, "JONCx: the half-thickness must be > 0", b);
  require(std::isfinite(rho) && rho > 0.0, "JONCx: the density must be > 0", rho);
  const double m_rect = 4.0 * rho * a * b;
  const double i_rect = m_rect * (4.0 * a * a + 4.0 * b * b) / 12.0;
  const double m_half = 0.5 * rho * kPi * b * b;
  const double c = 4.0 * b / (3.0 * kPi);
  const double i_half = m_half * (0.5 * b * b - c * c + (a + c) * (a + c));
  return {m_rect + 2.0 * m_half, i_rect + 2.0 * i_half};
}

namespace {

std::string who(const Registry& reg, BodyId body, const char* kind) {
  if (!body.valid() || body.index() >= reg.bodies.size())
    throw Error(std::string("attach ") + kind + ": unknown body id");
  const std::string& n = reg.bodies.name[body.index()];
  return std::string(kind) + " of body " + std::to_string(body.index()) + (n.empty() ? "" : " '" + n + "'");
}

void require_point(Vec2 p, const std::string& what) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw Error(what + ": the offset must be finite");
}

double density_of(const Registry& reg, MaterialId m, const char* kind) {
  if (!m.valid() || m.index() >= reg.materials.size()) throw Error(std::string(kind) + " body: unknown material id");
  return reg.materials.density[m.index()];
}

}  // namespace

namespace {

// DISKx and xKSID rows hold the same fields: body, centre offset, radius.
template <class Id, class Table>
Id attach_circle(const Registry& reg, Table& t, BodyId body, Vec2 offset, double radius, const char* kind) {
  const std::string w = who(reg, body, kind);
  require_point(offset, w);
  require(std::isfinite(radius) && radius > 0.0, (w + ": the radius must be > 0").c_str(), radius);
  t.body.push_back(body);
  t.offset.push_back(offset);
  t.radius.push_back(radius);
  return Id(static_cast<std::uint32_t>(t.size() - 1));
}

}  // namespace

DiskxId attach_diskx(Registry& reg, BodyId body, Vec2 offset, double radius) {
  return attach_circle<DiskxId>(reg, reg.diskx, body, offset, radius, "DISKx");
}

JoncxId attach_joncx(Registry& reg, BodyId body, Vec2 offset, Vec2 axis, double half_length, double half_thickness) {
  const std::string w = who(reg, body, "JONCx");
  require_point(offset, w);
  const double len = norm(axis);
  if (!std::isfinite(len) || !(len > 0.0)) throw Error(w + ": the axis must be a finite non-zero vector");
  require(std::isfinite(half_length) && half_length >= 0.0, (w + ": the half-length must be >= 0").c_str(),
          half_length);
  require(std::isfinite(half_thickness) && half_thickness > 0.0, (w + ": the half-thickness must be > 0").c_str(),
          half_thickness);
  JoncxTable& t = reg.joncx;
  t.body.push_back(body);
  t.offset.push_back(offset);
  t.axis.push_back((1.0 / len) * axis);
  t.half_length.push_back(half_length);
  t.half_thickness.push_back(half_thickness);
  return JoncxId(static_cast<std::uint32_t>(t.size() - 1));
}

XksidId attach_xksid(Registry& reg, BodyId body, Vec2 offset, double radius) {
  return attach_circle<XksidId>(reg, reg.xksid, body, offset, radius, "xKSID");
}

namespace {

BodyId add_round_body(Registry& reg, const RoundMass& m, MaterialId material, Vec2 position, double angle,
                      const std::string& name) {
  RigidBodySpec spec;
  spec.name = name;
  spec.material = material;
  spec.position = position;
  spec.angle = angle;
  spec.mass = m.mass;
  spec.inertia = m.inertia;
  return add_body(reg, spec);
}

}  // namespace

BodyId add_disk_body(Registry& reg, double radius, MaterialId material, Vec2 position, const std::string& name) {
  const BodyId b =
      add_round_body(reg, diskx_mass(radius, density_of(reg, material, "DISKx")), material, position, 0.0, name);
  attach_diskx(reg, b, {0.0, 0.0}, radius);
  return b;
}

BodyId add_jonc_body(Registry& reg, double half_length, double half_thickness, MaterialId material, Vec2 position,
                     double angle, const std::string& name) {
  const RoundMass m = joncx_mass(half_length, half_thickness, density_of(reg, material, "JONCx"));
  const BodyId b = add_round_body(reg, m, material, position, angle, name);
  attach_joncx(reg, b, {0.0, 0.0}, {1.0, 0.0}, half_length, half_thickness);
  return b;
}

}  // namespace nscd
