// nscd/solvers/nlgs_colored.cpp — the colored sweep's iteration (nlgs_iterate_colored,
// nlgs_colored.hpp): the threads' shares, the sweeps colour by colour, the bodies' numbering.
// The mixing's parts: nlgs_colored_mixing.cpp.
#include "nscd/solvers/nlgs_colored.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "nscd/core/error.hpp"
#include "nscd/solvers/nlgs_colored_solve.hpp"
#include "nscd/solvers/nlgs_lanes.hpp"

namespace nscd::colored {

ColoredSolve::ColoredSolve(ContactSystem& s, const NlgsOptions& o, NlgsColoredWorkspace& w)
    : sys(s), opt(o), ws(w), be(s), n(s.contacts.size()), mixing(o, w.mixing) {}

// each thread's share: one range of keys (blocks, or columns of cells) for all colours, about
// as many contacts each, so that a body is written by one thread only, but at the ranges'
// borders
void ColoredSolve::split_shares() {
  std::vector<std::uint32_t>& border = ws.scratch.border;
  border.assign(T + 1, 0);
  std::vector<std::uint64_t>& upto = ws.scratch.upto;  // contacts in blocks of keys before k
  upto.assign(ws.keys + 2, 0);
  for (std::size_t i = 0; i < start[kOverflow]; ++i) upto[ws.block_key[i] + 1] += block_start[i + 1] - block_start[i];
  for (std::size_t b = 0; b + 1 < upto.size(); ++b) upto[b + 1] += upto[b];
  const std::uint64_t total = upto.back();
  for (std::size_t t = 1; t < T; ++t)
    border[t] = static_cast<std::uint32_t>(std::lower_bound(upto.begin(), upto.end(), total * t / T) - upto.begin());
  border[T] = std::numeric_limits<std::uint32_t>::max();
  ws.split.resize(colours * (T + 1));
  for (unsigned k = 0; k < colours; ++k) {
    std::uint32_t* s = ws.split.data() + k * (T + 1);
    const auto b0 = ws.block_key.begin() + start[k], b1 = ws.block_key.begin() + start[k + 1];
    for (std::size_t t = 0; t <= T; ++t)
      s[t] = static_cast<std::uint32_t>(std::lower_bound(b0, b1, border[t]) - ws.block_key.begin());
  }
}

// SIMD lanes: the blocks of each thread share, colour by colour, dealt to the lanes of the
// share's bundles (built, swept and read back by the thread that sweeps the share)
template <class Bundles>
void ColoredSolve::build_bundles(std::size_t u, Bundles& v) {
  v.clear();
  // One thread on the cells or strips of a small system (below kParallelMin: a colour's
  // blocks are few, its last bundles half idle): the colours' blocks in one run of bundles, a
  // colour's idle lanes taking the next colours' blocks. A larger system's colours have many
  // blocks and fill their lanes anyway (blocks of consecutive contacts: no fewer bundles at
  // 7,000 or 70,000 grains): colour by colour, in the layout's order.
  if (T == 1 && (ws.cells || ws.strips) && n < kParallelMin) {
    ws.bundle_split[0] = 0;
    append_bundles_scheduled(sys.contacts, sys.bodies.data(), sys.bodies.size(), block_start, start, colours, v,
                             ws.lane_schedule);
    for (unsigned k = 1; k <= colours; ++k) ws.bundle_split[k] = static_cast<std::uint32_t>(v.size());
    return;
  }
  for (unsigned k = 0; k < colours; ++k) {
    const std::uint32_t* s = ws.split.data() + k * (T + 1);
    ws.bundle_split[u * per_share + k] = static_cast<std::uint32_t>(v.size());
    append_bundles(sys.contacts, sys.bodies.data(), block_start, s[u], s[u + 1], v, ws.share_order[u]);
  }
  ws.bundle_split[u * per_share + colours] = static_cast<std::uint32_t>(v.size());
}

void ColoredSolve::build_share(std::size_t u) {
  stream ? build_bundles(u, ws.share_streamed[u]) : build_bundles(u, ws.share_bundles[u]);
}

void ColoredSolve::finish_share(std::size_t u) {
  auto finish = [&](const auto& v) {
    bundle_results_to_contacts(v.data(), v.data() + v.size(), sys.contacts.data(), sys.status.data());
  };
  stream ? finish(ws.share_streamed[u]) : finish(ws.share_bundles[u]);
}

// blocks b0 … b1−1: consecutive contacts, Gauss–Seidel; on a checked sweep each block adds
// up its own convergence terms (a thread reads no other thread's contacts)
void ColoredSolve::sweep_blocks(std::uint32_t b0, std::uint32_t b1, bool check) {
  const double omega = mixing.omega();
  for (std::uint32_t b = b0; b < b1; ++b) {
    CriteriaAccumulator acc;
    SequentialSums sums{acc};
    for (std::uint32_t a = block_start[b]; a < block_start[b + 1]; ++a) nlgs_visit(be, a, opt, ws, check, omega, sums);
    if (check) ws.block_sums[b] = acc;
  }
}

// colour k, thread share u: in lanes, or scalar
void ColoredSolve::sweep_share(unsigned k, std::size_t u, bool check) {
  if (!lanes) {
    const std::uint32_t* s = ws.split.data() + k * (T + 1);
    return sweep_blocks(s[u], s[u + 1], check);
  }
  auto sweep = [&](auto* base) {
    sweep_bundles(base + ws.bundle_split[u * per_share + k], base + ws.bundle_split[u * per_share + k + 1],
                  sys.bodies.data(), mixing.omega(), check, ws.block_sums.data(), opt.lanes);
  };
  stream ? sweep(ws.share_streamed[u].data()) : sweep(ws.share_bundles[u].data());
}

// 2.–4. after the colours: the overflow colour on one thread, the blocks' sums added in the
// layout's order (fixed, whatever the threads), the links, the convergence test. True: converged.
bool ColoredSolve::end_of_sweep(int sweep, bool check) {
  sweep_blocks(start[kOverflow], start[kOverflow + 1], check);
  CriteriaAccumulator acc;
  if (check)
    for (std::uint32_t b = 0; b < start[kOverflow + 1]; ++b) acc.merge(ws.block_sums[b]);
  be.sweep_extra(check, acc, check ? 1.0 : mixing.omega());
  res.sweeps = sweep;
  if (!check) return false;
  res.criteria = acc.finish(opt.tol);
  res.converged = sweep >= opt.min_sweeps && converged(res.criteria, opt.policy);
  if (opt.anderson > 0 && !res.converged) mixing.follow(res);
  return res.converged;
}

// Each body's share: the last share whose contacts touch it (a body at a border: one of two).
// A body of no contact: with `fill`, the share of the body before it (where it lies in memory);
// without, share 0 if a link moves it, else none (T: the mixing leaves it out).
void ColoredSolve::body_owners(std::vector<std::uint32_t>& owner, bool fill) const {
  const std::size_t nb = sys.bodies.size();
  const auto none = static_cast<std::uint32_t>(T);
  owner.assign(nb, none);
  for (unsigned k = 0; k < colours; ++k)
    for (std::size_t u = 0; u < T; ++u) {
      const std::uint32_t* s = ws.split.data() + k * (T + 1);
      for (std::uint32_t a = block_start[s[u]]; a < block_start[s[u + 1]]; ++a)
        owner[sys.contacts[a].cd] = owner[sys.contacts[a].an] = static_cast<std::uint32_t>(u);
    }
  if (!fill) {
    for (std::uint32_t a = block_start[start[kOverflow]]; a < n; ++a)  // (the overflow: share 0's)
      for (std::uint32_t i : {sys.contacts[a].cd, sys.contacts[a].an}) owner[i] = owner[i] == none ? 0 : owner[i];
    for (const SolverLink& l : sys.links)
      for (std::uint32_t i : {l.cd, l.an}) owner[i] = owner[i] == none ? 0 : owner[i];
    return;
  }
  for (std::size_t i = 0; i < nb; ++i)
    if (owner[i] == none) owner[i] = i > 0 ? owner[i - 1] : 0;
}

// The bodies share by share (body_owners), each share's in their order: order[j] is the j-th
// body, split[u] the first of share u (without `fill`, only the bodies the solve moves).
void ColoredSolve::group_bodies(std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& split, bool fill) {
  const std::size_t nb = sys.bodies.size();
  std::vector<std::uint32_t>&owner = ws.scratch.placed, &next = ws.scratch.next;
  body_owners(owner, fill);
  split.assign(T + 2, 0);
  for (std::size_t i = 0; i < nb; ++i) ++split[owner[i] + 1];
  for (std::size_t u = 0; u < T; ++u) split[u + 1] += split[u];
  next.assign(split.begin(), split.end() - 2);
  order.resize(split[T]);
  for (std::size_t i = 0; i < nb; ++i)
    if (owner[i] < T) order[next[owner[i]]++] = static_cast<std::uint32_t>(i);
  split.pop_back();
}

// Up to this many contacts, a solve on threads renumbers the bodies (renumber_bodies). It pays
// up to 12,200 contacts; on a settled step of 21,000 or 213,000 contacts (10 sweeps) its two
// passes over every body and contact cost more than the sweeps gain (docs/benchmarks.md §11.6).
constexpr std::size_t kRenumberMax = 16384;

// A system on threads is solved with its bodies numbered share by share (body_owners),
// each share's in their own order: a core's hardware prefetcher fetches the lines next to those
// it is asked for, and where those are another thread's bodies (the bodies are numbered
// as the scene lists them, row after row across the threads' strips) the two cores take the
// lines from each other at every sweep (docs/benchmarks.md §11.6). The numbers do not depend
// on where a body lies in memory; restore_bodies() puts them back.
void ColoredSolve::renumber_bodies() {
  std::vector<std::uint32_t>&to_new = ws.body_new, &to_old = ws.body_old;
  group_bodies(to_old, ws.scratch.first, true);
  to_new.resize(to_old.size());
  for (std::size_t j = 0; j < to_old.size(); ++j) to_new[to_old[j]] = static_cast<std::uint32_t>(j);
  renumber(to_new);
}

void ColoredSolve::restore_bodies() { renumber(ws.body_old); }

// body i becomes body to[i], in the bodies, the contacts and the links: on the threads from
// kLoopParallelMin contacts on, each copying and moving its range of bodies, then renaming its
// range of contacts
void ColoredSolve::renumber(const std::vector<std::uint32_t>& to) {
  const int team = loop_threads(n, threads);
  ws.body_copy.resize(sys.bodies.size());
#pragma omp parallel num_threads(team) if (team > 1)
  {
    const auto [i0, i1] = thread_range(sys.bodies.size());
    std::copy(sys.bodies.data() + i0, sys.bodies.data() + i1, ws.body_copy.data() + i0);
#pragma omp barrier
    for (std::size_t i = i0; i < i1; ++i) sys.bodies[to[i]] = ws.body_copy[i];
    const auto [a0, a1] = thread_range(n);
    for (SolverContact* c = sys.contacts.data() + a0; c != sys.contacts.data() + a1; ++c)
      c->cd = to[c->cd], c->an = to[c->an];
  }
  for (SolverLink& l : sys.links) l.cd = to[l.cd], l.an = to[l.an];
}

void ColoredSolve::run_one_thread() {
  if (lanes) build_share(0);
  for (int sweep = 1; sweep <= opt.max_sweeps; ++sweep) {
    const bool check = sweep % opt.check_every == 0 || sweep == opt.max_sweeps;
    // 1. Colours 0 … 62, one after the other.
    for (unsigned k = 0; k < colours; ++k) sweep_share(k, 0, check);
    if (end_of_sweep(sweep, check)) break;
    mix_step(sweep);
  }
  if (lanes) finish_share(0);
}

// The contacts of run (k, u): colour k's blocks of share u; k = colours, the overflow's
// (thread 0's, the links' too)
std::pair<std::uint32_t, std::uint32_t> ColoredSolve::run_contacts(unsigned k, std::size_t u) const {
  if (k == colours) return {u == 0 ? block_start[start[kOverflow]] : 0, u == 0 ? static_cast<std::uint32_t>(n) : 0};
  const std::uint32_t* s = ws.split.data() + k * (T + 1);
  return {block_start[s[u]], block_start[s[u + 1]]};
}

// The dynamic bodies that more than one share touches (the overflow and the links are thread
// 0's): each run's list (border_first, border_bodies; the overflow's run is colour `colours`).
// At every sweep their lines cross between the cores, and a sweep that meets them one after
// another waits for each in turn.
void ColoredSolve::list_border_bodies() {
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max(), kMany = kNone - 1;
  std::vector<std::uint32_t>&seen = ws.scratch.placed, &listed = ws.scratch.next;
  seen.assign(sys.bodies.size(), kNone);
  auto touch = [&](std::uint32_t b, std::uint32_t u) {
    if (is_dynamic(sys.bodies[b])) seen[b] = seen[b] == kNone || seen[b] == u ? u : kMany;
  };
  for (unsigned k = 0; k <= colours; ++k)
    for (std::size_t u = 0; u < T; ++u) {
      const auto [a0, a1] = run_contacts(k, u);
      for (std::uint32_t a = a0; a < a1; ++a) touch(sys.contacts[a].cd, u), touch(sys.contacts[a].an, u);
    }
  for (const SolverLink& l : sys.links) touch(l.cd, 0), touch(l.an, 0);
  listed.assign(sys.bodies.size(), kNone);
  ws.border_first.assign(1, 0);
  ws.border_bodies.clear();
  for (unsigned k = 0; k <= colours; ++k)
    for (std::size_t u = 0; u < T; ++u) {
      const auto r = static_cast<std::uint32_t>(k * T + u);
      auto list = [&](std::uint32_t b) {
        if (seen[b] == kMany && listed[b] != r) ws.border_bodies.push_back(b), listed[b] = r;
      };
      const auto [a0, a1] = run_contacts(k, u);
      for (std::uint32_t a = a0; a < a1; ++a) list(sys.contacts[a].cd), list(sys.contacts[a].an);
      for (std::size_t l = 0; k == colours && u == 0 && l < sys.links.size(); ++l)
        list(sys.links[l].cd), list(sys.links[l].an);
      ws.border_first.push_back(static_cast<std::uint32_t>(ws.border_bodies.size()));
    }
}

// The waits between the threads' runs (ws.waits), the overflow's run (thread 0's) the sweep's
// last. Run (k, u) and a run of another share v touch one dynamic body only at the border; the
// last of v's runs before (k, u) that touches one of its border bodies is the one to wait for
// (the earlier ones are done before it; the blocks of one colour share no dynamic body): in
// this sweep if one does, else in the last sweep. Colour by colour: the waits from the colours
// before, then this colour's touches; then the last sweep's, from the whole sweep's touches.
void ColoredSolve::list_waits() {
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  const std::size_t runs = (colours + 1) * T;
  std::vector<std::uint32_t>& row = ws.scratch.next;  // a border body's row of ws.wait_last
  std::vector<std::uint32_t>& last = ws.wait_last;    // … each share's last colour there, + 1
  row.assign(sys.bodies.size(), kNone);
  std::uint32_t rows = 0;
  for (const std::uint32_t b : ws.border_bodies)
    if (row[b] == kNone) row[b] = rows++;
  last.assign(std::size_t{rows} * T, 0);
  ws.waits.assign(runs * T, kNoWait);
  auto each_border = [&](std::size_t r, const auto& f) {
    for (std::uint32_t i = ws.border_first[r]; i < ws.border_first[r + 1]; ++i)
      f(last.data() + std::size_t{row[ws.border_bodies[i]]} * T);
  };
  auto wait_at_least = [&](std::size_t r, std::size_t v, std::int32_t w) {
    std::int32_t& at = ws.waits[r * T + v];
    at = at == kNoWait ? w : std::max(at, w);
  };
  for (unsigned k = 0; k <= colours; ++k) {
    for (std::size_t u = 0; u < T; ++u)
      each_border(k * T + u, [&](const std::uint32_t* at) {
        for (std::size_t v = 0; v < T; ++v)
          if (v != u && at[v] > 0) wait_at_least(k * T + u, v, static_cast<std::int32_t>(at[v]));
      });
    for (std::size_t u = 0; u < T; ++u) each_border(k * T + u, [&](std::uint32_t* at) { at[u] = k + 1; });
  }
  const auto per_sweep = static_cast<std::int32_t>(colours + 1);
  for (std::size_t r = 0; r < runs; ++r)
    for (std::size_t v = 0; v < T; ++v) {
      if (v == r % T || ws.waits[r * T + v] != kNoWait) continue;
      std::uint32_t prev = 0;
      each_border(r, [&](const std::uint32_t* at) { prev = std::max(prev, at[v]); });
      if (prev > 0) ws.waits[r * T + v] = static_cast<std::int32_t>(prev) - per_sweep;
    }
}

// Before run (k, t) of the sweep whose runs count from `base`: thread t waits until each other
// thread v has swept the runs ws.waits names (`done`: each thread's runs swept, on its own line;
// `seen`: what thread t last read there, so that a wait already met reads no other core's line).
void ColoredSolve::wait_for_runs(unsigned k, std::size_t t, unsigned base, const OwnLine<std::atomic<unsigned>>* done,
                                 std::vector<unsigned>& seen) const {
  const std::int32_t* need = ws.waits.data() + (k * T + t) * T;
  for (std::size_t v = 0; v < T; ++v) {
    if (need[v] == kNoWait || static_cast<std::int64_t>(base) + need[v] <= std::int64_t{seen[v]}) continue;
    const auto target = static_cast<unsigned>(static_cast<std::int64_t>(base) + need[v]);
    seen[v] = wait_for(done[v].v, [&](unsigned swept) { return swept >= target; });
  }
}

// A run's border bodies asked for all at once before its sweep (after the colour's barrier, or
// the runs it waits for: what the other cores wrote to them is final), their misses overlapping.
void ColoredSolve::fetch_border_bodies(std::size_t run) const {
  for (std::uint32_t i = ws.border_first[run]; i < ws.border_first[run + 1]; ++i)
    __builtin_prefetch(&sys.bodies[ws.border_bodies[i]]);
}

// One parallel region for the whole solve: a region per sweep costs more than a small sweep.
void ColoredSolve::run_threads() {
  SpinBarrier barrier;
  const auto done = std::make_unique<OwnLine<std::atomic<unsigned>>[]>(T);  // runs swept, a thread each
#pragma omp parallel num_threads(threads)
  {
#ifdef _OPENMP
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const auto team = static_cast<std::size_t>(omp_get_num_threads());  // fewer than asked if OpenMP says so
#else
    const std::size_t t = 0, team = 1;
#endif
#pragma omp single
    barrier.reset(static_cast<unsigned>(team));  // (the single's own barrier follows)
    unsigned sense = 0;
    if (lanes) {  // the same on every thread
      for (std::size_t u = t; u < T; u += team) build_share(u);
      // the bundles are built from the bodies' inverse masses, which no sweep writes, but the
      // sweeps write the rows around them: all built before any sweep
#pragma omp barrier
    }
    const bool waits = !ws.waits.empty() && team == T;  // (else barriers)
    std::vector<unsigned> seen(T, 0);
    for (int sweep = 1; sweep <= opt.max_sweeps; ++sweep) {
      const bool check = sweep % opt.check_every == 0 || sweep == opt.max_sweeps;
      const unsigned base = static_cast<unsigned>(sweep - 1) * (colours + 1);  // (runs swept before it)
      // 1. Colours 0 … 62: the blocks of a colour share no dynamic body; each thread sweeps its
      //    share, after the other threads' runs that touch its border bodies before it
      //    (wait_for_runs), or after a barrier between the colours.
      for (unsigned k = 0; k < colours; ++k) {
        for (std::size_t u = t; u < T; u += team) {
          if (waits) wait_for_runs(k, t, base, done.get(), seen);
          fetch_border_bodies(k * T + u), sweep_share(k, u, check);
        }
        if (waits)
          wake(done[t].v, base + k + 1);
        else if (k + 1 < colours)
          barrier.wait(sense, t);
      }
      // 2.–3. An unchecked sweep without a mixing, the threads waiting for runs: the overflow
      //    and the links on thread 0 as its last run, no barrier. 2.–4. Else on thread 0 at
      //    the end's barrier, the others waiting (the overflow's bodies stay in thread 0's
      //    cache). 5. A mixing due: on every thread (mix_on_threads), after the verdict that
      //    every thread reads past the barrier.
      if (waits && !check && !mixing.due(sweep)) {
        if (t == 0) wait_for_runs(colours, 0, base, done.get(), seen), end_of_sweep(sweep, false);
        wake(done[t].v, base + colours + 1);
        continue;
      }
      if (waits && t != 0) wake(done[t].v, base + colours + 1);
      const bool over = barrier.wait_then(sense, t, [&] {
        const bool converged = end_of_sweep(sweep, check);
        if (waits) wake(done[0].v, base + colours + 1);
        return converged;
      });
      if (over) break;
      if (mixing.due(sweep)) mix_on_threads(t, team, barrier, sense);
    }
    if (lanes)
      for (std::size_t u = t; u < T; u += team) finish_share(u);
  }
}

NlgsResult ColoredSolve::run() {
  if (n == 0 && sys.links.empty()) {
    res.converged = true;
    return res;
  }
  if (ws.arranged != &sys || ws.arranged_contacts != n || ws.arranged_order != opt.order)
    color_contacts(sys, ws, opt.order, opt.threads);
  if (opt.skip_zero) {
    ws.vanish.assign(n, 0u);
    ws.level.assign(n, 1u);
  }
  ws.block_sums.assign(ws.block_start.size(), CriteriaAccumulator{});  // an empty block adds nothing
  if (sys.status.size() != n) sys.status.resize(n, ContactStatus::Open);  // written on checked sweeps
  block_start = ws.block_start.data();
  start = ws.color_start.data();
  while (colours < kOverflow && start[colours + 1] > start[colours]) ++colours;
  parallel = opt.threads > 1 && (ws.cells || ws.strips || n >= kParallelMin);
  threads = parallel ? opt.threads : 1;
  T = static_cast<std::size_t>(threads);
  split_shares();
  const bool renumbered = parallel && n <= kRenumberMax;
  if (renumbered) renumber_bodies();
  ws.waits.clear();
  if (renumbered) {
    list_border_bodies();
    list_waits();
  } else if (parallel) {  // (a large system's borders are a small part of its sweep: no lists)
    ws.border_first.assign((colours + 1) * T + 1, 0);
  }
  if (opt.anderson > 0) {
    if (parallel) {
      set_body_slots();
      set_mix_slots();
    }
    mixing.start(sys, parallel ? &ws.mixing.slots : nullptr);
    set_mix_chunks();
  }
  lanes = opt.lanes != 0 && !opt.skip_zero && lanes_available();
  per_share = colours + 1;
  // bundles larger than the last-level cache are streamed: without the inverse masses, which the
  // sweeps read from the bodies, and prefetched (nlgs_lanes.hpp)
  stream = lanes && n * (sizeof(MassBundle) / MassBundle::kLanes) > stream_bytes();
  if (lanes) {
    ws.share_bundles.resize(stream ? 0 : T);
    ws.share_streamed.resize(stream ? T : 0);
    ws.share_order.resize(T);
    ws.bundle_split.assign(T * per_share, 0);
  }
  parallel ? run_threads() : run_one_thread();
  if (renumbered) restore_bodies();
  res.mixes = mixing.mixes();
  return res;
}

}  // namespace nscd::colored

namespace nscd {

NlgsResult nlgs_iterate_colored(ContactSystem& sys, const NlgsOptions& opt, NlgsColoredWorkspace& ws) {
  return colored::ColoredSolve(sys, opt, ws).run();
}

}  // namespace nscd
