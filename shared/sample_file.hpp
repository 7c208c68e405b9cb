// nscd/shared/sample_file.hpp — grains read from a sample file: the exact sample of another
// code (LMGC90's pre-processor, contrib/lmgc90/deposit_700.py) so that a run of nscd starts
// from the same positions, sizes and orientations (issue #8).
//
// Format: text, one grain per line; '#' starts a comment line, blank lines are skipped.
//   index x y radius theta vx0 vy0 vx1 vy1 ... vx(n-1) vy(n-1)
//   * index      0, 1, 2, ... in order (the file's order is the grains' order)
//   * x y        the centre of mass (m); radius: the circumradius (m), > 0
//   * theta      the orientation (rad), finite; it becomes the body's angle
//   * vx vy      n >= 3 vertices in the global frame (m), counter-clockwise, a strictly convex
//                polygon (validate_polygon's rules), each within the circumradius of the
//                centre (1e-9 relative), their centroid at the centre (1e-6 × radius)
// Numbers are parse_real's (whole token, finite). Every error is an nscd::Error
// "sample file '<file>', line <n>: <rule>". An empty file (no grain) is refused.
#pragma once

#include <filesystem>
#include <span>
#include <vector>

#include "nscd/contactors/polyg.hpp"
#include "nscd/registry/registry.hpp"

namespace nscd::scenes {

/// One grain of a sample file.
struct SampleGrain {
  Vec2 centre;
  double radius = 0.0;
  double theta = 0.0;
  Polygon vertices;       ///< global frame, counter-clockwise
  std::size_t line = 0;   ///< line of the file (for messages)
};

/// Reads and checks a sample file (the rules above). Throws nscd::Error on the first defect.
std::vector<SampleGrain> read_sample_file(const std::filesystem::path& file);

/// Parses the text of a sample file (`file` only names it in messages).
std::vector<SampleGrain> parse_sample_text(std::string text, const std::filesystem::path& file);

/// One rigid body per grain, material `material`, named "grain <i>": the vertices exactly as
/// read, the body angle theta. Returns the bodies in the file's order.
std::vector<BodyId> add_sample_grains(Registry& reg, MaterialId material, std::span<const SampleGrain> grains);

}  // namespace nscd::scenes
