// nscd/shared/tiling.hpp — big scenes made of copies of a settled sample, side by side.
//
// A deposit of 70,000 grains takes hours on a small machine; for cost measurements a settled
// sample of N grains in a box of width W (e.g. `deposit --grains 7000`'s final_state.nscd) is
// copied K times along x into a box of width K·W: K·N grains, the same layer depth, packings
// already at rest. The seams are where two copies' wall-side grains meet: they are as close as
// each was to its wall (overlaps of the order of the settled ones, ~1e-4 m), so the first steps
// after tiling rearrange the seams a little. Body order: the walls, then copy 0's grains in the
// sample's order, copy 1's, ... (each copy keeps the sample's order, so memory locality within
// a copy is the sample's).
#pragma once

#include <cstddef>

#include "nscd/core/registry.hpp"
#include "nscd/shared/samples.hpp"

namespace nscd::scenes {

/// Inner width of the box of a sample built by add_box: the distance between the inner faces
/// of the bodies named "left wall" and "right wall". Throws nscd::Error if either is missing.
double sample_box_width(const Registry& sample);

/// `copies` copies of the free bodies of `sample` (every body that is not driven), copy k
/// shifted by k·W along x (W = sample_box_width), with their velocities, single-POLYG shapes
/// and materials, in a new box (add_box) of width copies·W whose walls are as tall as the
/// highest grain top + 1 cm. Parameters, materials and contact laws are the sample's; the
/// time and step counter start at 0; there is no warm-start memory (run a few steps first).
/// Throws nscd::Error for copies = 0, a sample without the box's walls or without free
/// bodies, or a free body with more than one POLYG.
Scene tile_scene(const Registry& sample, std::size_t copies);

}  // namespace nscd::scenes
