// nscd/shared/biaxial.hpp — the biaxial test of a disk packing (issue #12): polydisperse DISKx
// grains in a rectangle of four JONCx walls, no gravity.
//
//   biaxial_box     the grains (disks, or regular pentagons) on a square lattice (spacing 2.1 r_max, radii uniform in
//                   [r_min, r_max] from the seed, portable draws: grading.hpp), about `aspect`
//                   times taller than wide; the walls' inner faces on x = 0, x = W, y = 0, y = H,
//                   each a JONCx of half-thickness r_max long enough to keep the corners closed
//                   while the sample deforms. The bottom and left walls are fixed; the right and
//                   top walls move along their normal only (the drives are the driver's).
//   hexagonal_biaxial_box  equal disks on a hexagonal lattice between the same walls: the
//                   ordered packing whose strength is known in closed form (Rowe 1962).
//   wall_state      the sample's inner width and height from the walls' positions, and the
//                   stresses the grains exert on the top and right walls: σ₁ = F_top / W,
//                   σ₃ = F_right / H (N/m per metre of wall: Pa in 2D), from the last step's
//                   contact forces.
//   internal_stress the grains' mean stress from their contact forces (the internal moment
//                   tensor, Love–Weber): σ = −(1/(W H)) Σ_grains Σ_their contacts f ⊗ ℓ, ℓ from the
//                   grain's centre to the contact point, compression positive; a cross-check of
//                   the wall stresses that sees the whole sample, not its boundary.
//   StressAverage   the time average of these stresses over the steps of an output row: the
//                   mean of the step forces weighted by dt, i.e. the walls' impulse over the row
//                   divided by its duration (the momentum balance holds at every sweep of NLGS,
//                   so the impulse over many steps is resolved even where one step's is not).
//   mobilized_friction  sin φ = (σ₁ − σ₃) / (σ₁ + σ₃): the Mohr–Coulomb friction angle the
//                   sample mobilizes (no cohesion), in degrees.
//   friction_angles the peak (the largest running mean of φ over 5 rows, past a strain) and the
//                   residual (the mean of φ over the rows at strain >= a threshold, with its spread).
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
  double density = 2600.0;            ///< grains (kg/m³)
  double wall_density = 2600.0;       ///< walls (kg/m³): sets the mass of the two moving walls
  bool pentagons = false;             ///< grains: regular POLYG pentagons of circumradius r, orientations
                                      ///< uniform (drawn after each radius from the same stream), instead of disks
};

struct BiaxialBox {
  Registry reg;
  std::vector<BodyId> grains;
  std::vector<double> radius;  ///< of each grain: a disk's radius, a polygon's circumradius (m)
  double solid_area = 0.0;     ///< Σ of the grains' areas (m²)
  BodyId bottom, top, left, right;
  MaterialId grain_material, wall_material;
  double wall_half_thickness = 0.0;
};

/// Throws nscd::Error on grains = 0, radii not 0 < r_min <= r_max, aspect or density not > 0.
BiaxialBox biaxial_box(const BiaxialOptions& o);

/// Equal disks on a hexagonal (triangular) lattice, one lattice direction horizontal: rows
/// alternate `columns` and `columns` − 1 disks, every disk touching its neighbours, the long rows
/// touching the side walls; the same walls as biaxial_box. Under vertical compression the
/// lattice can only fail by sliding at its inclined contacts: the analytic case of the biaxial
/// test (validation/biaxial_lattice.cpp, docs/theory.md §5.4).
struct HexagonalOptions {
  std::size_t columns = 10, rows = 11;  ///< disks in the long rows; rows (>= 2 each)
  double radius = 5e-3;                 ///< m
  double density = 2600.0, wall_density = 2600.0;
};
/// Throws nscd::Error on columns or rows < 2, radius or densities not finite and > 0.
BiaxialBox hexagonal_biaxial_box(const HexagonalOptions& o);

struct WallState {
  double width = 0.0, height = 0.0;  ///< inner dimensions (m)
  double sigma1 = 0.0, sigma3 = 0.0; ///< stresses on the top and right walls (Pa = N/m per m)
};
WallState wall_state(const BiaxialBox& b);

/// A symmetric 2D stress (Pa), compression positive.
struct Stress2 {
  double xx = 0.0, yy = 0.0, xy = 0.0;
  double major() const;  ///< the larger principal value
  double minor() const;  ///< the smaller principal value
};
/// −(1/(W H)) Σ f ⊗ ℓ over the grains' contacts (symmetrized), the last step's forces. With
/// `only` (one flag per body, by body index), the sum runs over the flagged grains alone: the
/// stress of a part of the sample, still over the whole box's area.
Stress2 internal_stress(const BiaxialBox& b, const WallState& w, const std::vector<std::uint8_t>* only = nullptr);

/// Time average of the wall stresses σ₁, σ₃ and of the internal stress over a row's steps.
class StressAverage {
 public:
  /// Adds one step of duration dt > 0 (throws nscd::Error on dt not > 0 or a non-finite value).
  void add(double dt, double sigma1, double sigma3, const Stress2& internal = {});
  double duration() const { return time_; }
  std::size_t steps() const { return steps_; }
  double sigma1() const;     ///< Σ dt σ₁ / Σ dt (throws nscd::Error when no step was added)
  double sigma3() const;
  Stress2 internal() const;
  void clear() { *this = StressAverage{}; }

 private:
  double time_ = 0.0, s1_ = 0.0, s3_ = 0.0;
  Stress2 in_;
  std::size_t steps_ = 0;
};

/// asin((σ₁ − σ₃) / (σ₁ + σ₃)) in degrees (0 when σ₁ + σ₃ <= 0).
double mobilized_friction_deg(double sigma1, double sigma3);

struct FrictionAngles {
  double peak = 0.0, peak_strain = 0.0;  ///< degrees, and the strain of the row where it is
  double residual = 0.0, spread = 0.0;   ///< mean and standard deviation (degrees); NaN, 0 with no row
  std::size_t residual_rows = 0;
};
/// Peak: the largest running mean of phi over 5 rows (fewer at the ends) of the rows with strain
/// >= peak_from, the others left out (the first rows hold the wall's start-up transient); residual: the
/// mean of phi over the rows with strain >= residual_from. Throws nscd::Error on sizes that
/// differ, no row, or no row at strain >= peak_from.
FrictionAngles friction_angles(const std::vector<double>& strain, const std::vector<double>& phi, double residual_from,
                               double peak_from = 0.0);

/// Σ of the grains' areas / (W H): the packing fraction of the sample.
double biaxial_packing_fraction(const BiaxialBox& b, const WallState& w);

}  // namespace nscd::scenes
