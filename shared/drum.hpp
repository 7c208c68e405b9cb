// nscd/shared/drum.hpp — the rotating drum (issue #12): polydisperse DISKx grains inside an
// xKSID ring whose rotation the driver imposes, gravity on.
//
//   drum_scene      the ring (centre at the origin) on a body whose three dofs are fixed; the
//                   driver turns it with impose_velocity(reg, drum, Dof::Rot, ω). A rough wall
//                   (bump_radius > 0) carries DISKx bumps of that radius on the same body,
//                   centred on the ring and touching each other, so that the grains cannot roll
//                   along it as on bearings. The inner radius (the ring's, less the bumps') is
//                   set by the fill fraction: R_in = sqrt(Σ r² / (fill × packing)), so that the
//                   settled bed (packing fraction about `packing`) fills `fill` of that disk.
//                   The grains (radii uniform in [r_min, r_max] from the seed, portable draws:
//                   grading.hpp) sit on a triangular lattice of spacing 2.05 r_max, the lowest
//                   lattice sites inside the ring first; the driver lets them settle.
//   bed_angle       the free-surface angle from the bed's centre of mass G: a flat surface cuts
//                   the disk along a chord, and the bed (a circular segment) is symmetric about
//                   the chord's perpendicular bisector, which passes through the drum's centre
//                   O; so G lies on the line through O perpendicular to the surface, and the
//                   surface's inclination equals the angle between OG and the downward
//                   vertical. Exact for a flat surface and a bed of uniform packing fraction;
//                   signed, positive when G lies on the +x side (a drum turning
//                   counter-clockwise lifts its bed on that side).
//   surface_fit_angle  a cross-check: the topmost grain of each column (width 2 r_max) of the
//                   bed's middle 60 % (in x), a least-squares line through their tops; its slope
//                   in degrees (same sign convention).
//   segment_fill    the fill fraction of the circular segment whose centroid is at distance
//                   |OG| from O (flat surface): the bed's area over the disk's, as the
//                   centre-of-mass measure sees it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "nscd/registry/registry.hpp"

namespace nscd::scenes {

struct DrumOptions {
  std::size_t grains = 400;
  std::uint64_t seed = 2012;
  double r_min = 2e-3, r_max = 4e-3;  ///< disk radii (m), uniform in between
  double fill = 0.4;                  ///< the bed's share of the drum's area, in (0, 0.5]
  double packing = 0.82;              ///< the settled bed's packing fraction assumed for R
  double density = 2600.0;            ///< grains (kg/m³)
  double bump_radius = 0.0;           ///< > 0: a rough wall of DISKx bumps of this radius (m)
  bool pentagons = false;             ///< grains: regular POLYG pentagons of circumradius r (PLKDx
                                      ///< on the ring, DKPLx with the bumps) instead of disks
};

struct DrumScene {
  Registry reg;
  std::vector<BodyId> grains;
  BodyId drum;
  MaterialId grain_material, wall_material;
  double radius = 0.0;        ///< the ring's radius R (m); its centre is the origin
  double inner_radius = 0.0;  ///< R less the bumps' radius: the free disk the grains fill (m)
  std::size_t bumps = 0;      ///< DISKx bumps on the drum's body (0: a smooth wall)
};

/// Throws nscd::Error on grains = 0, radii not 0 < r_min <= r_max, fill outside (0, 0.5],
/// packing outside (0, 1), density not > 0, bump_radius < 0, or fewer lattice sites in the ring than grains.
DrumScene drum_scene(const DrumOptions& o);

/// Empty if every grain's centre is finite and its disk inside the ring to within `tolerance`
/// (m); otherwise what is wrong, naming the first grain at fault (the drivers' impossible result).
std::string grains_outside(const DrumScene& d, double tolerance);

struct BedAngle {
  double angle_deg = 0.0;   ///< inclination of the free surface (degrees, > 0: G on the +x side)
  double distance = 0.0;    ///< |OG| (m)
  Vec2 centre_of_mass;      ///< G (m), the drum's centre at the origin
};
/// The centre-of-mass measure (see the file comment); NaN angle when the bed has no mass.
BedAngle bed_angle(const DrumScene& d);

/// How the bed follows the drum: its angular velocity about the drum's centre, Σ m (r × v) /
/// Σ m r² (the drum's ω when it turns as one block with it), and the mean sliding speed |U_T|
/// over the grain–drum contacts that carry a force (0 when the grains roll on the wall or stick).
struct BedMotion {
  double spin = 0.0;       ///< rad/s
  double wall_slip = 0.0;  ///< m/s
  std::size_t wall_contacts = 0;
};
BedMotion bed_motion(const DrumScene& d);

/// The least-squares slope of the column tops (see the file comment), in degrees; NaN when
/// fewer than 3 columns hold grains.
double surface_fit_angle(const DrumScene& d);

/// The fill fraction of the circular segment of a disk of radius R whose centroid lies at
/// `distance` from the disk's centre: (α − sin α) / 2π where the segment of central angle α
/// has its centroid at 4 R sin³(α/2) / (3 (α − sin α)): 0.5 at 4R/3π, 1 at distance 0, tending
/// to 0 as distance → R (clamped there). Throws nscd::Error unless R > 0 and distance >= 0.
double segment_fill(double radius, double distance);

}  // namespace nscd::scenes
