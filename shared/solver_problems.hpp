// nscd/shared/solver_problems.hpp — hand-made hard contact problems for the solver studies
// (examples/solver_comparison): scenes whose first step is a difficult frictional contact
// problem, built as ordinary registries so that they can be stepped like any scene and
// dumped with MoreauJean::local_problem().
//
//   block_column(...)   N rectangular blocks stacked exactly (gaps 0) on a fixed floor. Face on
//                       face, so 2 contact points per interface: 2N contacts, 4N unknowns for
//                       3N dofs — W is rank-deficient (the split of an interface's load between
//                       its two points is not unique). Every block falls freely at −h g, so
//                       q ≠ 0 at the floor only: the whole weight must travel up the column
//                       through N interfaces, Gauss–Seidel's worst case (≈ N² sweeps).
//   pentagon_pile(...)  a triangular heap of regular pentagons (rows of base, base − 1, ..., 1
//                       grains) on a triangular lattice of pitch 0.9 d on a fixed floor, random
//                       orientations from a seed, the bottom row sunk 20 µm into the floor.
//                       Neighbours overlap (by up to 0.1 d) or not depending on their
//                       orientations: an irregular network of vertex–edge contacts under
//                       gravity. The alert distance is 0, so only overlapping pairs are
//                       contacts: with a positive alert, the open pairs within it would enter q
//                       with their IQS_CLB shift g/(θh) (up to 12.5 m/s at 1.25 mm, against
//                       h g = 2 mm/s), and the residual over ||q|| would start near 1e-4 at r = 0.
//                       (Stepped, such a scene finds contacts only once they overlap.)
//   brick_box(...)      rectangular bricks in a running-bond pattern (rows offset by half a
//                       brick, half bricks at the ends) filling a box of fixed walls exactly:
//                       every brick touches its neighbours, the two bricks below it and the
//                       walls face to face (2 points per interface).
//   lmgc90_deposit(...) the LMGC90 comparison deposit, the scene of examples/deposit
//                       (`lmgc90_deposit_case`): 700 pentagons on a lattice in a box.
//   problem_of(...)     the contact problem of the next step of a scene.
//
// Contact points with the defaults (IQS_CLB, μ = 0.5, h = 2e-4 s, alert 1.25 mm but 0 for the
// pile; solver_comparison prints them): block_column 2000 (1000 blocks); pentagon_pile 1048
// (base 34, 595 grains); brick_box 988 (16 rows of 10 bricks: 494 face–face interfaces).
#pragma once

#include <cstdint>

#include "nscd/registry/registry.hpp"
#include "nscd/shared/samples.hpp"
#include "nscd/solvers/local_problem.hpp"
#include "nscd/solvers/moreau_jean.hpp"

namespace nscd::scenes {

/// Time step, θ and alert distance of every scene below (those of the deposit studies).
inline constexpr double kProblemDt = 2e-4;
inline constexpr double kProblemAlert = 1.25e-3;

struct ColumnOptions {
  int blocks = 1000;          ///< N, > 0
  double width = 0.2;         ///< m
  double height = 0.1;        ///< m
  double density = 2000.0;    ///< kg/m³
  double mu = 0.5;
};

/// The column (see the header comment): a fixed floor 1 m wide (top face y = 0, marked big)
/// and blocks "block <k>", k = 0 at the bottom, bottom face of block k at y = k·height.
Registry block_column(const ColumnOptions& o = {});

struct PileOptions {
  int base = 34;              ///< grains in the bottom row, > 0; base(base + 1)/2 grains in all
  double diameter = 0.02;     ///< circumscribed diameter d (m)
  double pitch_factor = 0.9;  ///< lattice pitch / d, in (0.5, 2)
  double density = kPaperDensity;
  double mu = 0.5;
  std::uint64_t seed = kDefaultSeed;  ///< orientations
  double alert = 0.0;         ///< m: 0 keeps only the overlapping pairs (see the header comment)
  double floor_overlap = 2e-5;  ///< m: how deep the bottom row sits in the floor (found at alert 0)
};

/// The heap (see the header comment): floor "floor" (big), grains "grain <i>", row by row.
Registry pentagon_pile(const PileOptions& o = {});

struct BrickOptions {
  int columns = 10;           ///< whole bricks per row (odd rows: columns − 1 whole + 2 halves)
  int rows = 16;              ///< > 0
  double width = 0.2;         ///< brick width (m)
  double height = 0.1;        ///< brick height (m)
  double density = 2000.0;
  double mu = 0.5;
};

/// The brick packing (see the header comment): box of inner width columns·width (add_box,
/// walls as high as the packing), bricks "brick <row>.<k>".
Registry brick_box(const BrickOptions& o = {});

/// The LMGC90 comparison deposit of examples/deposit (the same scene, built the same way):
/// 700 regular pentagons, circumradius uniform in [12.5, 25] mm from `seed`, density 2700, on
/// a 28 × 25 lattice of pitch 55 mm in a 1.54 m box; IQS_CLB μ = 0.5; h = 2e-4 s, θ = 0.5,
/// alert 1.25 mm.
Scene lmgc90_deposit(std::uint64_t seed = kDefaultSeed);

/// The contact problem of the scene's next step: a fresh MoreauJean with `options` runs
/// begin_step, detect and prepare, and returns local_problem(). Nothing of the scene's state
/// (positions, velocities, time) changes; reg.contacts holds the step's contacts afterwards.
FrictionProblem2D problem_of(Registry& reg, const StepperOptions& options = {});

/// The same on a running stepper (between steps): begin_step, detect, prepare, then
/// local_problem(). The caller continues the step with solve() and end_step().
FrictionProblem2D problem_of(MoreauJean& stepper);

}  // namespace nscd::scenes
