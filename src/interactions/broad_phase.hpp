// nscd/interactions/broad_phase.hpp — candidate pairs from axis-aligned bounding boxes on a
// uniform grid of tiles (Saussine et al. 2006, §2.3: "predetection").
//
// Each ordinary box goes into the one tile holding its centre; tiles are at least as large
// as the largest ordinary box, so two overlapping boxes sit in the same or neighbouring
// tiles. Cost O(N) per call, no O(N²) anywhere. "Big" boxes (walls, floors: much larger than
// the grains) stay out of the grid, as in LMGC90, and are tested against every ordinary box
// (O(N) per big box). The pair list is deterministic: for each i ascending, its partners j > i
// ascending, then the pairs involving big boxes in the same order.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "nscd/core/math.hpp"
#include "nscd/core/own_line.hpp"

namespace nscd {

/// The four comparisons all made (`&`, not `&&`): no branch to mispredict in the broad phase's
/// loop over candidates.
inline bool overlap(const Aabb& a, const Aabb& b) {
  return (a.xmin <= b.xmax) & (b.xmin <= a.xmax) & (a.ymin <= b.ymax) & (b.ymin <= a.ymax);
}

using IndexPair = std::pair<std::uint32_t, std::uint32_t>;

namespace broad {
/// What find_pairs' pass over boxes i0 … i1−1 finds: whether all are finite, how many are
/// ordinary (small) and big, and the ordinary boxes' bounds and largest extent. Min and max are
/// exact, so scans of ranges merged in any order give the scan of the whole.
struct BoxScan {
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  bool finite = true;
  std::size_t small = 0, big = 0;
  double size = 0.0, x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
  double mag = 0.0;  ///< the largest |coordinate| of every box, big ones too
  void merge(const BoxScan& o) {
    finite = finite && o.finite;
    small += o.small, big += o.big;
    size = std::max(size, o.size);
    mag = std::max(mag, o.mag);
    x0 = std::min(x0, o.x0), y0 = std::min(y0, o.y0), x1 = std::max(x1, o.x1), y1 = std::max(y1, o.y1);
  }
};

}  // namespace broad

/// Reusable workspace: the grid and the output pairs (no allocation once warmed up).
struct BroadPhase {
  std::vector<IndexPair> pairs;  ///< output: i < j, boxes overlap
  // grid
  std::vector<std::uint32_t> small, big;
  std::vector<std::uint32_t> cell_of, cell_start, cell_items, scratch;
  std::vector<Aabb> tile_boxes;  ///< the ordinary boxes in cell_items' order
  double cell_size = 0.0;
  std::int64_t nx = 0, ny = 0;
  // find_pairs_reusing: the pairs of the boxes inflated by `margin` at the last rebuild, and
  // those boxes
  std::vector<IndexPair> near;
  std::vector<Aabb> built, inflated;
  std::vector<std::uint8_t> built_big;
  double margin = 0.0;
  std::size_t rebuilds = 0, reuses = 0;  ///< calls of find_pairs_reusing that rebuilt / reused `near`
  /// find_pairs_reusing: the index in `near` of each pair of `pairs` (empty where nothing was
  /// kept); `near` and these indices hold from one rebuild to the next (rebuilds counts them).
  std::vector<std::uint32_t> pair_near;
  std::vector<std::size_t> thread_rows;  ///< on threads: each chunk's (find_pairs) or thread's first pair
  /// find_pairs on threads: each chunk's partners, then each thread's pairs with the big boxes
  std::vector<OwnLine<std::vector<IndexPair>>> thread_pairs;
  std::vector<OwnLine<broad::BoxScan>> scans;  ///< … each part's scan of its boxes
  std::vector<std::size_t> counts;  ///< … its ordinary and big boxes, bands, big pairs
};

/// All pairs (i < j) of overlapping boxes. `is_big[i]` = 1 keeps box i out of the grid.
/// `threads`: every pass (the scan, the sort into tiles, the partners, the big boxes' tests)
/// shared between that many OpenMP threads (the same pairs, in order).
void find_pairs(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, BroadPhase& ws, int threads = 1);

/// The same pairs, in the same order, as find_pairs, found again from a list kept between calls
/// (a Verlet list): the pairs of the boxes inflated by a margin (a tenth of the largest ordinary
/// box) at a rebuild. While no bound of any box has moved by a quarter of that margin since,
/// every pair of boxes that overlap now overlapped inflated then, so the list holds them all,
/// and keeping those that overlap now gives find_pairs' answer exactly (and in its order: each
/// list is sorted the same way). Else, or when the boxes' count or big flags change, it rebuilds.
/// `threads`: the test of the boxes against the list's, a rebuild (its passes over the boxes and
/// find_pairs) and the kept pairs' filter on that many OpenMP threads (the same pairs in the
/// same order).
void find_pairs_reusing(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, BroadPhase& ws,
                        int threads = 1);

/// O(N²) reference, for tests.
std::vector<IndexPair> find_pairs_brute_force(std::span<const Aabb> boxes);

}  // namespace nscd
