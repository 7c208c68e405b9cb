// nscd/solvers/nlgs_colored.cpp — the colored sweep's iteration (nlgs_iterate_colored,
// nlgs_colored.hpp): the threads' shares, the sweeps colour by colour, the Anderson mixing.
#include "nscd/solvers/nlgs_colored.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <thread>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "nscd/core/error.hpp"
#include "nscd/solvers/nlgs_blocks.hpp"
#include "nscd/solvers/nlgs_lanes.hpp"
#include "nscd/solvers/nlgs_mixing.hpp"
#include "nscd/solvers/scene_backend.hpp"

namespace nscd {
namespace {

using colored::kOverflow;

/// A barrier that spins: the colours of a small system are a microsecond apart, and OpenMP's
/// barrier costs several times more than this one (docs/benchmarks.md §8). After a few thousand
/// spins a waiting thread yields, in case it shares its core with another. wait_then(serial):
/// thread 0 waits for the others, runs `serial` and only then lets them go, so that a serial
/// part between two phases costs one barrier, not two (a barrier's cost is one round trip of a
/// cache line between cores, which is most of it on a small system: §11.7).
class SpinBarrier {
 public:
  void reset(unsigned team) {
    team_ = team;
    count_.store(0, std::memory_order_relaxed);
    flag_.store(0, std::memory_order_relaxed);
  }
  /// `sense`: the calling thread's own, 0 before its first wait.
  void wait(unsigned& sense, std::size_t t) {
    wait_then(sense, t, [] {});
  }
  /// The others arrive (count_), thread `t` = 0 sees them all, resets the count, runs `serial`
  /// and flips the flag they spin on (acquire and release order every write around it).
  template <class F>
  void wait_then(unsigned& sense, std::size_t t, const F& serial) {
    sense ^= 1u;
    if (t == 0) {
      spin([&] { return count_.load(std::memory_order_acquire) + 1 == team_; });
      count_.store(0, std::memory_order_relaxed);
      serial();
      flag_.store(sense, std::memory_order_release);
      return;
    }
    count_.fetch_add(1, std::memory_order_acq_rel);
    spin([&] { return flag_.load(std::memory_order_acquire) == sense; });
  }

 private:
  template <class Done>
  static void spin(const Done& done) {
    for (unsigned spins = 0; !done(); ++spins) {
      if (spins < 4096) {
#if defined(__x86_64__) || defined(__i386__)
        __builtin_ia32_pause();
#endif
      } else {
        std::this_thread::yield();
      }
    }
  }
  alignas(64) std::atomic<unsigned> count_{0};
  alignas(64) std::atomic<unsigned> flag_{0};
  unsigned team_ = 1;
};

/// One colored solve, its steps as members: the threads' shares (split_shares), the bundles of
/// the SIMD lanes (build_share, finish_share), a colour's share swept (sweep_share), the end of
/// a sweep (end_of_sweep: 2.–4.), the mixing (mix_step: 5.), on one thread or several.
class ColoredSolve {
 public:
  ColoredSolve(ContactSystem& sys, const NlgsOptions& opt, NlgsColoredWorkspace& ws);
  NlgsResult run();

 private:
  void split_shares();
  void build_share(std::size_t u);
  template <class Bundles>
  void build_bundles(std::size_t u, Bundles& v);
  void finish_share(std::size_t u);
  void sweep_blocks(std::uint32_t b0, std::uint32_t b1, bool check);
  void sweep_share(unsigned k, std::size_t u, bool check);
  bool end_of_sweep(int sweep, bool check);
  void mix_step(int sweep);
  void set_mix_chunks();
  void body_owners(std::vector<std::uint32_t>& owner) const;
  void group_bodies(std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& split);
  void set_body_slots();
  void renumber_bodies();
  void restore_bodies();
  void renumber(const std::vector<std::uint32_t>& to);
  template <class F>
  void own_contacts(std::size_t t, std::size_t team, const F& f) const;
  void mix_on_threads(std::size_t t, std::size_t team, SpinBarrier& barrier, unsigned& sense);
  void propagate_moves(std::size_t team);
  void run_one_thread();
  void run_threads();

  ContactSystem& sys;
  const NlgsOptions& opt;
  NlgsColoredWorkspace& ws;
  SceneBackend be;
  NlgsResult res;
  const std::size_t n;
  NlgsMixing mixing;  ///< Anderson's (its ω: 1 while mixing, else the relaxation)
  const std::uint32_t* block_start = nullptr;
  const std::uint32_t* start = nullptr;  ///< the colours' first blocks (ws.color_start)
  unsigned colours = 0;  ///< colours 0 … colours−1 are used (greedy: the lowest free colour first)
  bool parallel = false;
  int threads = 1;
  std::size_t T = 1;
  bool lanes = false, stream = false;
  AndersonMixer::Verdict mix_verdict{};  ///< mix_on_threads: thread 0's verdict, read by all after a barrier
  std::size_t per_share = 1;
};

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
// on the threads (AndersonMixer::set_chunks).
void ColoredSolve::set_mix_chunks() {
  std::vector<std::size_t>& bounds = ws.mixing.chunks;
  const std::uint32_t blocks = start[kOverflow + 1];
  bounds.assign(1, 0);
  for (std::uint32_t b = 1; b <= blocks; ++b) bounds.push_back(2 * std::size_t{block_start[b]});
  if (bounds.back() != 2 * n) throw Error("colored NLGS: the blocks do not hold every contact");
  const std::size_t nx = ws.mixing.mixer.impulses();
  if (bounds.back() != nx) bounds.push_back(nx);
  ws.mixing.mixer.set_chunks(bounds);
}

// Each body's share: the last share whose contacts touch it (a body at a border: one of two),
// a body of no contact the share of the body before it.
void ColoredSolve::body_owners(std::vector<std::uint32_t>& owner) const {
  const std::size_t nb = sys.bodies.size();
  owner.assign(nb, std::numeric_limits<std::uint32_t>::max());
  for (unsigned k = 0; k < colours; ++k)
    for (std::size_t u = 0; u < T; ++u) {
      const std::uint32_t* s = ws.split.data() + k * (T + 1);
      for (std::uint32_t a = block_start[s[u]]; a < block_start[s[u + 1]]; ++a)
        owner[sys.contacts[a].cd] = owner[sys.contacts[a].an] = static_cast<std::uint32_t>(u);
    }
  for (std::size_t i = 0; i < nb; ++i)
    if (owner[i] >= T) owner[i] = i > 0 ? owner[i - 1] : 0;
}

// The bodies share by share (body_owners), each share's in their order: order[j] is the j-th
// body, split[u] the first of share u.
void ColoredSolve::group_bodies(std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& split) {
  const std::size_t nb = sys.bodies.size();
  std::vector<std::uint32_t>&owner = ws.scratch.placed, &next = ws.scratch.next;
  body_owners(owner);
  split.assign(T + 1, 0);
  for (std::size_t i = 0; i < nb; ++i) ++split[owner[i] + 1];
  for (std::size_t u = 0; u < T; ++u) split[u + 1] += split[u];
  next.assign(split.begin(), split.end() - 1);
  order.resize(nb);
  for (std::size_t i = 0; i < nb; ++i) order[next[owner[i]]++] = static_cast<std::uint32_t>(i);
}

// On threads, the mixer's velocities in slots share by share (group_bodies), so that each thread
// gathers, mixes and scatters the velocities it sweeps. Each entry is mixed on its own: the
// slots do not change the numbers.
void ColoredSolve::set_body_slots() {
  group_bodies(ws.mixing.bodies, ws.mixing.body_split);
  ws.mixing.moves.resize(T);
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
  group_bodies(to_old, ws.scratch.first);
  to_new.resize(to_old.size());
  for (std::size_t j = 0; j < to_old.size(); ++j) to_new[to_old[j]] = static_cast<std::uint32_t>(j);
  renumber(to_new);
}

void ColoredSolve::restore_bodies() { renumber(ws.body_old); }

// body i becomes body to[i], in the bodies, the contacts and the links
void ColoredSolve::renumber(const std::vector<std::uint32_t>& to) {
  ws.body_copy.assign(sys.bodies.begin(), sys.bodies.end());
  for (std::size_t i = 0; i < to.size(); ++i) sys.bodies[to[i]] = ws.body_copy[i];
  for (SolverContact& c : sys.contacts) c.cd = to[c.cd], c.an = to[c.an];
  for (SolverLink& l : sys.links) l.cd = to[l.cd], l.an = to[l.an];
}

// each contact range a thread owns in the mixing, in contact order: its shares' blocks colour
// by colour, and on thread 0 the overflow's
template <class F>
void ColoredSolve::own_contacts(std::size_t t, std::size_t team, const F& f) const {
  for (unsigned k = 0; k < colours; ++k)
    for (std::size_t u = t; u < T; u += team) {
      const std::uint32_t* s = ws.split.data() + k * (T + 1);
      f(s[u], s[u + 1]);  // blocks
    }
  if (t == 0) f(start[kOverflow], start[kOverflow + 1]);
}

// 5. on the threads (every thread calls it): mix_step's passes, each thread on what it sweeps —
//    the impulses of its blocks (from its bundles, or its contacts) and the velocities of its
//    bodies out, its blocks' sums; thread 0 the overflow's and the links', then γ from every
//    block's sums in block order; each thread its entries mixed, projected and back. Then
//    thread 0 propagates the projection's moves in contact order. Nothing a thread mixes was
//    written by another since its last sweep: no impulse or velocity travels between cores.
//    Thread 0's parts run inside the barriers (SpinBarrier::wait_then): one barrier, or two
//    when it mixes.
void ColoredSolve::mix_on_threads(std::size_t t, std::size_t team, SpinBarrier& barrier, unsigned& sense) {
  AndersonMixer& mixer = ws.mixing.mixer;
  NlgsMixingBuffers& buf = ws.mixing;
  double* x = mixing.x();
  auto shares = [&](auto pass) {
    for (std::size_t u = t; u < T; u += team) {
      auto run = [&](auto& b) { pass(b.data(), b.data() + b.size(), x); };
      stream ? run(ws.share_streamed[u]) : run(ws.share_bundles[u]);
    }
  };
  auto bodies = [&](auto pass) {
    for (std::size_t u = t; u < T; u += team) pass(buf.bodies.data(), buf.body_split[u], buf.body_split[u + 1]);
  };
  const std::uint32_t overflow = block_start[start[kOverflow]];
  if (lanes) shares([](auto* b0, auto* b1, double* to) { bundle_impulses_to(b0, b1, to); });
  own_contacts(t, team, [&](std::uint32_t b0, std::uint32_t b1) {
    if (!lanes || block_start[b0] >= overflow) mixing.gather_contacts(sys, block_start[b0], block_start[b1]);
  });
  bodies([&](const std::uint32_t* ids, std::size_t s0, std::size_t s1) { mixing.gather_bodies(sys, ids, s0, s1); });
  if (t == 0) mixing.gather_links(sys);
  if (!mixer.restarting()) {
    own_contacts(t, team, [&](std::uint32_t b0, std::uint32_t b1) { mixer.sums(b0, b1); });
    if (t == 0) mixer.sums(start[kOverflow + 1], mixer.chunks());  // the links'
  }
  barrier.wait_then(sense, t, [&] { mix_verdict = mixer.decide(buf.mu.data()); });
  std::vector<AndersonMixer::Move>& moves = buf.moves[t].v;
  moves.clear();
  own_contacts(t, team, [&](std::uint32_t b0, std::uint32_t b1) {
    mixer.apply_x(2 * std::size_t{block_start[b0]}, 2 * std::size_t{block_start[b1]}, moves);
  });
  if (t == 0) mixer.apply_x(2 * n, mixer.impulses(), moves);
  bodies([&](const std::uint32_t*, std::size_t s0, std::size_t s1) { mixer.apply_v(3 * s0, 3 * s1); });
  // (unmixed, only the mixer's own entries changed, each on the thread that will read it next)
  if (mix_verdict != AndersonMixer::Verdict::Mixed) return;
  if (lanes) shares([](auto* b0, auto* b1, const double* from) { bundle_impulses_from(b0, b1, from); });
  own_contacts(t, team, [&](std::uint32_t b0, std::uint32_t b1) {
    if (!lanes || block_start[b0] >= overflow) mixing.scatter_contacts(sys, block_start[b0], block_start[b1]);
  });
  bodies([&](const std::uint32_t* ids, std::size_t s0, std::size_t s1) { mixing.scatter_bodies(sys, ids, s0, s1); });
  if (t == 0) mixing.scatter_links(sys);
  barrier.wait_then(sense, t, [&] { propagate_moves(team); });
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

// One parallel region for the whole solve: a region per sweep costs more than a small sweep.
void ColoredSolve::run_threads() {
  bool done = false;
  SpinBarrier barrier;
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
    for (int sweep = 1; sweep <= opt.max_sweeps; ++sweep) {
      const bool check = sweep % opt.check_every == 0 || sweep == opt.max_sweeps;
      // 1. Colours 0 … 62: the blocks of a colour share no dynamic body; each thread sweeps
      //    its share, and a barrier separates the colours. 2.–4. on thread 0 at the last
      //    colour's barrier, the others waiting (the overflow's bodies stay in thread 0's
      //    cache): one barrier a colour, whatever comes after them. 5. A mixing due: on every
      //    thread (mix_on_threads), after the verdict that every thread reads past the barrier.
      for (unsigned k = 0; k < colours; ++k) {
        for (std::size_t u = t; u < T; u += team) sweep_share(k, u, check);
        if (k + 1 < colours) barrier.wait(sense, t);
      }
      barrier.wait_then(sense, t, [&] { done = end_of_sweep(sweep, check); });
      if (done) break;
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
  if (opt.anderson > 0) mixing.start(sys);
  block_start = ws.block_start.data();
  start = ws.color_start.data();
  while (colours < kOverflow && start[colours + 1] > start[colours]) ++colours;
  parallel = opt.threads > 1 && (ws.cells || ws.strips || n >= kParallelMin);
  threads = parallel ? opt.threads : 1;
  T = static_cast<std::size_t>(threads);
  split_shares();
  const bool renumbered = parallel && n <= kRenumberMax;
  if (renumbered) renumber_bodies();
  if (opt.anderson > 0) set_mix_chunks();
  if (opt.anderson > 0 && parallel) set_body_slots();
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

}  // namespace

NlgsResult nlgs_iterate_colored(ContactSystem& sys, const NlgsOptions& opt, NlgsColoredWorkspace& ws) {
  return ColoredSolve(sys, opt, ws).run();
}

}  // namespace nscd
