// nscd/interactions/broad_phase.cpp — see broad_phase.hpp.
#include "nscd/interactions/broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "nscd/core/error.hpp"
#include "nscd/core/thread_share.hpp"
#include "nscd/interactions/broad_phase_grid.hpp"

namespace nscd {
namespace broad {

[[noreturn]] void bad_box(std::uint32_t i, const Aabb& b, const char* why) {
  std::ostringstream m;
  m.precision(17);
  m << "broad phase: bounding box " << i << " [" << b.xmin << ", " << b.xmax << "] x [" << b.ymin << ", " << b.ymax
    << "] " << why;
  throw Error(m.str());
}

void name_bad_box(std::span<const Aabb> boxes) {
  for (std::uint32_t i = 0; i < boxes.size(); ++i) {
    const Aabb& b = boxes[i];
    if (!(std::isfinite(b.xmin) && std::isfinite(b.xmax) && std::isfinite(b.ymin) && std::isfinite(b.ymax)))
      bad_box(i, b, "is not finite (a NaN or an infinite position)");
  }
  throw Error("broad phase: a bounding box is not finite");  // (not reached: the caller found one)
}

Grid grid_of(const BoxScan& scan, std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, BroadPhase& ws) {
  Grid g{scan.x0, scan.y0, scan.size};
  const double max_cells = 4.0 * static_cast<double>(scan.small) + 16.0;
  // Tiles a hair larger than the largest box. Two overlapping boxes have centres at most one
  // box extent apart, i.e. exactly one tile for two touching boxes of the largest size; the
  // margin absorbs the rounding of (centre − x0) / size (a few ulps of the coordinates),
  // which could otherwise floor such centres, sitting on tile boundaries, two tiles apart.
  const double mag = std::max({std::abs(scan.x0), std::abs(scan.y0), std::abs(scan.x1), std::abs(scan.y1)});
  g.size = std::max(g.size * (1.0 + 1e-12) + 1e-14 * mag, 1e-300);
  const double w = scan.x1 - scan.x0, h = scan.y1 - scan.y0;
  if (!std::isfinite(w) || !std::isfinite(h) || !std::isfinite(g.size)) {
    auto last = static_cast<std::uint32_t>(boxes.size() - 1);  // the last ordinary box
    while (is_big[last]) --last;
    bad_box(last, boxes[last], "makes the boxes span more than the largest double (coordinates near 1e308)");
  }
  while ((w / g.size + 1.0) * (h / g.size + 1.0) > max_cells) g.size *= 1.5;
  ws.cell_size = g.size;
  ws.nx = static_cast<std::int64_t>(w / g.size) + 1;
  ws.ny = static_cast<std::int64_t>(h / g.size) + 1;
  return g;
}

// The three rows of tiles are three runs; each candidate is written and kept only if it is a
// partner (no branch to mispredict), then the box's few partners are sorted.
std::size_t tile_partners(std::span<const Aabb> boxes, const BroadPhase& ws, std::size_t s0, std::size_t s1,
                          std::vector<IndexPair>& out) {
  std::size_t count = 0;  // pairs found; `out` is kept larger while it is filled
  out.resize(std::max<std::size_t>(out.capacity(), 64));
  for (std::size_t s = s0; s < s1; ++s) {
    const std::uint32_t i = ws.small[s];
    const Aabb& a = boxes[i];
    const std::int64_t c = ws.cell_of[i], cx = c % ws.nx, cy = c / ws.nx;
    const std::int64_t x0 = std::max<std::int64_t>(cx - 1, 0), x1 = std::min(cx + 1, ws.nx - 1);
    const std::size_t first = count;
    for (std::int64_t yy = std::max<std::int64_t>(cy - 1, 0); yy <= std::min(cy + 1, ws.ny - 1); ++yy) {
      const std::uint32_t k0 = ws.cell_start[static_cast<std::size_t>(yy * ws.nx + x0)];
      const std::uint32_t k1 = ws.cell_start[static_cast<std::size_t>(yy * ws.nx + x1) + 1];
      if (out.size() < count + (k1 - k0)) out.resize(2 * (count + (k1 - k0)));
      IndexPair* o = out.data();
      for (std::uint32_t k = k0; k < k1; ++k) {
        const std::uint32_t j = ws.cell_items[k];
        o[count] = {i, j};
        count += static_cast<std::size_t>((j > i) & overlap(a, ws.tile_boxes[k]));
      }
    }
    // insertion sort: a box has a handful of partners
    for (std::size_t m = first + 1; m < count; ++m)
      for (std::size_t q = m; q > first && out[q].second < out[q - 1].second; --q) std::swap(out[q], out[q - 1]);
  }
  return count;
}

}  // namespace broad

using broad::BoxScan;

// 1. One scan: finite, ordinary or big, the ordinary boxes' bounds; 2. the grid; 3. a counting
// sort of the ordinary boxes into their tiles (by centre); 4. each box's partners; 5. the big
// boxes against every box (they are few). On threads: broad_phase_threads.cpp.
void find_pairs(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, BroadPhase& ws, int threads) {
  if (threads > 1) return broad::find_pairs_on_threads(boxes, is_big, ws, threads);
  ws.pairs.clear();
  const auto n = static_cast<std::uint32_t>(boxes.size());
  const BoxScan scan = broad::scan_boxes(boxes, is_big, 0, n);
  // (non-finite coordinates would make the tile indices undefined: out-of-bounds reads)
  if (!scan.finite) broad::name_bad_box(boxes);
  ws.small.clear();
  ws.big.clear();
  for (std::uint32_t i = 0; i < n; ++i) (is_big[i] ? ws.big : ws.small).push_back(i);
  if (!ws.small.empty()) {
    const broad::Grid g = broad::grid_of(scan, boxes, is_big, ws);
    const auto cells = static_cast<std::size_t>(ws.nx * ws.ny);
    broad::size_tiles(ws, n, ws.small.size());
    for (std::uint32_t i : ws.small) ws.cell_of[i] = broad::tile_of(boxes[i], g, ws.nx, ws.ny);
    broad::count_band(ws, 0, cells);
    broad::place_band(boxes, ws, 0, cells);
    ws.pairs.resize(broad::tile_partners(boxes, ws, 0, ws.small.size(), ws.pairs));
  }
  broad::big_pairs(boxes, is_big, ws, {0, n}, ws.pairs, nullptr);
}

void find_pairs_reusing(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, BroadPhase& ws,
                        int threads) {
  const std::size_t n = boxes.size();
  // 1. Still within a quarter margin of the boxes of the last rebuild? (NaN compares false:
  //    a non-finite box rebuilds, and find_pairs names it.)
  bool reuse = ws.built.size() == n && ws.built_big.size() == n && ws.margin > 0.0 &&
               std::equal(is_big.begin(), is_big.end(), ws.built_big.begin());
  const double slack = 0.25 * ws.margin;
  auto near_built = [&](std::size_t i) {
    const Aabb& a = boxes[i];
    const Aabb& b = ws.built[i];
    return std::abs(a.xmin - b.xmin) < slack && std::abs(a.ymin - b.ymin) < slack &&
           std::abs(a.xmax - b.xmax) < slack && std::abs(a.ymax - b.ymax) < slack;
  };
  if (reuse && threads > 1) {  // (every box tested: no early stop across threads)
    const auto m = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for num_threads(threads) schedule(static) reduction(&& : reuse)
    for (std::ptrdiff_t i = 0; i < m; ++i) reuse = reuse && near_built(static_cast<std::size_t>(i));
  } else {
    for (std::size_t i = 0; reuse && i < n; ++i) reuse = near_built(i);
  }
  if (!reuse) {
    // 2. Rebuild: the margin, and the pairs of the inflated boxes. A box that is not finite, or
    //    no ordinary box (no margin): find_pairs on the boxes as they are (which names a bad box).
    const BoxScan scan =
        threads > 1 ? broad::scan_on_threads(boxes, is_big, ws, threads) : broad::scan_boxes(boxes, is_big, 0, n);
    // (boxes a billionth of their coordinates: the differences' rounding would eat the slack)
    ws.margin = scan.finite && scan.size > 1e-9 * scan.mag ? 0.1 * scan.size : 0.0;
    ++ws.rebuilds;
    if (!(ws.margin > 0.0) || !std::isfinite(ws.margin)) {
      ws.margin = 0.0;
      ws.built.clear();
      ws.pair_near.clear();
      find_pairs(boxes, is_big, ws);
      return;
    }
    const double half = 0.5 * ws.margin;
    if (threads > 1) {
      broad::keep_boxes_on_threads(boxes, is_big, ws, half, threads);
    } else {
      ws.inflated.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        ws.inflated[i] = {boxes[i].xmin - half, boxes[i].ymin - half, boxes[i].xmax + half, boxes[i].ymax + half};
      ws.built.assign(boxes.begin(), boxes.end());
      ws.built_big.assign(is_big.begin(), is_big.end());
    }
    find_pairs(ws.inflated, is_big, ws, threads);
    ws.near.swap(ws.pairs);
  } else {
    ++ws.reuses;
  }
  // 3. The kept pairs whose boxes overlap now, in the kept order.
  if (threads > 1) {
    auto overlapping = [&](std::size_t k) { return overlap(boxes[ws.near[k].first], boxes[ws.near[k].second]); };
    ordered_fill(
        ws.near.size(), threads, ws.thread_rows,
        [&](std::size_t k, std::size_t) -> std::size_t { return overlapping(k); },
        [&](std::size_t rows) {
          ws.pairs.resize(rows);
          ws.pair_near.resize(rows);
        },
        [&](std::size_t k, std::size_t at, std::size_t) -> std::size_t {
          if (!overlapping(k)) return 0;
          ws.pairs[at] = ws.near[k];
          ws.pair_near[at] = static_cast<std::uint32_t>(k);
          return 1;
        });
    return;
  }
  ws.pairs.resize(ws.near.size());
  ws.pair_near.resize(ws.near.size());
  std::size_t count = 0;
  for (std::uint32_t k = 0; k < ws.near.size(); ++k) {
    const IndexPair& p = ws.near[k];
    ws.pairs[count] = p;
    ws.pair_near[count] = k;
    count += overlap(boxes[p.first], boxes[p.second]);
  }
  ws.pairs.resize(count);
  ws.pair_near.resize(count);
}

std::vector<IndexPair> find_pairs_brute_force(std::span<const Aabb> boxes) {
  std::vector<IndexPair> out;
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
    for (std::uint32_t j = i + 1; j < boxes.size(); ++j)
      if (overlap(boxes[i], boxes[j])) out.emplace_back(i, j);
  return out;
}

}  // namespace nscd
