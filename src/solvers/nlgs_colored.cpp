// nscd/solvers/nlgs_colored.cpp — the colored sweep's iteration (nlgs_iterate_colored,
// nlgs_colored.hpp): the threads' shares, the sweeps colour by colour.
// The bodies' numbering: nlgs_colored_bodies.cpp; the mixing's parts: nlgs_colored_mixing.cpp.
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
  // A planned sweep (plan_sweeps): the share's colours in one run of bundles.
  if (planned) {
    append_planned(sys.contacts, sys.bodies.data(), block_start, ws.plan.shares[u], v);
    for (unsigned k = 0; k <= colours; ++k)
      ws.bundle_split[u * per_share + k] = k == 0 ? 0 : static_cast<std::uint32_t>(v.size());
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

// thread share u's bundles b0 … b1−1 (carry: where a checked sweep split inside a block keeps
// its lanes' sums)
void ColoredSolve::sweep_range(std::size_t u, std::uint32_t b0, std::uint32_t b1, bool check, LaneCarry* carry) {
  auto sweep = [&](auto* base) {
    sweep_bundles(base + b0, base + b1, sys.bodies.data(), mixing.omega(), check, ws.block_sums.data(), opt.lanes,
                  carry);
  };
  stream ? sweep(ws.share_streamed[u].data()) : sweep(ws.share_bundles[u].data());
}

// colour k, thread share u: in lanes, or scalar
void ColoredSolve::sweep_share(unsigned k, std::size_t u, bool check) {
  if (!lanes) {
    const std::uint32_t* s = ws.split.data() + k * (T + 1);
    return sweep_blocks(s[u], s[u + 1], check);
  }
  sweep_range(u, ws.bundle_split[u * per_share + k], ws.bundle_split[u * per_share + k + 1], check);
}

// Share u's blocks' sums claimed at the start of a checked sweep: thread 0 read them at the last
// check, and a block's sums written as it ends would wait for the line, and the stores after
// them too (docs/record/benchmarks-history.md §11.14).
void ColoredSolve::claim_block_sums(std::size_t u) {
  static_assert(sizeof(CriteriaAccumulator) == kCacheLine);
  for (unsigned k = 0; k < colours; ++k) {
    const std::uint32_t* s = ws.split.data() + k * (T + 1);
    for (std::uint32_t b = s[u]; b < s[u + 1]; ++b) claim_line(&ws.block_sums[b]);
  }
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

// Up to this many contacts, a solve on threads renumbers the bodies (renumber_bodies). It pays
// up to 12,200 contacts; on a settled step of 21,000 or 213,000 contacts (10 sweeps) its two
// passes over every body and contact cost more than the sweeps gain (docs/record/benchmarks-history.md §11.6).
constexpr std::size_t kRenumberMax = 16384;

void ColoredSolve::run_one_thread() {
  PartClock& c = clock(0);
  c.start(opt.profile);
  if (lanes) build_share(0);
  c.lap(PartClock::Setup);
  for (int sweep = 1; sweep <= opt.max_sweeps; ++sweep) {
    const bool check = sweep % opt.check_every == 0 || sweep == opt.max_sweeps;
    // 1. Colours 0 … 62, one after the other.
    for (unsigned k = 0; k < colours; ++k) sweep_share(k, 0, check);
    c.lap(PartClock::Sweeping);
    const bool over = end_of_sweep(sweep, check);
    c.lap(PartClock::Serial);
    if (over) break;
    mix_step(sweep);
    c.lap(PartClock::Mixing);
  }
  if (lanes) finish_share(0);
  c.lap(PartClock::Setup);
}

// A small system's sweeps planned lane by lane (nlgs_plan.hpp): every colour in one run of
// bundles per share, the shares planned together, on threads with the stops where they wait
// for each other; the tail (the overflow and the links) is share 0's, after its bundles. What
// the plan reads, and its start; one thread plans it all (plan_lanes), or with `team` the
// threads each their share (plan_on_threads).
void ColoredSolve::plan_sweeps(bool team) {
  std::vector<std::uint32_t>& tail = ws.plan_tail;
  tail.clear();
  auto add = [&](std::uint32_t i) {
    if (is_dynamic(sys.bodies[i])) tail.push_back(i);
  };
  for (std::uint32_t a = block_start[start[kOverflow]]; a < n && T > 1; ++a)
    add(sys.contacts[a].cd), add(sys.contacts[a].an);
  for (std::size_t l = 0; l < sys.links.size() && T > 1; ++l) add(sys.links[l].cd), add(sys.links[l].an);
  PlanInput& in = plan_in;
  in.contacts = &sys.contacts;
  in.n_bodies = sys.bodies.size();
  in.block_start = block_start;
  in.colour_start = start;
  in.colours = colours;
  in.shares = T;
  in.split = T > 1 ? ws.split.data() : nullptr;
  in.tail = &tail;
  if (!team) return plan_lanes(in, ws.plan);
  plan_start(in, ws.plan);
}

// One thread: whether the plan, where a colour's idle lanes take the next colours' blocks,
// needs fewer passes of the lane kernel than the colours dealt one after the other, where the
// deal moves blocks between a colour's lanes until they end together (append_bundles). Either
// gives the same numbers; which needs fewer passes depends on the blocks' lengths.
bool ColoredSolve::plan_pays() {
  const bool halves = lane_width() == 4;
  std::uint32_t dealt = 0;
  for (unsigned k = 0; k < colours; ++k)
    dealt += dealt_passes(block_start, start[k], start[k + 1], halves, ws.scratch.rank);
  // (no plan passes the contacts in fewer than one a lane of a pass)
  const std::uint32_t lanes_a_pass = halves ? ContactBundle::kLanes / 2 : ContactBundle::kLanes;
  const std::uint32_t least = (block_start[start[colours]] + lanes_a_pass - 1) / lanes_a_pass;
  if (dealt <= least) return false;
  plan_sweeps(false);
  return planned_passes(ws.plan.shares[0], halves, ws.plan.spans) < dealt;
}

// Thread t plans share t, colour by colour (the team meeting between colours), then numbers its
// lanes; the stops follow once every share is built (run_threads: plan_end).
void ColoredSolve::plan_on_threads(std::size_t t, SpinBarrier& barrier, unsigned& sense) {
  for (unsigned k = 0; k < colours; ++k) {
    if (k > 0) barrier.wait(sense, t);
    plan_colour(plan_in, ws.plan, k, t);
  }
  plan_share(ws.plan, t);
}

// Thread t's share of one planned sweep, stop by stop: its bundles up to the stop, then its
// progress published, or a wait until another share has swept the steps a contact of its next
// bundle follows (`done`: each share's steps swept, on its own line; `seen`: what thread t last
// read there, so that a wait already met reads no other core's line, nor cuts the run of
// bundles: a cut costs as much as a few contacts, docs/record/benchmarks-history.md §11.12); past a step's
// waits, the bodies the other shares wrote asked for all at once, their misses overlapping.
void ColoredSolve::sweep_planned(std::size_t t, unsigned sweep, bool check, OwnLine<std::atomic<unsigned>>* done,
                                 std::vector<unsigned>& seen) {
  const SharePlan& s = ws.plan.shares[t];
  const unsigned base = (sweep - 1) * s.steps();
  auto target = [&](const ShareStop& stop) {
    return std::int64_t{sweep - 1} * ws.plan.shares[stop.share].steps() + stop.need;
  };
  auto met = [&](const ShareStop& stop) {
    return stop.share != ShareStop::kPublish && target(stop) <= std::int64_t{seen[stop.share]};
  };
  LaneCarry carry;
  std::size_t i = 0, f = 0;
  for (std::uint32_t at = 0;;) {
    for (; i < s.stops.size() && s.stops[i].at <= at; ++i) {
      const ShareStop& stop = s.stops[i];
      if (stop.share == ShareStop::kPublish) {
        wake(done[t].v, base + at);
      } else if (!met(stop)) {
        const std::int64_t need = target(stop);
        PartClock& c = clock(t);
        c.lap(PartClock::Sweeping);
        seen[stop.share] = wait_for(done[stop.share].v, [&](unsigned swept) { return swept >= need; });
        c.lap(PartClock::Waiting);
      }
    }
    std::size_t j = i;  // the next stop that needs this thread: a publish, or a wait not met yet
    while (j < s.stops.size() && met(s.stops[j])) ++j;
    const std::uint32_t next = j < s.stops.size() ? std::min(s.stops[j].at, s.bundles) : s.bundles;
    // (the bodies of the waits met before `next`: written already, asked for now)
    for (; f < s.fetch.size() && (s.fetch[f].first <= at || s.fetch[f].first < next); ++f)
      __builtin_prefetch(&sys.bodies[s.fetch[f].second]);
    if (next > at) sweep_range(t, at, next, check, &carry);
    if (j == s.stops.size() && next == s.bundles) break;
    at = next;
  }
}

// Colour by colour, a barrier after each: thread t's shares of the sweep (all but the tail).
void ColoredSolve::sweep_colours(std::size_t t, std::size_t team, bool check, SpinBarrier& barrier, unsigned& sense) {
  for (unsigned k = 0; k < colours; ++k) {
    for (std::size_t u = t; u < T; u += team) sweep_share(k, u, check);
    if (k + 1 == colours) break;
    clock(t).lap(PartClock::Sweeping);
    barrier.wait(sense, t);
    clock(t).lap(PartClock::Waiting);
  }
}

// One parallel region for the whole solve: a region per sweep costs more than a small sweep.
// A planned sweep (team = T) waits at its stops only, and ends at a barrier only where it is
// checked; colour by colour, a sweep meets at a barrier after each colour and at its end.
void ColoredSolve::run_threads() {
  SpinBarrier barrier;
  const auto done = std::make_unique<OwnLine<std::atomic<unsigned>>[]>(T);  // steps swept, a share each
#pragma omp parallel num_threads(threads)
  {
#ifdef _OPENMP
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const auto team = static_cast<std::size_t>(omp_get_num_threads());  // fewer than asked if OpenMP says so
#else
    const std::size_t t = 0, team = 1;
#endif
    PartClock& c = clock(t);
    c.start(opt.profile);
#pragma omp single
    {
      barrier.reset(static_cast<unsigned>(team));
      if (planned && team != T) planned = false;  // (each thread sweeps one share, or barriers)
      team_ran = team;
    }  // (the single's own barrier follows)
    unsigned sense = 0;
    if (opt.anderson > 0)  // (read and written by this thread only until the solve ends)
      for (std::size_t u = t; u < T; u += team) mixing.start_share(sys, ws.mixing.slots, u);
    if (planned) plan_on_threads(t, barrier, sense);
    if (lanes)  // the same on every thread
      for (std::size_t u = t; u < T; u += team) build_share(u);
    // the bundles are built from the bodies' inverse masses, which no sweep writes, but the
    // sweeps write the rows around them: all built before any sweep; the plan's stops listed
    if (lanes) barrier.wait_then(sense, t, [&] {
        if (planned) plan_end(plan_in, ws.plan);
        return 0u;
      });
    std::vector<unsigned> seen(T, 0);
    c.lap(PartClock::Setup);
    for (int sweep = 1; sweep <= opt.max_sweeps; ++sweep) {
      const bool check = sweep % opt.check_every == 0 || sweep == opt.max_sweeps;
      const auto s = static_cast<unsigned>(sweep);
      const unsigned end = planned ? s * ws.plan.shares[t].steps() : 0;  // (the steps swept after it)
      // 1. Colours 0 … 62: planned, or colour by colour.
      if (check)
        for (std::size_t u = t; u < T; u += team) claim_block_sums(u);
      planned ? sweep_planned(t, s, check, done.get(), seen) : sweep_colours(t, team, check, barrier, sense);
      c.lap(PartClock::Sweeping);
      // 2.–3. A planned sweep unchecked: the overflow and the links on thread 0 as its tail, no
      //    barrier; a mixing due starts at once on every thread, since each thread mixes the
      //    bodies it wrote last (set_body_slots). 2.–4. Else on thread 0 at the end's barrier,
      //    the others waiting (the overflow's bodies stay in thread 0's cache). 5. A mixing due:
      //    on every thread (mix_on_threads), after the verdict that every thread reads past the
      //    barrier.
      if (planned && !check) {
        if (t == 0) {
          end_of_sweep(sweep, false);
          c.lap(PartClock::Serial);
        }
        wake(done[t].v, end);
        if (mixing.due(sweep)) mix_on_threads(t, team, barrier, sense);
        continue;
      }
      if (planned && t != 0) wake(done[t].v, end);
      const bool over = barrier.wait_then(sense, t, [&] {
        c.lap(PartClock::Waiting);
        const bool converged = end_of_sweep(sweep, check);
        if (planned) wake(done[0].v, end);
        c.lap(PartClock::Serial);
        return converged;
      });
      c.lap(PartClock::Waiting);
      if (over) break;
      if (mixing.due(sweep)) mix_on_threads(t, team, barrier, sense);
    }
    if (lanes)
      for (std::size_t u = t; u < T; u += team) finish_share(u);
    c.lap(PartClock::Setup);
  }
}

// The layout (color_contacts, unless `ws` arranged this system), the threads' shares, and how
// the sweeps run: on threads or not, in lanes or not, planned or colour by colour.
void ColoredSolve::choose_sweeps() {
  if (ws.arranged != &sys || ws.arranged_contacts != n || ws.arranged_order != opt.order)
    color_contacts(sys, ws, opt.order, opt.threads);
  block_start = ws.block_start.data();
  start = ws.color_start.data();
  while (colours < kOverflow && start[colours + 1] > start[colours]) ++colours;
  parallel = opt.threads > 1 && (ws.cells || ws.strips || n >= kParallelMin);
  threads = parallel ? opt.threads : 1;
  T = static_cast<std::size_t>(threads);
  split_shares();
  renumbered = parallel && n <= kRenumberMax;
  // (a bundle numbers its bodies in 32-bit words: beyond kMaxLaneBodies, the scalar sweep)
  lanes = opt.lanes != 0 && !opt.skip_zero && lanes_available() && sys.bodies.size() <= kMaxLaneBodies;
  per_share = colours + 1;
  // planned (plan_sweeps): a small system on strips or cells on one thread where the plan needs
  // fewer kernel passes than the deal (run: plan_pays), or on threads where the bodies are
  // renumbered (up to kRenumberMax contacts; beyond, a colour's blocks are many and fill their
  // lanes anyway)
  planned = lanes && (T == 1 ? (ws.cells || ws.strips) && n < kParallelMin : renumbered);
  // (on threads the shares' counts of steps swept, 32 bits for the futex, stay below 2^31: a
  // step a bundle at most)
  planned = planned && (T == 1 || (std::uint64_t(opt.max_sweeps) + 1) * (n + 2) < (std::uint64_t{1} << 31));
}

NlgsResult ColoredSolve::run() {
  if (n == 0 && sys.links.empty()) {
    res.converged = true;
    return res;
  }
  choose_sweeps();
  if (opt.skip_zero) {
    ws.vanish.assign(n, 0u);
    ws.level.assign(n, 1u);
  }
  ws.block_sums.assign(ws.block_start.size(), CriteriaAccumulator{});  // an empty block adds nothing
  if (sys.status.size() != n) sys.status.resize(n, ContactStatus::Open);  // written on checked sweeps
  if (renumbered) renumber_bodies();
  if (opt.anderson > 0) {
    if (parallel) {
      set_body_slots();
      set_mix_slots();
    }
    mixing.start(sys, parallel ? &ws.mixing.slots : nullptr);
    set_mix_chunks();
  }
  if (planned && parallel) plan_sweeps(true);
  if (planned && !parallel) planned = plan_pays();  // (planning first on one thread)
  // bundles larger than the last-level cache are streamed: without the inverse masses, which the
  // sweeps read from the bodies, and prefetched (nlgs_lanes.hpp)
  stream = lanes && n * (sizeof(MassBundle) / MassBundle::kLanes) > stream_bytes();
  if (lanes) {
    ws.share_bundles.resize(stream ? 0 : T);
    ws.share_streamed.resize(stream ? T : 0);
    ws.share_order.resize(T);
    ws.bundle_split.assign(T * per_share, 0);
  }
  const auto r0 = opt.profile ? PartClock::Clock::now() : PartClock::Clock::time_point{};
  if (ws.clocks.size() < T) ws.clocks.resize(T);  // (each thread starts its own, on or off)
  parallel ? run_threads() : run_one_thread();
  if (opt.profile) {  // (team_ran: 1 unless run_threads ran)
    res.parts.region = std::chrono::duration<double>(PartClock::Clock::now() - r0).count();
    res.parts.thread_seconds = res.parts.region * static_cast<double>(team_ran);
    for (std::size_t t = 0; t < team_ran; ++t) clock(t).add_to(res.parts);
  }
  if (renumbered) restore_bodies();
  res.mixes = mixing.mixes();
  return res;
}

const LanePlan* ColoredSolve::plan_only() {
  if (n == 0) return nullptr;
  choose_sweeps();
  if (!planned) return nullptr;
  plan_sweeps(false);
  return &ws.plan;
}

}  // namespace nscd::colored

namespace nscd {

NlgsResult nlgs_iterate_colored(ContactSystem& sys, const NlgsOptions& opt, NlgsColoredWorkspace& ws) {
  return colored::ColoredSolve(sys, opt, ws).run();
}

const LanePlan* plan_colored(ContactSystem& sys, const NlgsOptions& opt, NlgsColoredWorkspace& ws) {
  return colored::ColoredSolve(sys, opt, ws).plan_only();
}

}  // namespace nscd
