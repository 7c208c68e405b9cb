// nscd/contactors/round_shapes.hpp — mass properties of the round contactors (issue #12):
// DISKx, a disk of radius r, and JONCx, LMGC90's "jonc" (a segment of half-length a thickened
// by a half-thickness b: a rectangle 2a × 2b with a half-disk of radius b on each end).
//
// Per unit thickness, as everywhere in nscd (docs/theory.md): mass in kg/m, inertia about the
// centre of mass in kg·m²/m, for a density ρ in kg/m³.
//   DISKx: m = ρ π r²,  I = m r² / 2.
//   JONCx: rectangle m_r = 4 ρ a b, I_r = m_r (4a² + 4b²) / 12; each half-disk m_h = ρ π b² / 2
//          has its centroid at c = 4b / (3π) from its flat side, I_h = m_h b² / 2 about the centre
//          of its flat side, hence m_h (b²/2 − c² + (a + c)²) about the capsule's centre (parallel
//          axis twice). With a = 0 it is the disk; with b → 0 the rod m (2a)² / 12.
#pragma once

#include <string>

#include "nscd/registry/registry.hpp"

namespace nscd {

struct RoundMass {
  double mass = 0.0;
  double inertia = 0.0;  ///< about the centre of mass
};

/// Throws nscd::Error unless radius > 0 and rho > 0 (finite).
RoundMass diskx_mass(double radius, double rho);
/// Throws nscd::Error unless half_length >= 0, half_thickness > 0 and rho > 0 (finite).
RoundMass joncx_mass(double half_length, double half_thickness, double rho);

/// Attaches a DISKx (centre `offset` in the body frame) to an existing body, its mass unchanged.
/// Throws nscd::Error naming the body unless the body exists and radius > 0 (finite).
DiskxId attach_diskx(Registry& reg, BodyId body, Vec2 offset, double radius);
/// Attaches a JONCx: the segment offset ± half_length · axis (axis: any non-zero vector of the
/// body frame, normalized here), thickened by half_thickness > 0 (half_length >= 0).
JoncxId attach_joncx(Registry& reg, BodyId body, Vec2 offset, Vec2 axis, double half_length, double half_thickness);
/// Attaches an xKSID: the hole of radius > 0 centred at `offset`; what touches it stays inside.
XksidId attach_xksid(Registry& reg, BodyId body, Vec2 offset, double radius);

/// A body made of one DISKx centred on its centre of mass, mass and inertia from the material's
/// density (diskx_mass).
BodyId add_disk_body(Registry& reg, double radius, MaterialId material, Vec2 position, const std::string& name = "");
/// A body made of one JONCx along the body's x axis, rotated by `angle`, mass and inertia from
/// the material's density (joncx_mass). Walls are usually fixed afterwards (fix_body).
BodyId add_jonc_body(Registry& reg, double half_length, double half_thickness, MaterialId material, Vec2 position,
                     double angle = 0.0, const std::string& name = "");

}  // namespace nscd
