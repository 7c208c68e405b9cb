// nscd/bodies/body_table.hpp — the tables of the bodies module: RBDY2 rigid bodies, their
// boundary conditions, and the materials (density) their masses come from.
//
// Hot per-step state (positions, velocities, inverse masses) in contiguous arrays, cold data
// (names, reference configuration, drives) apart. The functions are in rbdy2.hpp; the registry
// (registry/registry.hpp) holds one BodyTable and one MaterialTable.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "nscd/core/ids.hpp"
#include "nscd/core/time_function.hpp"

namespace nscd {

/// Degrees of freedom of an RBDY2 body, in the order of its velocity vector (vx, vy, ω).
enum class Dof : std::uint8_t { X = 0, Y = 1, Rot = 2 };

/// How a degree of freedom is driven. Free: gravity plus imposed forces; Fixed: velocity 0;
/// Velocity: velocity imposed as v(t); Force: an extra external force f(t) (moment for Rot).
enum class Drive : std::uint8_t { Free, Fixed, Velocity, Force };

struct DofDrive {
  BodyId body;
  Dof dof = Dof::X;
  Drive drive = Drive::Free;
  TimeFunction value;  ///< v(t) for Velocity, f(t) for Force; unused otherwise
};

/// RBDY2 bodies. Hot state indexed by BodyId::index(). The body frame's origin is the body's
/// centre of mass; `angle` rotates body-frame vectors into the world frame.
struct BodyTable {
  // hot: configuration and velocity at the beginning of the step (t_i)
  std::vector<double> x, y, angle;  ///< centre of mass and orientation
  std::vector<double> vx, vy, spin; ///< velocity of the centre of mass and angular velocity
  // hot: inverse mass seen by the contact solver per dof (0 for Fixed / Velocity dofs)
  std::vector<double> inv_mass_x, inv_mass_y, inv_inertia;
  // cold
  std::vector<double> mass, inertia;        ///< true mass and inertia about the centre of mass
  std::vector<double> x0, y0, angle0;       ///< reference configuration (for displacements)
  std::vector<MaterialId> material;
  std::vector<std::string> name;
  std::vector<std::uint8_t> is_driven;      ///< 1 if any dof has a Drive other than Free
  std::vector<DofDrive> drives;             ///< boundary conditions, few entries

  std::size_t size() const { return x.size(); }
  bool empty() const { return x.empty(); }
};

struct MaterialTable {
  std::vector<std::string> name;
  std::vector<double> density;  ///< kg/m³ (times the unit thickness: kg/m² of section)
  std::size_t size() const { return name.size(); }
};

}  // namespace nscd
