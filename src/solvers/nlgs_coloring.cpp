// nscd/solvers/nlgs_coloring.cpp — the colored sweep's colouring and layout (color_contacts,
// nlgs_colored.hpp), in its numbered steps.
#include <algorithm>
#include <atomic>
#include <bit>
#include <numeric>

#include "nscd/solvers/nlgs_blocks.hpp"
#include "nscd/solvers/nlgs_colored.hpp"
#include "nscd/solvers/thread_range.hpp"

namespace nscd {
namespace {

using namespace colored;
using Scratch = NlgsColoredWorkspace::ColorScratch;

/// Contacts per block of consecutive contacts (a system without positions): n/64 within
/// [256, 8192] — a function of the system only, never of the threads. Blocks of consecutive
/// contacts keep the detection order's cache locality; where that order follows the layers of a
/// packing, a block large enough to span a row meets only its neighbours and two or three
/// colours do, and fewer colours sweep faster (docs/benchmarks.md §8). Where it does not, a
/// block touches bodies all over the field and the colours are many and small (a 7,000-grain
/// deposit: 9–10 colours of 1–11 blocks): hence strips and cells wherever the bodies have
/// positions.
std::size_t block_size(std::size_t n) { return std::clamp<std::size_t>(n / 64, 256, 8192); }

/// The blocks' count and keys, the layout's sizes (what the steps hand on).
struct Blocks {
  std::size_t blocks = 0, keys = 0;
  bool spilled = false;  ///< some contacts are in no block (the overflow's own block)
};

// 1. Blocks: strips or cells of the field (systems with positions) or consecutive contacts.
Blocks assign_blocks(ContactSystem& sys, NlgsColoredWorkspace& ws, SweepOrder order, int threads) {
  const std::size_t n = sys.contacts.size();
  Scratch& x = ws.scratch;
  fill_ends(sys.contacts, x.ends, threads);
  std::vector<std::uint32_t>& block_of = x.block_of;
  Blocks k;
  const bool rows = is_cells(order);
  ws.cells = rows && cell_blocks(sys, ws, block_of, k.blocks, x.key, k.keys, x.body_cell,
                                 order == SweepOrder::ColoredCells, threads);
  ws.strips = !rows && strip_blocks(sys, ws, block_of, k.blocks, x.key, k.keys, threads);
  if (ws.cells || ws.strips) return k;
  // consecutive in detection order: by rank of the registry row when the rows say it (an
  // arranged system then gives back its own blocks), else by index
  const std::size_t kBlock = block_size(n);
  k.blocks = (n + kBlock - 1) / kBlock;
  block_of.resize(n);
  const bool by_rank = sys.rows.size() == n && !std::is_sorted(sys.rows.begin(), sys.rows.end());
  if (by_rank) {
    x.rank.resize(n);
    std::iota(x.rank.begin(), x.rank.end(), 0u);
    std::sort(x.rank.begin(), x.rank.end(),
              [&](std::uint32_t p, std::uint32_t q) { return sys.rows[p] < sys.rows[q]; });
    for (std::size_t r = 0; r < n; ++r) block_of[x.rank[r]] = static_cast<std::uint32_t>(r / kBlock);
  } else {
    for (std::size_t a = 0; a < n; ++a) block_of[a] = static_cast<std::uint32_t>(a / kBlock);
  }
  k.keys = k.blocks;  // the threads' shares: ranges of blocks
  x.key.resize(k.blocks);
  std::iota(x.key.begin(), x.key.end(), 0u);
  return k;
}

// 2. Each block's contacts, in contact order (a counting sort; the spilled ones last). On the
//    threads from kParallelMin contacts on: each thread counts its range of contacts by block,
//    the counts are added up block by block and, inside a block, thread by thread, and each
//    thread places its own contacts from there: the same members in the same order.
void gather_members(Scratch& x, std::size_t n, std::size_t nblocks, int threads) {
  const std::vector<std::uint32_t>& block_of = x.block_of;
  auto bin = [&](std::size_t a) { return block_of[a] == kSpill ? nblocks : block_of[a]; };
  std::vector<std::uint32_t>& first = x.first;
  first.assign(nblocks + 2, 0);
  x.members.resize(n);
  if (threads <= 1) {
    for (std::size_t a = 0; a < n; ++a) ++first[bin(a) + 1];
    for (std::size_t b = 0; b <= nblocks; ++b) first[b + 1] += first[b];
    x.next.assign(first.begin(), first.end() - 1);
    for (std::size_t a = 0; a < n; ++a) x.members[x.next[bin(a)]++] = static_cast<std::uint32_t>(a);
    return;
  }
  const std::size_t bins = nblocks + 1;
  x.thread_next.assign(static_cast<std::size_t>(threads) * bins, 0);  // [t bins + b]: thread t's in bin b
#pragma omp parallel num_threads(threads)
  {
    const auto [a0, a1] = thread_range(n);
    std::uint32_t* next = x.thread_next.data() + thread_index() * bins;
    for (std::size_t a = a0; a < a1; ++a) ++next[bin(a)];
#pragma omp barrier
#pragma omp single
    {
      std::uint32_t at = 0;
      for (std::size_t b = 0; b < bins; ++b) {
        first[b] = at;
        for (std::size_t u = 0; u < thread_count(); ++u) {
          const std::uint32_t count = x.thread_next[u * bins + b];
          x.thread_next[u * bins + b] = at;
          at += count;
        }
      }
      first[bins] = at;
    }
    for (std::size_t a = a0; a < a1; ++a) x.members[next[bin(a)]++] = static_cast<std::uint32_t>(a);
  }
}

// 3. Colours, block by block, marked at every dynamic body of the block (col[b]). Strips and
//    consecutive blocks: greedy, the lowest colour not taken at any of its dynamic bodies
//    (two or three colours).
//    Cells: levels, the lowest colour above every colour taken at its dynamic bodies, so that
//    two blocks sharing a dynamic body are swept in block order: the sweep is that of the
//    cells one after the other, row by row from the bottom (theory §9.5), two colours a row.
//    No colour left: the overflow.
void greedy_colours(NlgsColoredWorkspace& ws, std::size_t bodies, std::size_t nblocks) {
  Scratch& x = ws.scratch;
  const std::vector<Ends>& ends = x.ends;
  const std::vector<std::uint32_t>& first = x.first;
  const std::vector<std::uint32_t>& members = x.members;
  ws.body_colors.assign(bodies, 0);
  for (std::size_t b = 0; b < nblocks; ++b) {
    std::uint64_t taken = 0;
    for (std::uint32_t i = first[b]; i < first[b + 1]; ++i) {
      const Ends e = ends[members[i]];
      taken |= (e.cd != kNoBody ? ws.body_colors[e.cd] : 0) | (e.an != kNoBody ? ws.body_colors[e.an] : 0);
    }
    std::uint64_t free_colors = ~taken & ((std::uint64_t{1} << kOverflow) - 1);
    if (ws.cells && taken != 0)
      free_colors &= ~std::uint64_t{0} << (64 - std::countl_zero(taken));  // above the highest taken
    const unsigned c = free_colors ? static_cast<unsigned>(std::countr_zero(free_colors)) : kOverflow;
    if (c != kOverflow)
      for (std::uint32_t i = first[b]; i < first[b + 1]; ++i) {
        const Ends e = ends[members[i]];
        if (e.cd != kNoBody) ws.body_colors[e.cd] |= std::uint64_t{1} << c;
        if (e.an != kNoBody) ws.body_colors[e.an] |= std::uint64_t{1} << c;
      }
    x.col[b] = c;
  }
}

// 3. Strips, on threads: strip b's contacts touch dynamic bodies of strips b and b + 1 only
//    (strip_blocks), so a body is touched by two consecutive blocks at most, and block b shares
//    bodies with block b − 1 at most among those before it. The greedy colouring then gives
//    block b colour 1 where it shares a body with block b − 1 of colour 0, else colour 0. Which
//    neighbours share a body is found on the threads: each body's even and odd block (one of
//    each at most; written by several threads, always the same value), then a pass over the
//    bodies. False (nothing decided) if two blocks that are not neighbours share a body.
bool strip_colours(NlgsColoredWorkspace& ws, std::size_t bodies, std::size_t nblocks, int threads) {
  Scratch& x = ws.scratch;
  constexpr std::uint32_t kNone = kNoBody;
  x.body_block[0].resize(bodies);
  x.body_block[1].resize(bodies);
  x.shares.assign(nblocks, 0);
  std::uint32_t* const by_parity[2] = {x.body_block[0].data(), x.body_block[1].data()};
  const std::vector<Ends>& ends = x.ends;
  const std::vector<std::uint32_t>& block_of = x.block_of;
  bool neighbours = true;
#pragma omp parallel num_threads(threads) reduction(&& : neighbours)
  {
    const auto [i0, i1] = thread_range(bodies);
    std::fill(by_parity[0] + i0, by_parity[0] + i1, kNone);
    std::fill(by_parity[1] + i0, by_parity[1] + i1, kNone);
#pragma omp barrier
    const auto [a0, a1] = thread_range(ends.size());
    for (std::size_t a = a0; a < a1; ++a) {
      const std::uint32_t b = block_of[a];
      if (b == kSpill) continue;
      std::uint32_t* mark = by_parity[b & 1u];
      if (ends[a].cd != kNoBody) std::atomic_ref(mark[ends[a].cd]).store(b, std::memory_order_relaxed);
      if (ends[a].an != kNoBody) std::atomic_ref(mark[ends[a].an]).store(b, std::memory_order_relaxed);
    }
#pragma omp barrier
    for (std::size_t i = i0; i < i1; ++i) {
      const std::uint32_t even = by_parity[0][i], odd = by_parity[1][i];
      if (even == kNone || odd == kNone) continue;
      const std::uint32_t hi = std::max(even, odd);
      neighbours = neighbours && hi - std::min(even, odd) == 1;
      std::atomic_ref(x.shares[hi]).store(1, std::memory_order_relaxed);
    }
  }
  if (!neighbours) return false;
  for (std::size_t b = 0; b < nblocks; ++b) x.col[b] = b > 0 && x.shares[b] && x.col[b - 1] == 0 ? 1 : 0;
  return true;
}

// 3. Each block's colour (strips of a large system on threads: strip_colours, else
//    greedy_colours); count[k + 1] receives the blocks of colour k.
void color_blocks(NlgsColoredWorkspace& ws, std::size_t bodies, Blocks& k, std::uint32_t* count, int threads) {
  Scratch& x = ws.scratch;
  const std::size_t nblocks = k.blocks;
  std::vector<std::uint32_t>& col = x.col;
  col.assign(nblocks + 1, 0);
  if (!(ws.strips && threads > 1 && strip_colours(ws, bodies, nblocks, threads))) greedy_colours(ws, bodies, nblocks);
  for (std::size_t b = 0; b < nblocks; ++b) ++count[col[b] + 1];
  k.spilled = x.first[nblocks + 1] > x.first[nblocks];
  col[nblocks] = kOverflow;  // the spilled contacts: one more block of the overflow, the last
  if (k.spilled) ++count[kOverflow + 1];
}

// 4. Layout: blocks colour by colour (by key inside a colour: block order, or column then
//    row), so that a block, a colour and a thread's share are each one range of consecutive
//    records (records are written at every visit: records of two threads sharing a cache line
//    would bounce between the cores). Returns the blocks laid.
std::size_t lay_out_blocks(NlgsColoredWorkspace& ws, const Blocks& k, const std::uint32_t* count) {
  Scratch& x = ws.scratch;
  const std::size_t nblocks = k.blocks, nkeys = k.keys;
  ws.color_start.assign(kOverflow + 2, 0);
  for (unsigned c = 0; c <= kOverflow; ++c) ws.color_start[c + 1] = ws.color_start[c] + count[c + 1];
  x.next.assign(ws.color_start.begin(), ws.color_start.end() - 1);
  std::vector<std::uint32_t>& placed = x.placed;
  placed.resize(nblocks + 1);
  std::vector<std::uint32_t>& by_key = x.by_key;  // the blocks by key (a counting sort, stable)
  by_key.resize(nblocks);
  x.key_first.assign(nkeys + 1, 0);
  for (std::size_t b = 0; b < nblocks; ++b) ++x.key_first[x.key[b] + 1];
  for (std::size_t c = 0; c < nkeys; ++c) x.key_first[c + 1] += x.key_first[c];
  for (std::size_t b = 0; b < nblocks; ++b) by_key[x.key_first[x.key[b]]++] = static_cast<std::uint32_t>(b);
  for (const std::uint32_t b : by_key) placed[x.next[x.col[b]]++] = b;
  if (k.spilled) placed[x.next[kOverflow]++] = static_cast<std::uint32_t>(nblocks);
  const std::size_t laid = ws.color_start.back();
  ws.block_start.resize(laid + 1);
  ws.block_id.assign(placed.begin(), placed.begin() + static_cast<std::ptrdiff_t>(laid));
  ws.block_key.resize(laid);
  for (std::size_t i = 0; i < laid; ++i)
    ws.block_key[i] = placed[i] < nblocks ? x.key[placed[i]] : static_cast<std::uint32_t>(nkeys);
  ws.keys = nkeys;
  std::uint32_t at = 0;
  for (std::size_t i = 0; i < laid; ++i) {
    ws.block_start[i] = at;
    at += x.first[placed[i] + 1] - x.first[placed[i]];
  }
  ws.block_start[laid] = at;
  return laid;
}

// 5. The system's records (with their rows and statuses) put in the layout's order, block by
//    block: each block's own range (on the threads from kLoopParallelMin contacts on: a copy of
//    every record).
void copy_records(ContactSystem& sys, NlgsColoredWorkspace& ws, std::size_t laid, int threads) {
  Scratch& x = ws.scratch;
  const std::vector<SolverContact>& c = sys.contacts;
  const std::size_t n = c.size();
  const bool with_rows = sys.rows.size() == n, with_status = sys.status.size() == n;
  x.contacts.resize(n);
  if (with_rows) x.rows.resize(n);
  if (with_status) x.status.resize(n);
  auto copy_block = [&](std::size_t i) {
    const std::uint32_t b = x.placed[i];
    std::uint32_t to = ws.block_start[i];
    for (std::uint32_t j = x.first[b]; j < x.first[b + 1]; ++j, ++to) {
      const std::uint32_t a = x.members[j];
      x.contacts[to] = c[a];
      if (with_rows) x.rows[to] = sys.rows[a];
      if (with_status) x.status[to] = sys.status[a];
    }
  };
  each_index(laid, loop_threads(n, threads), copy_block);
  sys.contacts.swap(x.contacts);  // the old arrays stay in the scratch, for the next step
  if (with_rows) sys.rows.swap(x.rows);
  if (with_status) sys.status.swap(x.status);
}

}  // namespace

std::size_t color_contacts(ContactSystem& sys, NlgsColoredWorkspace& ws, SweepOrder order, int threads) {
  const std::size_t n = sys.contacts.size();
  Blocks k = assign_blocks(sys, ws, order, threads);
  gather_members(ws.scratch, n, k.blocks, n >= kParallelMin ? threads : 1);
  if (ws.cells && order == SweepOrder::ColoredCells) sort_cells_upward(sys, ws, k.blocks, threads);
  std::uint32_t count[kOverflow + 2] = {};
  color_blocks(ws, sys.bodies.size(), k, count, n >= kParallelMin ? threads : 1);
  const std::size_t laid = lay_out_blocks(ws, k, count);
  copy_records(sys, ws, laid, threads);
  ws.arranged = &sys;
  ws.arranged_order = order;
  ws.arranged_contacts = n;
  std::size_t used = 0;
  for (unsigned c = 0; c <= kOverflow; ++c) used += ws.color_start[c + 1] > ws.color_start[c];
  return used;
}

}  // namespace nscd
