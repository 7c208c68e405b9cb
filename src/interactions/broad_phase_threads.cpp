// nscd/interactions/broad_phase_threads.cpp — find_pairs on threads (broad_phase_grid.hpp): the
// one-thread passes (broad_phase.cpp), each shared between the threads of one parallel region,
// giving the same pairs in the same order. Left on one thread, a rebuild's scan, sort into
// tiles and tests of the big boxes are work that grows with the scene and that no added thread
// shortens.
#include <algorithm>

#include "nscd/core/thread_share.hpp"
#include "nscd/interactions/broad_phase_grid.hpp"

namespace nscd::broad {

// 3a. The ordinary boxes of tiles c0 … c1−1 counted by tile and added up inside the band:
//     cell_start[c + 1] (zeroed here) gets the band's boxes up to tile c. Returns the band's
//     boxes. Every thread reads every box's tile and counts those of its band; the others go to
//     a sink (no branch to mispredict: the boxes' order need not follow the rows).
std::uint32_t count_band(BroadPhase& ws, std::size_t c0, std::size_t c1) {
  std::uint32_t* count = ws.cell_start.data() + 1;
  std::fill(count + c0, count + c1, 0u);
  std::uint32_t sink = 0;
  const std::size_t span = c1 - c0;
  for (const std::uint32_t i : ws.small) {
    const std::size_t c = ws.cell_of[i];
    ++*(c - c0 < span ? count + c : &sink);
  }
  std::uint32_t at = 0;
  for (std::size_t c = c0; c < c1; ++c) at = (count[c] += at);
  return at;
}

// 3b. The band's boxes into their tiles, in box order (stable, as the one-thread sort), then
//     their boxes in tile order; cell_start final.
void place_band(std::span<const Aabb> boxes, BroadPhase& ws, std::size_t c0, std::size_t c1) {
  std::uint32_t* next = ws.scratch.data();
  std::copy(ws.cell_start.data() + c0, ws.cell_start.data() + c1, next + c0);
  std::uint32_t* items = ws.cell_items.data();
  std::uint32_t sink[2] = {0, 0};  // a box outside the band: its slot, and where it is written
  const std::size_t span = c1 - c0;
  for (const std::uint32_t i : ws.small) {
    const std::size_t c = ws.cell_of[i];
    const bool in = c - c0 < span;
    std::uint32_t* slot = in ? next + c : sink;
    *(in ? items + *slot : sink + 1) = i;
    ++*slot;
  }
  for (std::uint32_t k = ws.cell_start[c0]; k < ws.cell_start[c1]; ++k) ws.tile_boxes[k] = boxes[items[k]];
}

// 5. Boxes range = [i0, i1) against each big box, big box by big box, appended to `out`;
//    counts[k] (where given) gets the pairs of big box k (its index in ws.big).
void big_pairs(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, const BroadPhase& ws,
               std::pair<std::size_t, std::size_t> range, std::vector<IndexPair>& out, std::size_t* counts) {
  const auto [i0, i1] = range;
  for (std::size_t k = 0; k < ws.big.size(); ++k) {
    const std::uint32_t b = ws.big[k];
    const std::size_t before = out.size();
    for (auto i = static_cast<std::uint32_t>(i0); i < i1; ++i) {
      if (i == b || (is_big[i] && i < b)) continue;  // big–big pairs once
      if (overlap(boxes[b], boxes[i])) out.emplace_back(std::min(b, i), std::max(b, i));
    }
    if (counts) counts[k] = out.size() - before;
  }
}

void size_tiles(BroadPhase& ws, std::size_t boxes, std::size_t small) {
  const auto cells = static_cast<std::size_t>(ws.nx * ws.ny);
  ws.cell_of.resize(boxes);
  ws.cell_start.resize(cells + 1);  // (zeroed band by band: count_band)
  ws.cell_start[0] = 0;
  ws.scratch.resize(cells);
  ws.cell_items.resize(small);
  ws.tile_boxes.resize(small);
}

namespace {

/// Chunks of the partner search a thread: taken in turn (dynamic), they even out the threads'
/// loads where the boxes' partners are uneven (a packed bed below, falling grains above).
constexpr std::size_t kChunksPerThread = 4;

/// Thread t's band of tiles: whole rows, ny·t/team … ny·(t+1)/team − 1, so one range of tiles.
std::pair<std::size_t, std::size_t> band(const BroadPhase& ws, std::size_t t, std::size_t team) {
  const auto nx = static_cast<std::size_t>(ws.nx), ny = static_cast<std::size_t>(ws.ny);
  return {ny * t / team * nx, ny * (t + 1) / team * nx};
}

/// Part u of T of the boxes [0, n): the ranges the scan and the lists share, whatever the team.
std::pair<std::size_t, std::size_t> part(std::size_t n, std::size_t u, std::size_t T) {
  return {n * u / T, n * (u + 1) / T};
}

// 2. The parts' scans joined (one thread, outside the threads' region: the grid may throw):
//    each part's first ordinary and big box, the grid, the arrays sized. counts: part u's first
//    ordinary box at u (T + 1 of them), its first big box at T+1 + u, thread t's band's first
//    box at 2T+2 + t, part u's pairs with big box k at 3T+3 + u·big + k (join_rows adds their
//    first rows). Returns the partner search's chunks (0: no ordinary box).
std::size_t join_scans(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, BroadPhase& ws,
                       const BoxScan& all, Grid& grid) {
  const std::size_t T = ws.scans.size();
  ws.counts.assign(3 * (T + 1) + 2 * T * all.big, 0);
  std::size_t* at = ws.counts.data();
  for (std::size_t u = 0; u < T; ++u) {
    at[u + 1] = at[u] + ws.scans[u].v.small;
    at[T + 2 + u] = at[T + 1 + u] + ws.scans[u].v.big;
  }
  ws.small.resize(all.small);
  ws.big.resize(all.big);
  const std::size_t chunks = all.small > 0 ? kChunksPerThread * T : 0;
  ws.thread_pairs.resize(std::max(ws.thread_pairs.size(), chunks + T));
  if (chunks == 0) return 0;
  grid = grid_of(all, boxes, is_big, ws);
  size_tiles(ws, boxes.size(), all.small);
  return chunks;
}

// 3. Part u's boxes in their lists, each ordinary box in its tile.
void list_part(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, BroadPhase& ws, const Grid& grid,
               std::size_t u, bool tiles) {
  const std::size_t T = ws.scans.size();
  const auto [i0, i1] = part(boxes.size(), u, T);
  std::size_t s = ws.counts[u], b = ws.counts[T + 1 + u];
  for (auto i = static_cast<std::uint32_t>(i0); i < i1; ++i) {
    if (is_big[i]) {
      ws.big[b++] = i;
      continue;
    }
    ws.small[s++] = i;
    if (tiles) ws.cell_of[i] = tile_of(boxes[i], grid, ws.nx, ws.ny);
  }
}

// 6. The chunks' partners, then the big boxes' pairs big box by big box, part by part: each
//    list's first row (thread_rows for the chunks; part u's with big box k at
//    3T+3 + (T+u)·big + k), and the pairs sized. (One thread.)
void join_rows(BroadPhase& ws, std::size_t chunks) {
  const std::size_t T = ws.scans.size(), big = ws.big.size();
  ws.thread_rows.assign(chunks + 1, 0);
  for (std::size_t k = 0; k < chunks; ++k) ws.thread_rows[k + 1] = ws.thread_rows[k] + ws.thread_pairs[k].v.size();
  std::size_t rows = ws.thread_rows[chunks];
  std::size_t* count = ws.counts.data() + 3 * (T + 1);
  for (std::size_t k = 0; k < big; ++k)
    for (std::size_t u = 0; u < T; ++u) {
      count[(T + u) * big + k] = rows;
      rows += count[u * big + k];
    }
  ws.pairs.resize(rows);
}

// 6. Part u's pairs with the big boxes into their rows.
void copy_big_pairs(BroadPhase& ws, std::size_t chunks, std::size_t u) {
  const std::size_t T = ws.scans.size(), big = ws.big.size();
  const std::vector<IndexPair>& mine = ws.thread_pairs[chunks + u].v;
  const std::size_t* count = ws.counts.data() + 3 * (T + 1);
  for (std::size_t k = 0, from = 0; k < big; from += count[u * big + k], ++k)
    std::copy(mine.begin() + static_cast<std::ptrdiff_t>(from),
              mine.begin() + static_cast<std::ptrdiff_t>(from + count[u * big + k]),
              ws.pairs.begin() + static_cast<std::ptrdiff_t>(count[(T + u) * big + k]));
}

}  // namespace

BoxScan scan_on_threads(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, BroadPhase& ws,
                        int threads) {
  const auto T = static_cast<std::size_t>(threads);
  ws.scans.assign(T, {});
#pragma omp parallel num_threads(threads)
  for (std::size_t u = thread_index(); u < T; u += thread_count()) {
    const auto [i0, i1] = part(boxes.size(), u, T);
    ws.scans[u].v = scan_boxes(boxes, is_big, i0, i1);
  }
  BoxScan all;
  for (const OwnLine<BoxScan>& s : ws.scans) all.merge(s.v);
  return all;
}

// The passes of find_pairs (broad_phase.cpp), shared: each thread scans its parts of the boxes;
// then, in one region, lists and tiles them, counts and places the boxes of its band of tiles,
// tests its parts against the big boxes; the partner search's chunks are taken in turn; the
// lists are joined in order (the same pairs, in the same order, as on one thread).
void find_pairs_on_threads(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, BroadPhase& ws,
                           int threads) {
  ws.pairs.clear();
  const BoxScan all = scan_on_threads(boxes, is_big, ws, threads);
  if (!all.finite) name_bad_box(boxes);
  Grid grid;
  const std::size_t chunks = join_scans(boxes, is_big, ws, all, grid), T = ws.scans.size();
#pragma omp parallel num_threads(threads)
  {
    const std::size_t t = thread_index(), team = thread_count();
    for (std::size_t u = t; u < T; u += team) list_part(boxes, is_big, ws, grid, u, chunks > 0);
    const auto [c0, c1] = chunks > 0 ? band(ws, t, team) : std::pair<std::size_t, std::size_t>{0, 0};
    std::size_t* band_at = ws.counts.data() + 2 * (T + 1);  // 3. the tiles' counts, band by band
#pragma omp barrier
    if (chunks > 0) band_at[t + 1] = count_band(ws, c0, c1);
#pragma omp barrier
#pragma omp single
    for (std::size_t u = 0; u < team; ++u) band_at[u + 1] += band_at[u];
    for (std::size_t c = c0; c < c1; ++c) ws.cell_start[c + 1] += static_cast<std::uint32_t>(band_at[t]);
#pragma omp barrier
    if (chunks > 0) place_band(boxes, ws, c0, c1);
    // 5. (before the partners' barrier) this thread's parts against the big boxes
    for (std::size_t u = t; u < T; u += team) {
      ws.thread_pairs[chunks + u].v.clear();
      big_pairs(boxes, is_big, ws, part(boxes.size(), u, T), ws.thread_pairs[chunks + u].v,
                ws.counts.data() + 3 * (T + 1) + u * ws.big.size());
    }
#pragma omp barrier
    const std::size_t S = ws.small.size();  // 4. the partners, chunk by chunk
#pragma omp for schedule(dynamic, 1)
    for (std::size_t k = 0; k < chunks; ++k) {
      std::vector<IndexPair>& out = ws.thread_pairs[k].v;
      out.resize(tile_partners(boxes, ws, S * k / chunks, S * (k + 1) / chunks, out));
    }
#pragma omp single
    join_rows(ws, chunks);
#pragma omp for schedule(static) nowait
    for (std::size_t k = 0; k < chunks; ++k)
      std::copy(ws.thread_pairs[k].v.begin(), ws.thread_pairs[k].v.end(),
                ws.pairs.begin() + static_cast<std::ptrdiff_t>(ws.thread_rows[k]));
    for (std::size_t u = t; u < T; u += team) copy_big_pairs(ws, chunks, u);
  }
}

void keep_boxes_on_threads(std::span<const Aabb> boxes, std::span<const std::uint8_t> is_big, BroadPhase& ws,
                           double half, int threads) {
  const std::size_t n = boxes.size();
  ws.inflated.resize(n);
  ws.built.resize(n);
  ws.built_big.resize(n);
#pragma omp parallel num_threads(threads)
  {
    const auto [i0, i1] = thread_range(n);
    for (std::size_t i = i0; i < i1; ++i) {
      const Aabb& b = boxes[i];
      ws.inflated[i] = {b.xmin - half, b.ymin - half, b.xmax + half, b.ymax + half};
      ws.built[i] = b;
      ws.built_big[i] = is_big[i];
    }
  }
}

}  // namespace nscd::broad
