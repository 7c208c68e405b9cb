// nscd/shared/ballast.hpp — the ballast settlement scene (Saussine et al. 2006, §2.9, §3, §4):
// graded pentagons in a box whose floor is a deformable sublayer, and a sleeper on top.
//
// Geometry (all options in BallastOptions, defaults below):
//   * box: fixed side walls (inner faces x = 0 and x = width) and a fixed ground body (the
//     box floor, top face y = 0) that anchors the springs;
//   * sublayer: `pads` rigid rectangles side by side (height pad_height, by default the springs'
//     length, so that a pad sinking as far as its spring allows stays beside its neighbours' sides; gaps pad_gap between
//     them and to the walls, larger than the alert distance so pads never interact with each
//     other), each tied to the ground by one VOIGT_ROD spring of length spring_length, from a
//     ground anchor straight below the pad's centre to the pad's bottom centre. Pads are guided
//     vertically: their horizontal and rotational dofs are fixed (kinematic), only y moves;
//   * grains: the paper's grading (361/242/121 pentagons of 1/1.5/2 cm, ρ = 2367 kg/m³; each
//     count times grading_fraction, at least 1, for smaller samples) on a
//     loose square lattice above the pads (pitch 1.1 × 2 cm: no contact at start), seeded
//     shuffle and orientations; they are deposited by the driver under gravity;
//   * sleeper (place_sleeper, after the deposit): an aluminium rectangle (ρ = 2700) centred
//     on the box, its bottom (or the bottom of its bars) 1 mm above the highest grain under its
//     footprint; optionally square bars fixed under its lower face (paper §4.1: "to improve its
//     resistance to lateral sliding").
//   * contact law IQS_CLB, μ = 0.5 between every pair of materials (paper §3, e = 0).
// Per unit thickness (2D): masses in kg/m, forces in N/m (docs/theory.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "nscd/shared/samples.hpp"

namespace nscd::scenes {

struct BallastOptions {
  std::uint64_t seed = kDefaultSeed;
  double box_width = kPaperBoxWidth;  ///< m
  double pitch_factor = kLoosePitchFactor;
  double mu = kPaperFriction;
  double grading_fraction = 1.0;      ///< scales every class count of the paper's grading (small samples)
  // sublayer
  int pads = 50;
  /// m: as deep as the springs are long, so that no pad can sink below its neighbour's sides and
  /// let a grain under it, whatever the load and the sample's width (the paper's elastomer is
  /// continuous); a pad weighs what a 1 cm pad of the paper's density does (pad_density below)
  double pad_height = 0.1;
  double pad_gap = 2e-3;              ///< m, between pads and to the walls (> alert)
  double pad_density = kPaperDensity * 0.01 / 0.1;  ///< kg/m³: the mass of a 1 cm pad of the paper's density
  double k = 4100.0;                  ///< N/m per spring (paper §4.1)
  double nu = 80.0;                   ///< N·s/m per spring
  double spring_length = 0.1;         ///< L0 (m)
  double eps0 = 0.0;                  ///< prestrain
  // sleeper
  double sleeper_width = 0.15;        ///< m
  double sleeper_height = 0.04;       ///< m
  double sleeper_density = 2700.0;    ///< kg/m³ (aluminium)
  int bars = 3;                       ///< square bars under the sleeper (0: none)
  double bar_size = 0.006;            ///< m
};

/// Throws nscd::Error naming the first option out of range.
void validate(const BallastOptions& o);

struct BallastScene {
  Scene scene;                 ///< registry, grains, walls (walls.floor is the spring ground)
  std::vector<BodyId> pads;
  std::vector<LinkId> springs;
  BodyId sleeper;              ///< invalid until place_sleeper
  MaterialId pad_material, sleeper_material;
  double largest_diameter = 0.0;
};

/// Box, sublayer and grains on their start lattice (see the header comment).
BallastScene ballast_sample(const BallastOptions& o);

/// Places the sleeper on the settled layer (see the header comment) and returns it.
BodyId place_sleeper(BallastScene& s, const BallastOptions& o);

/// Finds the pads, springs and sleeper of a scene loaded from a checkpoint by their names
/// ("pad <i>", "sleeper") and the grains ("grain <i>"). Throws if the scene is not a ballast one.
BallastScene recognise_ballast(Registry&& reg);

/// A grain that has left the layer through the sublayer: its centre below the lowest pad's top
/// face (a grain resting on a pad has its centre at least 0.4 d above that face, so none can be
/// there without passing through or between the pads, e.g. into the space a pad sinking far
/// below its neighbour opens: docs/extremes.md). Returns a message naming the grain, or "".
std::string grain_below_sublayer(const BallastScene& s);

/// Multiplies every spring's stiffness by `factor`, adjusting its prestrain so that its force
/// at the current length is unchanged (the sample does not jump when the stiffness changes).
void scale_sublayer_stiffness(BallastScene& s, double factor);

}  // namespace nscd::scenes
