// nscd/shared/samples.hpp — builders of the granular samples used by the examples, the
// validation cases, the tests and the benchmarks.
//
//   add_box(...)                  fixed floor and two fixed side walls (big rectangles).
//   add_pentagons_on_lattice(...) one regular pentagon per diameter, on a rectangular lattice,
//                                 orientations drawn from a seed.
//   paper_sample(...)             the paper's 724 pentagons (grading.hpp) in a box, on a
//                                 lattice: loose (no contact at start) or packed (overlapping
//                                 neighbours, many contacts).
//   pentagon_field(...)           n equal pentagons on a square lattice, no walls (benchmarks).
//
// Geometry of paper_sample (d_max = 2 cm, the largest diameter of the grading):
//   * box width 1.0 m (default). The grains cover A = Σ n_k · (5/8) d_k² sin 72° ≈ 0.0826 m²
//     (a regular pentagon of circumscribed diameter d has area (5/8) d² sin 72°); settled at a
//     packing fraction near 0.8 they form a layer A / (0.8 · 1.0 m) ≈ 10 cm thick, the
//     thickness of the Schneebeli sample of the reference experiment (paper §4.1).
//   * lattice: square, pitch = pitch_factor × d_max. Loose: factor 1.1, so two grains never
//     come closer than 0.1 d_max = 2 mm, above the default alert distance (1.25 mm): detection
//     finds no contact. Packed: factor 0.8, below the grain size, so neighbouring pentagons
//     overlap depending on their sizes and orientations: many contacts, some double
//     (edge–edge); seed 2006 gives 208 pairs in contact, 241 points, 33 double contacts,
//     deepest overlap 2.9 mm (two 2 cm grains, inradius sum 1.62 cm > 1.6 cm, always overlap;
//     two 1 cm grains never touch). The pitch sets how many columns fit in the box (62).
//   * clearance c = 0.1 d_max between the lattice and the walls / floor, for both variants, so
//     that no grain touches the box at start.
//   * box height = top of the highest lattice row + c: the whole initial arrangement stands
//     between the walls (loose, width 1.0 m: 45 columns × 17 rows, height 0.376 m). The top is
//     open.
//   * walls 5 cm thick (any value > 0 works: they are fixed and only their inner faces matter).
//   * material "ballast", density 2367 kg/m³; walls "wall", same density (irrelevant: fixed);
//     default contact law IQS_CLB with μ = 0.5 (paper §3: restitution 0, friction 0.5).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "nscd/registry/registry.hpp"
#include "nscd/shared/grading.hpp"

namespace nscd::scenes {

inline constexpr double kPaperDensity = 2367.0;      ///< kg/m³ (paper §3)
inline constexpr double kPaperFriction = 0.5;        ///< μ (paper §3)
inline constexpr double kPaperBoxWidth = 1.0;        ///< m, see the header comment
inline constexpr double kWallThickness = 0.05;       ///< m
inline constexpr double kLoosePitchFactor = 1.1;     ///< lattice pitch / d_max, no contact
inline constexpr double kPackedPitchFactor = 0.8;    ///< lattice pitch / d_max, many contacts
inline constexpr double kClearanceFactor = 0.1;      ///< gap lattice–walls / d_max
inline constexpr std::uint64_t kDefaultSeed = 2006;

struct BoxWalls {
  BodyId floor, left, right;
};

/// A fixed floor and two fixed side walls, rectangles `wall_thickness` thick: the floor's top
/// face is y = 0 and spans x in [−t, width + t]; the walls' inner faces are x = 0 and
/// x = width, from y = −t up to y = height. Bodies named "floor", "left wall", "right wall",
/// fixed with fix_body, their POLYGs marked big (out of the broad-phase grid). Throws
/// nscd::Error unless width, height and wall_thickness are finite and > 0.
BoxWalls add_box(Registry& reg, MaterialId material, double width, double height, double wall_thickness);

/// The same box with JONCx walls, LMGC90's usual ones (a segment thickened by `half_thickness`,
/// round ends): the floor's flat face is y = 0 over x in [−2b, width + 2b], the side walls'
/// flat faces x = 0 and x = width from y = −2b to height (b = half_thickness), so that grains see
/// the faces of add_box(..., 2b). Fixed, named as add_box's. Same errors.
BoxWalls add_jonc_box(Registry& reg, MaterialId material, double width, double height, double half_thickness);

struct LatticeSpec {
  double x0 = 0.0, y0 = 0.0;  ///< centre of the first site (m)
  int columns = 1;            ///< sites per row, > 0
  double pitch_x = 0.0;       ///< distance between columns (m), > 0
  double pitch_y = 0.0;       ///< distance between rows (m), > 0
  std::uint64_t seed = kDefaultSeed;  ///< orientations uniform in [0, 2π/5)
};

/// One regular pentagon per diameter (circumscribed, m), grain i at site i: rows filled left
/// to right, bottom to top, site i at (x0 + (i mod columns)·pitch_x, y0 + (i div columns)·pitch_y).
/// Body angle = a random orientation in [0, 2π/5) (a pentagon's symmetry period). Bodies are
/// named "grain <i>" (i counted from 0 in this call). Returns the new bodies in order.
std::vector<BodyId> add_pentagons_on_lattice(Registry& reg, MaterialId material, std::span<const double> diameters,
                                             const LatticeSpec& lattice);

/// A scene: the registry and what the builder knows about it.
struct Scene {
  Registry reg;
  MaterialId grain_material, wall_material;  ///< wall_material invalid when there is no box
  BoxWalls walls;                            ///< invalid ids when there is no box
  std::vector<BodyId> grains;
  double box_width = 0.0, box_height = 0.0;  ///< 0 when there is no box
  LatticeSpec lattice;                       ///< where the grains were placed
};

struct SampleOptions {
  std::uint64_t seed = kDefaultSeed;        ///< grading shuffle and orientations
  std::size_t grains = 0;                   ///< 0: the paper's 724; n > 0: paper_grading(n)
  double box_width = kPaperBoxWidth;        ///< m
  double wall_thickness = kWallThickness;   ///< m
  double pitch_factor = kLoosePitchFactor;  ///< lattice pitch / d_max, > 0
};

/// The paper's grading in a box on a square lattice (see the header comment). Throws
/// nscd::Error on a non-positive size or factor, or a box narrower than one grain plus the
/// clearances.
Scene paper_sample(const SampleOptions& opt);
/// The box width that gives n grains of the paper's grading the layer depth of the paper's
/// sample (724 grains in 1 m): kPaperBoxWidth × n / 724, but at least one lattice column
/// (d_max + 2 clearances = 2.4 cm), so that a very small n still fits. Throws nscd::Error
/// for n = 0.
double scaled_box_width(std::size_t n);

/// Loose lattice (pitch 1.1 d_max): no contact at start.
Scene paper_sample_loose(std::uint64_t seed = kDefaultSeed);
/// Packed lattice (pitch 0.8 d_max): neighbours overlap slightly, many contacts.
Scene paper_sample_packed(std::uint64_t seed = kDefaultSeed);

/// n equal pentagons of circumscribed diameter `diameter` on a square lattice of `pitch`,
/// ceil(√n) columns, first site at (pitch/2, pitch/2), random orientations from `seed`, no
/// walls, same material and law as paper_sample. A pentagon's support distance ranges over
/// [0.809, 1] × d/2, so a pitch in (0.809 d, d) makes neighbours touch or overlap a little
/// depending on their orientations. With d = 1 cm, pitch 0.9 cm and the default alert
/// (1.25 mm), 700 grains give 1.9 pairs in contact and 2.5 contact points per grain (each
/// grain touches ~3.8 of its 4 lattice neighbours), deepest overlap 0.8 mm.
Scene pentagon_field(std::size_t n, double diameter, double pitch, std::uint64_t seed = kDefaultSeed);

/// Sets every body moving toward the bodies' centroid c (the mean of their centres):
/// v_i = −rate (x_i − c), spins untouched. With pentagon_field and rate 0.1 /s, the compressed
/// field of bench_nlgs and the colored-order tests. Does nothing on an empty registry.
void converge_to_centroid(Registry& reg, double rate);

}  // namespace nscd::scenes
