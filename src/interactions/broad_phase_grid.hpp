// nscd/interactions/broad_phase_grid.hpp — the pieces of find_pairs (broad_phase.hpp) that its
// one-thread path (broad_phase.cpp) and its path on threads (broad_phase_threads.cpp) share: a
// scan of the boxes, the grid of tiles it gives, a box's tile, and a box's partners.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "nscd/interactions/broad_phase.hpp"

namespace nscd::broad {

/// The scan of boxes i0 … i1−1 (BoxScan).
inline BoxScan scan_boxes(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, std::size_t i0,
                          std::size_t i1) {
  BoxScan s;
  for (std::size_t i = i0; i < i1; ++i) {
    const Aabb& b = boxes[i];
    s.finite =
        s.finite && std::isfinite(b.xmin) && std::isfinite(b.xmax) && std::isfinite(b.ymin) && std::isfinite(b.ymax);
    s.mag = std::max({s.mag, std::abs(b.xmin), std::abs(b.xmax), std::abs(b.ymin), std::abs(b.ymax)});
    if (is_big[i]) {
      ++s.big;
      continue;
    }
    ++s.small;
    s.size = std::max({s.size, b.xmax - b.xmin, b.ymax - b.ymin});
    s.x0 = std::min(s.x0, b.xmin), s.y0 = std::min(s.y0, b.ymin);
    s.x1 = std::max(s.x1, b.xmax), s.y1 = std::max(s.y1, b.ymax);
  }
  return s;
}

/// The grid's origin and tile size (its tile counts are in BroadPhase: nx, ny).
struct Grid {
  double x0 = 0.0, y0 = 0.0, size = 1.0;
};

/// The grid over the ordinary boxes of `scan` (at least one): tiles a hair larger than the
/// largest box, their count kept below ~4 per box by growing them if the boxes are spread far
/// apart; ws.cell_size, nx and ny set. Throws where the boxes span more than a double.
Grid grid_of(const BoxScan& scan, std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, BroadPhase& ws);

/// The tile of a box, by its centre (clamped against rounding at the grid's edges).
inline std::uint32_t tile_of(const Aabb& b, const Grid& g, std::int64_t nx, std::int64_t ny) {
  const auto cx =
      std::clamp<std::int64_t>(static_cast<std::int64_t>((0.5 * b.xmin + 0.5 * b.xmax - g.x0) / g.size), 0, nx - 1);
  const auto cy =
      std::clamp<std::int64_t>(static_cast<std::int64_t>((0.5 * b.ymin + 0.5 * b.ymax - g.y0) / g.size), 0, ny - 1);
  return static_cast<std::uint32_t>(cy * nx + cx);
}

/// For each box of ws.small[s0 … s1−1], its partners j > i in the 3×3 neighbouring tiles, in
/// ascending order, into `out` (grown as needed); returns the pairs written.
std::size_t tile_partners(std::span<const Aabb> boxes, const BroadPhase& ws, std::size_t s0, std::size_t s1,
                          std::vector<IndexPair>& out);

/// The tile arrays sized for `boxes` boxes, `small` of them ordinary (ws.nx, ny set).
void size_tiles(BroadPhase& ws, std::size_t boxes, std::size_t small);

/// The counting sort into tiles (broad_phase_threads.cpp), band by band: the ordinary boxes of
/// tiles c0 … c1−1 counted and added up (returns them; cell_start[c0] is the band's start
/// once every band before is counted), then placed in box order, their boxes copied in tile
/// order. One band of every tile (c0 = 0, c1 = nx·ny) is the whole sort on one thread.
std::uint32_t count_band(BroadPhase& ws, std::size_t c0, std::size_t c1);
void place_band(std::span<const Aabb> boxes, BroadPhase& ws, std::size_t c0, std::size_t c1);

/// Boxes range = [i0, i1) against each big box (ws.big), big box by big box, appended to `out`
/// (each pair once, i < j); counts[k], where given, gets big box k's pairs.
void big_pairs(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, const BroadPhase& ws,
               std::pair<std::size_t, std::size_t> range, std::vector<IndexPair>& out, std::size_t* counts);

/// Throws naming the first box of `boxes` that is not finite (there is one).
[[noreturn]] void name_bad_box(std::span<const Aabb> boxes);

/// find_pairs on `threads` threads (broad_phase_threads.cpp): every pass over the boxes, the
/// tiles' sort and the big boxes' tests shared; the same pairs in the same order.
void find_pairs_on_threads(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, BroadPhase& ws,
                           int threads);

/// find_pairs_reusing's rebuild on threads: the scan of every box (find_pairs' own, its ranges
/// merged: the same as one thread's), and the boxes inflated by `half` on each side, and kept
/// with their big flags (built, built_big).
BoxScan scan_on_threads(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, BroadPhase& ws, int threads);
void keep_boxes_on_threads(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, BroadPhase& ws,
                           double half, int threads);

}  // namespace nscd::broad
