// nscd/interactions/broad_phase.cpp — see broad_phase.hpp.
#include "nscd/interactions/broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "nscd/core/error.hpp"
#include "nscd/core/thread_share.hpp"

namespace nscd {
namespace {

[[noreturn]] void bad_box(std::uint32_t i, const Aabb& b, const char* why) {
  std::ostringstream m;
  m.precision(17);
  m << "broad phase: bounding box " << i << " [" << b.xmin << ", " << b.xmax << "] x [" << b.ymin << ", " << b.ymax
    << "] " << why;
  throw Error(m.str());
}

// 3. For each box of small[s0 … s1−1], its partners j > i in the 3×3 neighbouring tiles, in
//    ascending order, into `out` (grown as needed); returns the pairs written. The three rows of
//    tiles are three runs; each candidate is written and kept only if it is a partner (no
//    branch to mispredict), then the box's few partners are sorted.
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

}  // namespace

void find_pairs(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, BroadPhase& ws, int threads) {
  ws.pairs.clear();
  ws.small.clear();
  ws.big.clear();
  const auto n = static_cast<std::uint32_t>(boxes.size());
  for (std::uint32_t i = 0; i < n; ++i) {
    // Non-finite coordinates would make the tile indices below undefined (out-of-bounds reads).
    const Aabb& b = boxes[i];
    if (!(std::isfinite(b.xmin) && std::isfinite(b.xmax) && std::isfinite(b.ymin) && std::isfinite(b.ymax)))
      bad_box(i, b, "is not finite (a NaN or an infinite position)");
    (is_big[i] ? ws.big : ws.small).push_back(i);
  }

  // 1. Grid over the ordinary boxes: tile size = largest box extent; the tile count is kept
  //    below ~4 per box by growing the tiles if the boxes are spread far apart.
  if (!ws.small.empty()) {
    double size = 0.0, x0 = boxes[ws.small[0]].xmin, y0 = boxes[ws.small[0]].ymin, x1 = x0, y1 = y0;
    for (std::uint32_t i : ws.small) {
      const Aabb& b = boxes[i];
      size = std::max({size, b.xmax - b.xmin, b.ymax - b.ymin});
      x0 = std::min(x0, b.xmin); y0 = std::min(y0, b.ymin);
      x1 = std::max(x1, b.xmax); y1 = std::max(y1, b.ymax);
    }
    const double max_cells = 4.0 * static_cast<double>(ws.small.size()) + 16.0;
    // Tiles a hair larger than the largest box. Two overlapping boxes have centres at most one
    // box extent apart, i.e. exactly one tile for two touching boxes of the largest size; the
    // margin absorbs the rounding of (centre − x0) / size (a few ulps of the coordinates),
    // which could otherwise floor such centres, sitting on tile boundaries, two tiles apart.
    const double mag = std::max({std::abs(x0), std::abs(y0), std::abs(x1), std::abs(y1)});
    size = std::max(size * (1.0 + 1e-12) + 1e-14 * mag, 1e-300);
    const double w = x1 - x0, h = y1 - y0;
    if (!std::isfinite(w) || !std::isfinite(h) || !std::isfinite(size))
      bad_box(!std::isfinite(w) || !std::isfinite(h) ? ws.small.back() : ws.small[0], boxes[ws.small.back()],
              "makes the boxes span more than the largest double (coordinates near 1e308)");
    while ((w / size + 1.0) * (h / size + 1.0) > max_cells) size *= 1.5;
    ws.cell_size = size;
    ws.nx = static_cast<std::int64_t>(w / size) + 1;
    ws.ny = static_cast<std::int64_t>(h / size) + 1;
    const auto cells = static_cast<std::size_t>(ws.nx * ws.ny);

    // 2. Counting sort of the boxes into their tiles (by centre).
    ws.cell_of.resize(n);
    ws.cell_start.assign(cells + 1, 0);
    for (std::uint32_t i : ws.small) {
      const Aabb& b = boxes[i];
      // centres within [x0, x1]: indices in [0, nx − 1]; clamped against rounding all the same
      const auto cx =
          std::clamp<std::int64_t>(static_cast<std::int64_t>((0.5 * b.xmin + 0.5 * b.xmax - x0) / size), 0, ws.nx - 1);
      const auto cy =
          std::clamp<std::int64_t>(static_cast<std::int64_t>((0.5 * b.ymin + 0.5 * b.ymax - y0) / size), 0, ws.ny - 1);
      ws.cell_of[i] = static_cast<std::uint32_t>(cy * ws.nx + cx);
      ++ws.cell_start[ws.cell_of[i] + 1];
    }
    for (std::size_t c = 0; c < cells; ++c) ws.cell_start[c + 1] += ws.cell_start[c];
    ws.cell_items.resize(ws.small.size());
    ws.scratch.assign(ws.cell_start.begin(), ws.cell_start.end() - 1);
    for (std::uint32_t i : ws.small) ws.cell_items[ws.scratch[ws.cell_of[i]]++] = i;
    // the boxes in tile order, so that a row of three neighbouring tiles is one contiguous run
    ws.tile_boxes.resize(ws.small.size());
    for (std::size_t k = 0; k < ws.cell_items.size(); ++k) ws.tile_boxes[k] = boxes[ws.cell_items[k]];

    // 3. Each box's partners (tile_partners): on threads, each on its range of the boxes into
    //    a list of its own, the lists then joined in thread order (the same pairs, in order).
    if (threads > 1) {
      ws.thread_pairs.resize(static_cast<std::size_t>(threads));
      ws.thread_rows.assign(static_cast<std::size_t>(threads) + 1, 0);
#pragma omp parallel num_threads(threads)
      {
        const auto [s0, s1] = thread_range(ws.small.size());
        const std::size_t t = thread_index();
        std::vector<IndexPair>& mine = ws.thread_pairs[t].v;
        mine.resize(tile_partners(boxes, ws, s0, s1, mine));
        ws.thread_rows[t + 1] = mine.size();
#pragma omp barrier
#pragma omp single
        {
          for (std::size_t u = 0; u + 1 < ws.thread_rows.size(); ++u) ws.thread_rows[u + 1] += ws.thread_rows[u];
          ws.pairs.resize(ws.thread_rows.back());
        }
        std::copy(mine.begin(), mine.end(), ws.pairs.begin() + static_cast<std::ptrdiff_t>(ws.thread_rows[t]));
      }
    } else {
      ws.pairs.resize(tile_partners(boxes, ws, 0, ws.small.size(), ws.pairs));
    }
  }

  // 4. Big boxes against everything (they are few).
  for (std::uint32_t b : ws.big) {
    for (std::uint32_t i = 0; i < n; ++i) {
      if (i == b || (is_big[i] && i < b)) continue;  // big–big pairs once
      if (overlap(boxes[b], boxes[i])) ws.pairs.emplace_back(std::min(b, i), std::max(b, i));
    }
  }
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
    bool finite = true;
    double largest = 0.0, mag = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const Aabb& b = boxes[i];
      finite =
          finite && std::isfinite(b.xmin) && std::isfinite(b.xmax) && std::isfinite(b.ymin) && std::isfinite(b.ymax);
      if (!is_big[i]) largest = std::max({largest, b.xmax - b.xmin, b.ymax - b.ymin});
      mag = std::max({mag, std::abs(b.xmin), std::abs(b.xmax), std::abs(b.ymin), std::abs(b.ymax)});
    }
    // (boxes a billionth of their coordinates: the differences' rounding would eat the slack)
    ws.margin = finite && largest > 1e-9 * mag ? 0.1 * largest : 0.0;
    ++ws.rebuilds;
    if (!(ws.margin > 0.0) || !std::isfinite(ws.margin)) {
      ws.margin = 0.0;
      ws.built.clear();
      ws.pair_near.clear();
      find_pairs(boxes, is_big, ws);
      return;
    }
    const double half = 0.5 * ws.margin;
    ws.inflated.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      ws.inflated[i] = {boxes[i].xmin - half, boxes[i].ymin - half, boxes[i].xmax + half, boxes[i].ymax + half};
    find_pairs(ws.inflated, is_big, ws, threads);
    ws.near.swap(ws.pairs);
    ws.built.assign(boxes.begin(), boxes.end());
    ws.built_big.assign(is_big.begin(), is_big.end());
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
