// nscd/shared/tiling.hpp — big scenes made of copies of a settled sample, side by side.
//
// A deposit of 70,000 grains takes hours on a small machine; for cost measurements a settled
// sample of N grains in a box of width W (e.g. `deposit --grains 7000`'s final_state.nscd) is
// copied K times along x into a box of width K·W: K·N grains, the same layer depth, packings
// already at rest.
//
// The seams, where copy k's right-wall side meets copy k+1's left-wall side (Seams):
//   Walls (default)  a fixed wall 1 cm thick between the copies, made of a column of 1 cm
//                    squares (small polygons: they stay in the broad-phase grid; one big wall
//                    per seam would be tested against every grain, O(N²) in all). Each copy
//                    then sits in its own compartment exactly as it settled: the scene is at
//                    rest from the first step.
//   Plain            the copies touch. Two packings shaped by flat walls do not fit each other:
//                    the grains slide into the voids and the seams collapse for hundreds of
//                    steps (a 700-grain sample: 2 copies still needed ~400 sweeps a step after
//                    100 steps, 3 copies after 400 steps, against 10 for the sample alone).
//   Mirrored         every other copy reflected (x -> W - x), so that a seam meets the mirror
//                    image of the same wall side. Better (2 copies: 10 sweeps after 100 steps)
//                    but not enough: a grain and its image exert no vertical friction on each
//                    other, and 3 or 10 copies still needed ~150 sweeps a step after 100 steps.
//
// Body order (TileOrder): the walls, then the grains copy by copy (each copy in the sample's
// order: memory locality within a copy is the sample's), or in rows across the whole width,
// as a real wide deposit numbers them; then the seam walls.
#pragma once

#include <cstddef>

#include "nscd/registry/registry.hpp"
#include "nscd/shared/samples.hpp"

namespace nscd::scenes {

/// Inner width of the box of a sample built by add_box: the distance between the inner faces
/// of the bodies named "left wall" and "right wall". Throws nscd::Error if either is missing.
double sample_box_width(const Registry& sample);

enum class Seams { Walls, Plain, Mirrored };
/// Body order of the grains: Copies (copy 0's grains in the sample's order, then copy 1's, ...)
/// or Rows (bands one grain diameter high, bottom to top, each left to right over the whole
/// width: the order of a wide deposit's lattice, whose grains fall nearly straight down).
enum class TileOrder { Copies, Rows };
inline constexpr double kSeamWallThickness = 0.01;  ///< m, Seams::Walls

/// `copies` copies of the free bodies of `sample` (every body that is not driven), copy k
/// shifted by k·P along x (P = W = sample_box_width, or W + 1 cm with seam walls) and, with
/// Seams::Mirrored, copies 1, 3, 5, ... reflected about their middle (x -> W - x, shapes,
/// angles, vx and spin reflected), with their velocities, single-POLYG shapes and materials,
/// in a new box (add_box) of width (copies − 1)·P + W whose walls are as tall as the highest
/// grain top + 1 cm; with Seams::Walls, a fixed body "seam wall <k>" between copies k and k+1
/// (after the grains in the body order). Parameters, materials and contact laws are the
/// sample's; the time and step counter start at 0; there is no warm-start memory (run a few
/// steps first). Throws nscd::Error for copies = 0, a sample without the box's walls or
/// without free bodies, or a free body with more than one POLYG.
Scene tile_scene(const Registry& sample, std::size_t copies, Seams seams = Seams::Walls, TileOrder body_order = TileOrder::Copies);

}  // namespace nscd::scenes
