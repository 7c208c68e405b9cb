// nscd/bodies/rbdy2.hpp — RBDY2: 2D rigid bodies (LMGC90's name).
//
// A body is a row of Registry::bodies: centre of mass (x, y), orientation angle, velocity
// (vx, vy, spin), mass and inertia about the centre of mass. Mass and inertia are given here
// directly; contactors/polyg.hpp computes them from the body's polygons and a density.
// Boundary conditions act per degree of freedom: Fixed, imposed Velocity v(t), or an imposed
// Force f(t) added to gravity.
#pragma once

#include <string>

#include "nscd/registry/registry.hpp"

namespace nscd {

struct RigidBodySpec {
  std::string name;
  MaterialId material;
  Vec2 position;        ///< centre of mass, world frame
  double angle = 0.0;   ///< orientation (rad)
  Vec2 velocity;        ///< initial velocity of the centre of mass
  double spin = 0.0;    ///< initial angular velocity (rad/s)
  double mass = 0.0;    ///< > 0
  double inertia = 0.0; ///< > 0, about the centre of mass
};

/// Appends a body; throws nscd::Error (naming the body) on non-finite or non-positive data.
BodyId add_body(Registry& reg, const RigidBodySpec& spec);

/// Changes a body's mass and inertia (> 0, finite); the solver's inverse masses follow, kinematic
/// dofs keep 0.
void set_mass(Registry& reg, BodyId body, double mass, double inertia);

/// Boundary conditions. Fixed and Velocity make the dof kinematic (infinite mass for the
/// contact solver); Force adds f(t) to the dof's external force. A later call on the same
/// dof replaces the earlier one.
void fix_dof(Registry& reg, BodyId body, Dof dof);
void fix_body(Registry& reg, BodyId body);
void impose_velocity(Registry& reg, BodyId body, Dof dof, TimeFunction v);
void impose_force(Registry& reg, BodyId body, Dof dof, TimeFunction f);
/// Removes every boundary condition of the body's dof (back to Free).
void free_dof(Registry& reg, BodyId body, Dof dof);

/// The drive of a dof (Free when no condition was set).
Drive drive_of(const Registry& reg, BodyId body, Dof dof);

/// External generalized force on a body at time t: gravity·mass plus imposed forces
/// (components: fx, fy, moment). Kinematic dofs get 0.
struct BodyForce { double fx = 0.0, fy = 0.0, m = 0.0; };
BodyForce external_force(const Registry& reg, BodyId body, double t);

/// Sets the velocity of every kinematic dof to its imposed value at time t (0 for Fixed).
void apply_imposed_velocities(Registry& reg, double t);

/// Kinetic energy ½ m v² + ½ I ω² summed over the bodies that are not fully fixed, on
/// `threads` threads beyond kSumWhole bodies (core/thread_share.hpp: the same bits on any number).
double kinetic_energy(const Registry& reg, int threads = 1);

}  // namespace nscd
