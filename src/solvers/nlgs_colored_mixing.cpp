// nscd/solvers/nlgs_colored_mixing.cpp — the Anderson mixing of a colored solve
// (nlgs_colored_solve.hpp): on one thread, and on several, each thread mixing what it sweeps in
// a region of the mixer's arrays on pages of its own.
#include <algorithm>
#include <limits>

#include "nscd/core/error.hpp"
#include "nscd/solvers/nlgs_colored_solve.hpp"
#include "nscd/solvers/nlgs_lanes.hpp"

namespace nscd::colored {

// 5. Anderson mixing, every kMixPeriod sweeps: the impulses (from the bundles, or the
//    contacts; the overflow colour's are always in the contacts) and the velocities out, the
//    mixed ones back, the projection's changes propagated. One thread; the sums block by block,
//    added in block order (set_mix_chunks), as on several threads.
void ColoredSolve::mix_step(int sweep) {
  if (!mixing.due(sweep)) return;
  double* x = mixing.x();
  const std::size_t scalar_from = lanes ? block_start[start[kOverflow]] : 0;
  auto out = [&](const auto& shares) {
    for (const auto& b : shares) bundle_impulses_to(b.data(), b.data() + b.size(), x);
  };
  auto in = [&](auto& shares) {
    for (auto& b : shares) bundle_impulses_from(b.data(), b.data() + b.size(), x);
  };
  if (lanes) stream ? out(ws.share_streamed) : out(ws.share_bundles);
  mixing.gather(sys, scalar_from);
  if (!mixing.mix()) return;
  if (lanes) stream ? in(ws.share_streamed) : in(ws.share_bundles);
  mixing.scatter(sys, scalar_from);
}

// The mixing's sums chunk by chunk, a chunk a block (the overflow's blocks, then the links: a
// chunk each), so that the threads each sum the blocks they sweep and the numbers do not depend
// on the threads (AndersonMixer::set_chunks). On threads, each block where its run's slots put
// it (set_mix_slots).
void ColoredSolve::set_mix_chunks() {
  std::vector<std::size_t>& bounds = ws.mixing.chunks;
  const std::uint32_t blocks = start[kOverflow + 1];
  if (parallel) {
    std::vector<std::size_t>& ends = ws.mixing.chunk_ends;
    const MixSlots& m = ws.mixing.slots;
    bounds.clear();
    ends.clear();
    each_run([&](std::size_t r, std::uint32_t b0, std::uint32_t b1) {
      for (std::uint32_t b = b0; b < b1; ++b) {
        bounds.push_back(2 * static_cast<std::size_t>(block_start[b] + m.shift[r]));
        ends.push_back(2 * static_cast<std::size_t>(block_start[b + 1] + m.shift[r]));
      }
    });
    if (!sys.links.empty()) {
      bounds.push_back(2 * m.contacts);
      ends.push_back(2 * m.contacts + sys.links.size());
    }
    return ws.mixing.mixer.set_chunks(bounds, ends);
  }
  bounds.assign(1, 0);
  for (std::uint32_t b = 1; b <= blocks; ++b) bounds.push_back(2 * std::size_t{block_start[b]});
  if (bounds.back() != 2 * n) throw Error("colored NLGS: the blocks do not hold every contact");
  const std::size_t nx = ws.mixing.mixer.impulses();
  if (bounds.back() != nx) bounds.push_back(nx);
  ws.mixing.mixer.set_chunks(bounds);
}

// On threads, the mixer's velocities in slots share by share (group_bodies), so that each thread
// gathers, mixes and scatters the velocities it writes last in a sweep (the overflow's and the
// links': thread 0's), and a planned sweep's mixing needs no barrier before it. Each entry is
// mixed on its own: the slots do not change the numbers; a body no contact or link touches
// keeps its velocity through the solve and is left out (NlgsMixing::start).
void ColoredSolve::set_body_slots() {
  std::vector<std::uint32_t>& owner = ws.scratch.placed;
  if (renumbered) {  // (renumber_bodies found them, in the old numbers)
    owner.resize(ws.body_share.size());
    for (std::size_t i = 0; i < owner.size(); ++i) owner[ws.body_new[i]] = ws.body_share[i];
  } else {
    contact_owners(owner);
  }
  finish_owners(owner, false);
  NlgsMixingBuffers& buf = ws.mixing;
  group_bodies(owner, buf.bodies, buf.body_split);
  buf.runs.clear();
  buf.run_split.assign(1, 0);
  for (std::size_t u = 0; u < T; ++u) {
    NlgsMixing::list_runs(buf.bodies.data(), buf.body_split[u], buf.body_split[u + 1], buf.runs);
    buf.run_split.push_back(static_cast<std::uint32_t>(buf.runs.size()));
  }
  buf.moves.resize(T);
}

// each contact range a thread owns in the mixing, in contact order: its shares' blocks colour
// by colour, and on thread 0 the overflow's; f(first block, end block, the run's shift in the
// mixer: MixSlots)
template <class F>
void ColoredSolve::own_contacts(std::size_t t, std::size_t team, const F& f) const {
  const std::int64_t* shift = ws.mixing.slots.shift.data();
  for (unsigned k = 0; k < colours; ++k)
    for (std::size_t u = t; u < T; u += team) {
      const std::uint32_t* s = ws.split.data() + k * (T + 1);
      f(s[u], s[u + 1], std::ptrdiff_t{shift[k * T + u]});  // blocks
    }
  if (t == 0) f(start[kOverflow], start[kOverflow + 1], std::ptrdiff_t{shift[colours * T]});
}

// f(run, first block, end block) for each run of the threads' layout in block order: colour by
// colour each share's blocks (run k·T + u), then the overflow's (run colours·T)
template <class F>
void ColoredSolve::each_run(const F& f) const {
  for (unsigned k = 0; k < colours; ++k)
    for (std::size_t u = 0; u < T; ++u) {
      const std::uint32_t* s = ws.split.data() + k * (T + 1);
      f(k * T + u, s[u], s[u + 1]);
    }
  f(colours * T, start[kOverflow], start[kOverflow + 1]);
}

// On threads, each share's runs of contacts (its colours', and the overflow on share 0) one
// after the other in a region of the mixer's arrays that starts a whole number of pages into
// them, and each share's bodies likewise (MixSlots): a region on lines of its own keeps two
// cores from writing one line, and one on pages of its own keeps a core's prefetchers, which run
// ahead within a page, from fetching the other core's lines (docs/record/benchmarks-history.md
// §11.9; the mixer skews each array a few lines into its first page, so a region's last page may
// share those lines with the next region's first). The chunks' sums are still added in block order.
void ColoredSolve::set_mix_slots() {
  constexpr std::size_t kSlots = kPage / sizeof(double);  // (a page of flags or cones, two of impulses)
  auto page_up = [](std::size_t i) { return round_up(i, kSlots); };
  MixSlots& m = ws.mixing.slots;
  m.shift.assign(colours * T + 1, 0);
  std::size_t slot = 0, next = 0;
  m.region.clear();
  for (std::size_t u = 0; u < T; ++u) {
    slot = page_up(slot);
    m.region.push_back(slot);
    each_run([&](std::size_t r, std::uint32_t b0, std::uint32_t b1) {
      if (MixSlots::share_of(r, colours * T + 1, T) != u) return;
      m.shift[r] = static_cast<std::int64_t>(slot) - block_start[b0];
      slot += block_start[b1] - block_start[b0];
    });
  }
  m.block_shift.resize(start[kOverflow + 1]);
  each_run([&](std::size_t r, std::uint32_t b0, std::uint32_t b1) {
    std::fill(m.block_shift.data() + b0, m.block_shift.data() + b1, m.shift[r]);
  });
  m.first.clear();
  each_run([&](std::size_t, std::uint32_t b0, std::uint32_t b1) {
    if (block_start[b0] != next) throw Error("colored NLGS: the threads' runs do not follow one another");
    next = block_start[b1];
    m.first.push_back(block_start[b0]);
  });
  if (next != n) throw Error("colored NLGS: the threads' runs do not hold every contact");
  m.first.push_back(static_cast<std::uint32_t>(n));
  m.contacts = page_up(slot);
  m.region.push_back(m.contacts);
  const std::vector<std::uint32_t>& split = ws.mixing.body_split;
  m.body_shift.clear();
  m.body_region.clear();
  slot = 0;
  for (std::size_t u = 0; u < T; ++u) {
    slot = page_up(slot);  // (three pages of velocities)
    m.body_region.push_back(slot);
    m.body_shift.push_back(static_cast<std::int64_t>(slot) - split[u]);
    slot += split[u + 1] - split[u];
  }
  m.bodies = page_up(slot);
  m.body_region.push_back(m.bodies);
}

// A thread's entries into the mixer (out) or back (in), each at its slot: the impulses of its
// blocks (from its bundles, or its contacts; the overflow's always from the contacts), its
// bodies' velocities; on thread 0 the links' impulses too.
void ColoredSolve::exchange_on_threads(std::size_t t, std::size_t team, bool out) {
  double* x = mixing.x();
  const NlgsMixingBuffers& buf = ws.mixing;
  const MixSlots& slots = buf.slots;
  for (std::size_t u = t; u < T && lanes; u += team) {  // the share's bundles, each block at its run's slots
    auto pass = [&](auto& b) {
      out ? bundle_impulses_to(b.data(), b.data() + b.size(), x, slots.block_shift.data())
          : bundle_impulses_from(b.data(), b.data() + b.size(), x, slots.block_shift.data());
    };
    stream ? pass(ws.share_streamed[u]) : pass(ws.share_bundles[u]);
  }
  const std::uint32_t overflow = block_start[start[kOverflow]];
  own_contacts(t, team, [&](std::uint32_t b0, std::uint32_t b1, std::ptrdiff_t shift) {
    if (lanes && block_start[b0] < overflow) return;
    out ? mixing.gather_contacts(sys, block_start[b0], block_start[b1], shift)
        : mixing.scatter_contacts(sys, block_start[b0], block_start[b1], shift);
  });
  for (std::size_t u = t; u < T; u += team) {
    const std::uint32_t r0 = buf.run_split[u], r1 = buf.run_split[u + 1];
    out ? mixing.gather_bodies(sys, r0, r1, slots.body_shift[u])
        : mixing.scatter_bodies(sys, r0, r1, slots.body_shift[u]);
  }
  if (t == 0) out ? mixing.gather_links(sys) : mixing.scatter_links(sys);
}

// 5. on the threads (every thread calls it): mix_step's passes, each thread on what it sweeps —
//    its entries out (exchange_on_threads), its blocks' sums; thread 0 the overflow's and the
//    links', then γ from every block's sums in block order; each thread its entries mixed,
//    projected and back. Then thread 0 propagates the projection's moves in contact order.
//    Nothing a thread mixes was written by another since its last sweep: no impulse or
//    velocity travels between cores. Thread 0's parts run inside the barriers
//    (SpinBarrier::wait_then): one barrier, or two when it mixes.
void ColoredSolve::mix_on_threads(std::size_t t, std::size_t team, SpinBarrier& barrier, unsigned& sense) {
  AndersonMixer& mixer = ws.mixing.mixer;
  NlgsMixingBuffers& buf = ws.mixing;
  PartClock& c = clock(t);
  exchange_on_threads(t, team, true);
  if (!mixer.restarting()) {
    own_contacts(t, team, [&](std::uint32_t b0, std::uint32_t b1, std::ptrdiff_t) { mixer.sums(b0, b1); });
    if (t == 0) mixer.sums(start[kOverflow + 1], mixer.chunks());  // the links'
  }
  c.lap(PartClock::Mixing);
  const auto verdict = static_cast<AndersonMixer::Verdict>(barrier.wait_then(sense, t, [&] {
    c.lap(PartClock::Waiting);
    const auto v = static_cast<unsigned>(mixer.decide(buf.mu.data()));
    c.lap(PartClock::Serial);
    return v;
  }));
  c.lap(PartClock::Waiting);
  std::vector<AndersonMixer::Move>& moves = buf.moves[t].v;
  moves.clear();
  own_contacts(t, team, [&](std::uint32_t b0, std::uint32_t b1, std::ptrdiff_t shift) {
    mixer.apply_x(2 * static_cast<std::size_t>(block_start[b0] + shift),
                  2 * static_cast<std::size_t>(block_start[b1] + shift), moves, shift);
  });
  if (t == 0) mixer.apply_x(2 * mixer.contacts(), mixer.impulses(), moves);  // the links'
  for (std::size_t u = t; u < T; u += team) {
    const std::ptrdiff_t shift = buf.slots.body_shift[u];
    mixer.apply_v(3 * static_cast<std::size_t>(buf.body_split[u] + shift),
                  3 * static_cast<std::size_t>(buf.body_split[u + 1] + shift));
  }
  c.lap(PartClock::Mixing);
  // (unmixed, only the mixer's own entries changed, each on the thread that will read it next)
  if (verdict != AndersonMixer::Verdict::Mixed) return;
  exchange_on_threads(t, team, false);
  c.lap(PartClock::Mixing);
  barrier.wait_then(sense, t, [&] {
    c.lap(PartClock::Waiting);
    propagate_moves(team);
    c.lap(PartClock::Serial);
    return 0u;
  });
  c.lap(PartClock::Waiting);
}

// the threads' moves (each list in contact order) merged in contact order, and propagated
void ColoredSolve::propagate_moves(std::size_t team) {
  std::vector<OwnLine<std::vector<AndersonMixer::Move>>>& lists = ws.mixing.moves;
  auto moves = [&lists](std::size_t t) -> const std::vector<AndersonMixer::Move>& { return lists[t].v; };
  std::vector<AndersonMixer::Move>& all = ws.mixing.merged;
  std::vector<std::uint32_t>& at = ws.scratch.first;
  all.clear();
  at.assign(team, 0);
  for (;;) {
    std::size_t pick = team;
    for (std::size_t t = 0; t < team; ++t)
      if (at[t] < moves(t).size() && (pick == team || moves(t)[at[t]].contact < moves(pick)[at[pick]].contact))
        pick = t;
    if (pick == team) break;
    all.push_back(moves(pick)[at[pick]++]);
  }
  NlgsMixing::propagate(sys, all);
}

}  // namespace nscd::colored
