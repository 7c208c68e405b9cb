// nscd/solvers/nlgs_colored.cpp — see nlgs_colored.hpp.
#include "nscd/solvers/nlgs_colored.hpp"

#include <algorithm>
#include <bit>

#include "nscd/solvers/scene_backend.hpp"

namespace nscd {
namespace {

constexpr unsigned kOverflow = 63;  ///< colours 0 … 62 run in parallel, 63 on one thread
/// Contacts per block: n/64 within [256, 8192] — a function of the system only, never of the
/// threads. Blocks of consecutive contacts keep the fixed order's cache locality; large enough
/// to span a row of a packing, a block meets only its neighbours and two or three colours do
/// (bench_nlgs, 70,000 grains, one thread: blocks of 64 → 5 colours, 41 ns/update; 256 → 4,
/// 33 ns; 1024 and more → 2 colours, 29–30 ns, as the fixed order).
std::size_t block_size(std::size_t n) { return std::clamp<std::size_t>(n / 64, 256, 8192); }

/// Below this many contacts a sweep (~12 ns a contact) is shorter than the OpenMP region and
/// barriers it would need; the blocks are then swept on one thread, which gives the same
/// numbers (the blocks of a colour are independent) — threads never slow a small scene down.
constexpr std::size_t kParallelMin = 8192;  ///< contacts per block (fixed: the result must not depend on the threads)

/// Convergence terms of a checked sweep, one record per contact (written by whichever thread
/// visits the contact), added up afterwards in a fixed order.
struct RecordedSums {
  double* s;
  void add(std::uint32_t a, const Block2&, double pn, double pt, double lpn, double lpt) {
    double* r = s + 4 * static_cast<std::size_t>(a);
    r[0] = pn;
    r[1] = pt;
    r[2] = lpn;
    r[3] = lpt;
  }
};

}  // namespace

std::size_t color_contacts(const ContactSystem& sys, NlgsWorkspace& ws) {
  const std::vector<SolverContact>& c = sys.contacts;
  const std::size_t n = c.size();
  const std::size_t kBlock = block_size(n);
  const std::size_t nblocks = (n + kBlock - 1) / kBlock;
  ws.body_colors.assign(sys.bodies.size(), 0);
  std::vector<std::uint32_t> col(nblocks);
  std::uint32_t count[kOverflow + 2] = {};
  for (std::size_t b = 0; b < nblocks; ++b) {
    // a. the colours taken at any dynamic body of the block's contacts
    const std::size_t first = b * kBlock, last = std::min(n, first + kBlock);
    std::uint64_t taken = 0;
    for (std::size_t a = first; a < last; ++a)
      taken |= (c[a].cd_dynamic ? ws.body_colors[c[a].cd] : 0) | (c[a].an_dynamic ? ws.body_colors[c[a].an] : 0);
    // b. the lowest free one (or the overflow), marked at every dynamic body of the block
    const std::uint64_t free_colors = ~taken & ((std::uint64_t{1} << kOverflow) - 1);
    const unsigned k = free_colors ? static_cast<unsigned>(std::countr_zero(free_colors)) : kOverflow;
    if (k != kOverflow)
      for (std::size_t a = first; a < last; ++a) {
        if (c[a].cd_dynamic) ws.body_colors[c[a].cd] |= std::uint64_t{1} << k;
        if (c[a].an_dynamic) ws.body_colors[c[a].an] |= std::uint64_t{1} << k;
      }
    col[b] = k;
    ++count[k + 1];
  }
  // c. blocks listed colour by colour, in block order inside a colour
  ws.color_start.assign(kOverflow + 2, 0);
  for (unsigned k = 0; k <= kOverflow; ++k) ws.color_start[k + 1] = ws.color_start[k] + count[k + 1];
  std::vector<std::uint32_t> next(ws.color_start.begin(), ws.color_start.end() - 1);
  ws.order.resize(nblocks);
  for (std::size_t b = 0; b < nblocks; ++b) ws.order[next[col[b]]++] = static_cast<std::uint32_t>(b);
  std::size_t used = 0;
  for (unsigned k = 0; k <= kOverflow; ++k) used += ws.color_start[k + 1] > ws.color_start[k];
  return used;
}

NlgsResult nlgs_iterate_colored(ContactSystem& sys, const NlgsOptions& opt, NlgsWorkspace& ws) {
  NlgsResult res;
  const std::size_t n = sys.contacts.size();
  if (n == 0 && sys.links.empty()) {
    res.converged = true;
    return res;
  }
  color_contacts(sys, ws);
  if (opt.skip_zero) {
    ws.vanish.assign(n, 0u);
    ws.level.assign(n, 1u);
  }
  ws.sums.resize(4 * n);
  SceneBackend be(sys);
  const double omega = opt.relaxation;
  const std::uint32_t* blocks = ws.order.data();
  const std::vector<std::uint32_t>& start = ws.color_start;
  const int threads = opt.threads;
  const std::size_t kBlock = block_size(n);
  // one block: its contacts in order, Gauss–Seidel (cache-friendly: consecutive contacts)
  auto sweep_block = [&](std::uint32_t b, bool check, RecordedSums& rec) {
    const std::size_t first = b * kBlock, last = std::min(n, first + kBlock);
    for (std::size_t a = first; a < last; ++a) nlgs_visit(be, static_cast<std::uint32_t>(a), opt, ws, check, omega, rec);
  };
  // 2.–4. after the colours: the overflow colour on one thread, the convergence sums in colour
  // order (fixed, whatever the threads), the links, the convergence test. True: converged.
  auto end_of_sweep = [&](int sweep, bool check, RecordedSums& rec) {
    for (std::uint32_t i = start[kOverflow]; i < start[kOverflow + 1]; ++i) sweep_block(blocks[i], check, rec);
    CriteriaAccumulator acc;
    if (check)
      for (std::uint32_t i = 0; i < start[kOverflow + 1]; ++i) {
        const std::size_t first = blocks[i] * kBlock, last = std::min(n, first + kBlock);
        for (std::size_t a = first; a < last; ++a) {
          const double* r = ws.sums.data() + 4 * a;
          acc.add(sys.contacts[a].W, r[0], r[1], r[2], r[3]);
        }
      }
    be.sweep_extra(check, acc, check ? 1.0 : omega);
    res.sweeps = sweep;
    if (!check) return false;
    res.criteria = acc.finish(opt.tol);
    res.converged = sweep >= opt.min_sweeps && converged(res.criteria, opt.policy);
    return res.converged;
  };
  if (threads == 1 || n < kParallelMin) {
    for (int sweep = 1; sweep <= opt.max_sweeps; ++sweep) {
      const bool check = sweep % opt.check_every == 0 || sweep == opt.max_sweeps;
      RecordedSums rec{ws.sums.data()};
      // 1. Colours 0 … 62, one after the other.
      for (std::uint32_t i = 0; i < start[kOverflow]; ++i) sweep_block(blocks[i], check, rec);
      if (end_of_sweep(sweep, check, rec)) break;
    }
  } else {
    // One parallel region for the whole solve: a region per sweep costs more than a small sweep.
    bool done = false;
#pragma omp parallel num_threads(threads)
    for (int sweep = 1; sweep <= opt.max_sweeps; ++sweep) {
      const bool check = sweep % opt.check_every == 0 || sweep == opt.max_sweeps;
      RecordedSums rec{ws.sums.data()};
      // 1. Colours 0 … 62: the blocks of a colour share no dynamic body, any thread may take
      //    any; the barrier closing each `omp for` separates the colours.
      for (unsigned k = 0; k < kOverflow; ++k) {
        const auto first = static_cast<std::ptrdiff_t>(start[k]), last = static_cast<std::ptrdiff_t>(start[k + 1]);
        if (first == last) continue;
#pragma omp for schedule(static)
        for (std::ptrdiff_t i = first; i < last; ++i) sweep_block(blocks[i], check, rec);
      }
      // 2.–4. on one thread; the barrier closing `single` shows every thread the verdict.
#pragma omp single
      done = end_of_sweep(sweep, check, rec);
      if (done) break;
    }
  }
  return res;
}

}  // namespace nscd
