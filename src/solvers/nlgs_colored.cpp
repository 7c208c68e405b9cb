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

#include "nscd/solvers/nlgs_blocks.hpp"
#include "nscd/solvers/nlgs_lanes.hpp"
#include "nscd/solvers/scene_backend.hpp"

namespace nscd {
namespace {

using colored::kOverflow;

/// Anderson mixing (anderson.hpp): every kMixPeriod sweeps. After kStallChecks checks in a row
/// that do not bring the policy's ratio 10 % below its best since the phase began, the solve
/// goes over from mixed sweeps to relaxed ones, and from relaxed ones back to mixed ones, from a
/// fresh history (theory §9.5b, from the LMGC90 case).
constexpr int kMixPeriod = 4, kStallChecks = 5;

/// A barrier that spins: the colours of a small system are a microsecond apart, and OpenMP's
/// barrier costs several times more than this one (docs/benchmarks.md §8) (sense reversal: the
/// last thread to arrive resets the count and flips the flag). After a few thousand spins a
/// waiting thread yields, in case it shares its core with another.
class SpinBarrier {
 public:
  void reset(unsigned team) {
    team_ = team;
    count_.store(0, std::memory_order_relaxed);
    flag_.store(0, std::memory_order_relaxed);
  }
  /// `sense`: the calling thread's own, 0 before its first wait.
  void wait(unsigned& sense) {
    sense ^= 1u;
    if (count_.fetch_add(1, std::memory_order_acq_rel) + 1 == team_) {
      count_.store(0, std::memory_order_relaxed);
      flag_.store(sense, std::memory_order_release);
      return;
    }
    for (unsigned spins = 0; flag_.load(std::memory_order_acquire) != sense; ++spins) {
      if (spins < 4096) {
#if defined(__x86_64__) || defined(__i386__)
        __builtin_ia32_pause();
#endif
      } else {
        std::this_thread::yield();
      }
    }
  }

 private:
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
  void start_mixing();
  void split_shares();
  void build_share(std::size_t u);
  template <class Bundles>
  void build_bundles(std::size_t u, Bundles& v);
  void finish_share(std::size_t u);
  void sweep_blocks(std::uint32_t b0, std::uint32_t b1, bool check);
  void sweep_share(unsigned k, std::size_t u, bool check);
  bool end_of_sweep(int sweep, bool check);
  void follow_stall();
  void mix_step(int sweep);
  void run_one_thread();
  void run_threads();

  ContactSystem& sys;
  const NlgsOptions& opt;
  NlgsColoredWorkspace& ws;
  SceneBackend be;
  NlgsResult res;
  const std::size_t n;
  bool mixing;
  double omega;
  double best_ratio = HUGE_VAL;
  int stalled = 0;
  const std::uint32_t* block_start = nullptr;
  const std::uint32_t* start = nullptr;  ///< the colours' first blocks (ws.color_start)
  unsigned colours = 0;  ///< colours 0 … colours−1 are used (greedy: the lowest free colour first)
  bool parallel = false;
  int threads = 1;
  std::size_t T = 1;
  bool lanes = false, stream = false;
  std::size_t per_share = 1;
};

ColoredSolve::ColoredSolve(ContactSystem& s, const NlgsOptions& o, NlgsColoredWorkspace& w)
    : sys(s), opt(o), ws(w), be(s), n(s.contacts.size()), mixing(o.anderson > 0), omega(mixing ? 1.0 : o.relaxation) {}

// Anderson mixing: the sweeps it mixes are plain Gauss–Seidel (ω = 1); the relaxation takes
// over if it stalls, and the mixing again if the relaxed sweeps stall
void ColoredSolve::start_mixing() {
  AndersonMixer& mixer = ws.mixer;
  mixer.start(n, sys.links.size(), 3 * sys.bodies.size(), opt.anderson);
  double* x = mixer.x();
  ws.mix_mu.resize(n);
  for (std::size_t a = 0; a < n; ++a) {
    x[2 * a] = sys.contacts[a].pn;
    x[2 * a + 1] = sys.contacts[a].pt;
    ws.mix_mu[a] = sys.contacts[a].mu;
  }
  for (std::size_t l = 0; l < sys.links.size(); ++l) x[2 * n + l] = sys.links[l].p;
  mixer.begin();
}

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
    for (std::size_t t = 0; t <= T; ++t) s[t] = static_cast<std::uint32_t>(std::lower_bound(b0, b1, border[t]) - ws.block_key.begin());
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
                  sys.bodies.data(), omega, check, ws.block_sums.data(), opt.lanes);
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
  be.sweep_extra(check, acc, check ? 1.0 : omega);
  res.sweeps = sweep;
  if (!check) return false;
  res.criteria = acc.finish(opt.tol);
  res.converged = sweep >= opt.min_sweeps && converged(res.criteria, opt.policy);
  if (opt.anderson > 0 && !res.converged) follow_stall();
  return res.converged;
}

// Anderson: where a phase stalls, mixed sweeps give way to relaxed ones (the mixing stalls where
// the statuses keep changing), relaxed ones to mixed ones from a fresh history (relaxed sweeps
// can settle into a cycle that repeats the same changes)
void ColoredSolve::follow_stall() {
  const double ratio = policy_ratio(res.criteria, opt.policy);
  if (ratio < 0.9 * best_ratio) {
    best_ratio = ratio;
    stalled = 0;
  } else if (++stalled >= kStallChecks) {
    mixing = !mixing;
    omega = mixing ? 1.0 : opt.relaxation;
    if (mixing) {
      ws.mixer.restart_at_next();
      ++res.mix_returns;
    }
    best_ratio = HUGE_VAL;
    stalled = 0;
  }
}

// 5. Anderson mixing, every kMixPeriod sweeps: the impulses (from the bundles, or the
//    contacts; the overflow colour's are always in the contacts) and the velocities out, the
//    mixed ones back, the projection's changes propagated. One thread; every sum in a fixed
//    order.
void ColoredSolve::mix_step(int sweep) {
  if (!mixing || sweep % kMixPeriod != 0) return;
  AndersonMixer& mixer = ws.mixer;
  double* x = mixer.x();
  double* v = mixer.v();
  const std::size_t scalar_from = lanes ? block_start[start[kOverflow]] : 0;
  auto out = [&](const auto& shares) {
    for (const auto& b : shares) bundle_impulses_to(b.data(), b.data() + b.size(), x);
  };
  auto in = [&](auto& shares) {
    for (auto& b : shares) bundle_impulses_from(b.data(), b.data() + b.size(), x);
  };
  if (lanes) stream ? out(ws.share_streamed) : out(ws.share_bundles);
  for (std::size_t a = scalar_from; a < n; ++a) {
    x[2 * a] = sys.contacts[a].pn;
    x[2 * a + 1] = sys.contacts[a].pt;
  }
  for (std::size_t l = 0; l < sys.links.size(); ++l) x[2 * n + l] = sys.links[l].p;
  for (std::size_t i = 0; i < sys.bodies.size(); ++i) {
    v[3 * i] = sys.bodies[i].vx;
    v[3 * i + 1] = sys.bodies[i].vy;
    v[3 * i + 2] = sys.bodies[i].w;
  }
  if (!mixer.mix(ws.mix_mu.data())) return;
  if (lanes) stream ? in(ws.share_streamed) : in(ws.share_bundles);
  for (std::size_t a = scalar_from; a < n; ++a) {
    sys.contacts[a].pn = x[2 * a];
    sys.contacts[a].pt = x[2 * a + 1];
  }
  for (std::size_t l = 0; l < sys.links.size(); ++l) sys.links[l].p = x[2 * n + l];
  for (std::size_t i = 0; i < sys.bodies.size(); ++i) {
    sys.bodies[i].vx = v[3 * i];
    sys.bodies[i].vy = v[3 * i + 1];
    sys.bodies[i].w = v[3 * i + 2];
  }
  for (const AndersonMixer::Move& m : mixer.moved()) {
    const SolverContact& c = sys.contacts[m.contact];
    apply_impulse(c, sys.bodies[c.cd], sys.bodies[c.an], m.dpn, m.dpt);
  }
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
      //    its share, and a barrier separates the colours.
      for (unsigned k = 0; k < colours; ++k) {
        for (std::size_t u = t; u < T; u += team) sweep_share(k, u, check);
        barrier.wait(sense);
      }
      // 2.–4. on thread 0, always the same (the overflow's bodies stay in its cache); the
      //    barrier after it shows every thread the verdict.
      if (t == 0 && !(done = end_of_sweep(sweep, check))) mix_step(sweep);
      barrier.wait(sense);
      if (done) break;
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
  if (ws.arranged != &sys || ws.arranged_contacts != n || ws.arranged_order != opt.order) color_contacts(sys, ws, opt.order, opt.threads);
  if (opt.skip_zero) {
    ws.vanish.assign(n, 0u);
    ws.level.assign(n, 1u);
  }
  ws.block_sums.assign(ws.block_start.size(), CriteriaAccumulator{});  // an empty block adds nothing
  if (sys.status.size() != n) sys.status.resize(n, ContactStatus::Open);  // written on checked sweeps
  if (mixing) start_mixing();
  block_start = ws.block_start.data();
  start = ws.color_start.data();
  while (colours < kOverflow && start[colours + 1] > start[colours]) ++colours;
  parallel = opt.threads > 1 && (ws.cells || ws.strips || n >= kParallelMin);
  threads = parallel ? opt.threads : 1;
  T = static_cast<std::size_t>(threads);
  split_shares();
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
  res.mixes = static_cast<int>(opt.anderson > 0 ? ws.mixer.mixes() : 0);
  return res;
}

}  // namespace

NlgsResult nlgs_iterate_colored(ContactSystem& sys, const NlgsOptions& opt, NlgsColoredWorkspace& ws) {
  return ColoredSolve(sys, opt, ws).run();
}

}  // namespace nscd
