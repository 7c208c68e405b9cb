// nscd/bodies/rbdy2.cpp — see rbdy2.hpp.
#include "nscd/bodies/rbdy2.hpp"

#include <algorithm>
#include <cmath>

#include "nscd/core/error.hpp"
#include "nscd/core/thread_share.hpp"

namespace nscd {
namespace {

void check_body(const Registry& reg, BodyId b, const char* what) {
  if (!b.valid() || b.index() >= reg.bodies.size())
    throw Error(std::string(what) + ": unknown body id " + std::to_string(b.value));
}

// Recomputes the solver's inverse masses and the driven flag of one body from its drives.
void refresh(Registry& reg, BodyId b) {
  auto& t = reg.bodies;
  const std::size_t i = b.index();
  double inv[3] = {1.0 / t.mass[i], 1.0 / t.mass[i], 1.0 / t.inertia[i]};
  bool driven = false;
  for (const auto& d : t.drives) {
    if (d.body != b) continue;
    driven = true;
    if (d.drive == Drive::Fixed || d.drive == Drive::Velocity) inv[static_cast<int>(d.dof)] = 0.0;
  }
  t.inv_mass_x[i] = inv[0];
  t.inv_mass_y[i] = inv[1];
  t.inv_inertia[i] = inv[2];
  t.is_driven[i] = driven ? 1 : 0;
}

void set_drive(Registry& reg, BodyId b, Dof dof, Drive drive, TimeFunction f) {
  check_body(reg, b, "boundary condition");
  auto& d = reg.bodies.drives;
  d.erase(std::remove_if(d.begin(), d.end(), [&](const DofDrive& x) { return x.body == b && x.dof == dof; }), d.end());
  if (drive != Drive::Free) d.push_back(DofDrive{b, dof, drive, std::move(f)});
  refresh(reg, b);
}

}  // namespace

BodyId add_body(Registry& reg, const RigidBodySpec& s) {
  auto& t = reg.bodies;
  const std::string who = "body " + std::to_string(t.size()) + (s.name.empty() ? "" : " '" + s.name + "'");
  const double all[] = {s.position.x, s.position.y, s.angle, s.velocity.x, s.velocity.y, s.spin, s.mass, s.inertia};
  for (double v : all)
    if (!std::isfinite(v)) throw Error(who + ": position, velocity, mass and inertia must be finite");
  if (!(s.mass > 0.0)) throw Error(who + ": mass must be > 0, got " + std::to_string(s.mass));
  if (!(s.inertia > 0.0)) throw Error(who + ": inertia must be > 0, got " + std::to_string(s.inertia));
  if (s.material.valid() && s.material.index() >= reg.materials.size()) throw Error(who + ": unknown material id");

  t.x.push_back(s.position.x);
  t.y.push_back(s.position.y);
  t.angle.push_back(s.angle);
  t.vx.push_back(s.velocity.x);
  t.vy.push_back(s.velocity.y);
  t.spin.push_back(s.spin);
  t.inv_mass_x.push_back(1.0 / s.mass);
  t.inv_mass_y.push_back(1.0 / s.mass);
  t.inv_inertia.push_back(1.0 / s.inertia);
  t.mass.push_back(s.mass);
  t.inertia.push_back(s.inertia);
  t.x0.push_back(s.position.x);
  t.y0.push_back(s.position.y);
  t.angle0.push_back(s.angle);
  t.material.push_back(s.material);
  t.name.push_back(s.name);
  t.is_driven.push_back(0);
  return BodyId(static_cast<std::uint32_t>(t.size() - 1));
}

void set_mass(Registry& reg, BodyId b, double mass, double inertia) {
  check_body(reg, b, "set_mass");
  if (!(mass > 0.0) || !(inertia > 0.0) || !std::isfinite(mass) || !std::isfinite(inertia))
    throw Error("set_mass: body " + std::to_string(b.index()) + ": mass and inertia must be finite and > 0");
  reg.bodies.mass[b.index()] = mass;
  reg.bodies.inertia[b.index()] = inertia;
  refresh(reg, b);
}

void fix_dof(Registry& reg, BodyId b, Dof dof) { set_drive(reg, b, dof, Drive::Fixed, {}); }
void fix_body(Registry& reg, BodyId b) {
  for (Dof d : {Dof::X, Dof::Y, Dof::Rot}) fix_dof(reg, b, d);
}
void impose_velocity(Registry& reg, BodyId b, Dof dof, TimeFunction v) {
  set_drive(reg, b, dof, Drive::Velocity, std::move(v));
}
void impose_force(Registry& reg, BodyId b, Dof dof, TimeFunction f) {
  set_drive(reg, b, dof, Drive::Force, std::move(f));
}
void free_dof(Registry& reg, BodyId b, Dof dof) { set_drive(reg, b, dof, Drive::Free, {}); }

Drive drive_of(const Registry& reg, BodyId b, Dof dof) {
  check_body(reg, b, "drive_of");
  for (const auto& d : reg.bodies.drives)
    if (d.body == b && d.dof == dof) return d.drive;
  return Drive::Free;
}

BodyForce external_force(const Registry& reg, BodyId b, double t) {
  check_body(reg, b, "external_force");
  const auto& tb = reg.bodies;
  const std::size_t i = b.index();
  BodyForce f{tb.mass[i] * reg.params.gravity.x, tb.mass[i] * reg.params.gravity.y, 0.0};
  if (!tb.is_driven[i]) return f;
  for (const auto& d : tb.drives) {
    if (d.body != b) continue;
    double* comp = d.dof == Dof::X ? &f.fx : d.dof == Dof::Y ? &f.fy : &f.m;
    if (d.drive == Drive::Force) *comp += d.value(t);
    else *comp = 0.0;  // kinematic dof: no force acts on it
  }
  return f;
}

void apply_imposed_velocities(Registry& reg, double t) {
  auto& tb = reg.bodies;
  for (const auto& d : tb.drives) {
    if (d.drive != Drive::Fixed && d.drive != Drive::Velocity) continue;
    const double v = d.drive == Drive::Fixed ? 0.0 : d.value(t);
    const std::size_t i = d.body.index();
    (d.dof == Dof::X ? tb.vx : d.dof == Dof::Y ? tb.vy : tb.spin)[i] = v;
  }
}

double kinetic_energy(const Registry& reg, int threads) {
  const auto& t = reg.bodies;
  return ordered_sum(t.size(), threads, [&t](std::size_t i) {
    if (t.inv_mass_x[i] == 0.0 && t.inv_mass_y[i] == 0.0 && t.inv_inertia[i] == 0.0) return 0.0;
    return 0.5 * t.mass[i] * (t.vx[i] * t.vx[i] + t.vy[i] * t.vy[i]) + 0.5 * t.inertia[i] * t.spin[i] * t.spin[i];
  });
}

}  // namespace nscd
