// nscd/shared/biaxial.hpp — the biaxial test of a disk packing (issue #12): polydisperse DISKx
// grains in a rectangle of four JONCx walls, no gravity.
//
//   biaxial_box     the grains on a square lattice (spacing 2.1 r_max, radii uniform in
//                   [r_min, r_max] from the seed, portable draws: grading.hpp), about `aspect`
//                   times taller than wide; the walls' inner faces on x = 0, x = W, y = 0, y = H,
//                   each a JONCx of half-thickness r_max long enough to keep the corners closed
//                   while the sample deforms. The bottom and left walls are fixed; the right and
//                   top walls move along their normal only (the drives are the driver's).
//   wall_state      the sample's inner width and height from the walls' positions, and the
//                   stresses the grains exert on the top and right walls: σ₁ = F_top / W,
//                   σ₃ = F_right / H (N/m per metre of wall: Pa in 2D), from the last step's
//                   contact forces.
//   mobilized_friction  sin φ = (σ₁ − σ₃) / (σ₁ + σ₃): the Mohr–Coulomb friction angle the
//                   sample mobilizes (no cohesion), in degrees.
#pragma once

#include <cstdint>
#include <vector>

#include "nscd/registry/registry.hpp"

namespace nscd::scenes {

struct BiaxialOptions {
  std::size_t grains = 2000;
  std::uint64_t seed = 2012;
  double r_min = 2e-3, r_max = 4e-3;  ///< disk radii (m), uniform in between
  double aspect = 2.0;                ///< lattice height / width
  double density = 2600.0;            ///< grains and walls (kg/m³)
};

struct BiaxialBox {
  Registry reg;
  std::vector<BodyId> grains;
  BodyId bottom, top, left, right;
  MaterialId grain_material, wall_material;
  double wall_half_thickness = 0.0;
};

/// Throws nscd::Error on grains = 0, radii not 0 < r_min <= r_max, aspect or density not > 0.
BiaxialBox biaxial_box(const BiaxialOptions& o);

struct WallState {
  double width = 0.0, height = 0.0;  ///< inner dimensions (m)
  double sigma1 = 0.0, sigma3 = 0.0; ///< stresses on the top and right walls (Pa = N/m per m)
};
WallState wall_state(const BiaxialBox& b);

/// asin((σ₁ − σ₃) / (σ₁ + σ₃)) in degrees (0 when σ₁ + σ₃ <= 0).
double mobilized_friction_deg(double sigma1, double sigma3);

/// Σ π r² of the grains / (W H): the packing fraction of the sample.
double biaxial_packing_fraction(const BiaxialBox& b, const WallState& w);

}  // namespace nscd::scenes
