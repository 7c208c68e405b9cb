// nscd/solvers/nlgs_plan.cpp — the shares' sweeps planned lane by lane, and their stops
// (plan_lanes, nlgs_plan.hpp).
#include "nscd/solvers/nlgs_plan.hpp"

#include <algorithm>
#include <numeric>

namespace nscd {
namespace {

constexpr std::uint32_t kNone = 0xffffffffu;
// The clock of share 0's tail, after every block of the sweep: its start and its end.
constexpr std::uint32_t kTailStart = kNone - 2, kTailEnd = kNone - 1;

// share u's block b to the lane where it can start first, no earlier than `ready`: of the lanes
// free by then, the one free the latest (the shortest gap); else the one free the soonest.
// Returns its start.
std::uint32_t place_block(SharePlan& s, std::uint32_t* free_at, std::uint32_t* load, std::uint32_t b,
                          std::uint32_t ready, std::uint32_t length) {
  constexpr int K = ContactBundle::kLanes;
  int lane = -1;
  for (int j = 0; j < K; ++j)
    if (free_at[j] <= ready && (lane < 0 || free_at[j] > free_at[lane])) lane = j;
  if (lane < 0) lane = static_cast<int>(std::min_element(free_at, free_at + K) - free_at);
  const std::uint32_t start = std::max(ready, free_at[lane]);
  free_at[lane] = start + length;
  load[lane] += length;
  s.runs[lane].push_back({b, start, start + length});
  return start;
}

}  // namespace

// 1. Colour k of share u: its blocks longest first (ties: in order), each placed so that each of
//    its contacts comes after every contact planned before it on one of its dynamic bodies: on
//    threads, where a block's first contacts touch other bodies than its last it may start
//    before the blocks it follows end (a wavefront: fewer bundles for the busier share); one
//    share simply starts a block once those blocks end (a wavefront there saves few bundles,
//    and costs more planning than a settled step's few sweeps repay:
//    docs/record/benchmarks-history.md §11.11). A contact that follows another share's contact on a body waits for it
//    (LanePlan::Scratch::waits), at its own time. Only the colour's own blocks touch its
//    bodies: the colour's shares may be placed at once.
void plan_colour(const PlanInput& in, LanePlan& p, unsigned k, std::size_t u) {
  const std::vector<SolverContact>& contacts = *in.contacts;
  LanePlan::Scratch& x = p.scratch[u].v;
  auto length = [&](std::uint32_t b) { return in.block_start[b + 1] - in.block_start[b]; };
  // f(contact's offset in block b, dynamic body) for each of b's contacts in order
  auto each_body = [&](std::uint32_t b, const auto& f) {
    const std::uint32_t a0 = in.block_start[b], a1 = in.block_start[b + 1];  // (f's stores may alias them)
    for (std::uint32_t a = a0; a < a1; ++a) {
      const SolverContact& c = contacts[a];
      if (c.cd_dynamic) f(a - a0, c.cd);
      if (c.an_dynamic) f(a - a0, c.an);
    }
  };
  const std::uint32_t* s = in.split ? in.split + k * (in.shares + 1) + u : in.colour_start + k;
  x.order.clear();
  for (std::uint32_t b = s[0]; b < s[1]; ++b)
    if (length(b) > 0) x.order.push_back(b);
  std::stable_sort(x.order.begin(), x.order.end(), [&](std::uint32_t a, std::uint32_t b) { return length(a) > length(b); });
  const auto share = static_cast<std::uint32_t>(u);
  for (const std::uint32_t b : x.order) {
    std::uint32_t ready = 0;  // the block's earliest start
    if (in.shares == 1)
      each_body(b, [&](std::uint32_t, std::uint32_t i) { ready = std::max(ready, p.ready[i]); });
    else
      each_body(b, [&](std::uint32_t o, std::uint32_t i) { ready = std::max(ready, p.ready[i] > o ? p.ready[i] - o : 0); });
    const std::uint32_t start = place_block(p.shares[u], x.free_at, x.load, b, ready, length(b));
    if (in.shares == 1) {  // (one share waits for none)
      const std::uint32_t end = start + length(b);
      each_body(b, [&](std::uint32_t, std::uint32_t i) { p.ready[i] = end; });
      continue;
    }
    each_body(b, [&](std::uint32_t o, std::uint32_t i) {
      if (p.last[i] != kNone && p.last[i] != share) x.waits.push_back({share, start + o, p.last[i], p.ready[i], i});
      if (p.first_share[i] == kNone) p.first_share[i] = share, p.first_time[i] = start + o;
      p.ready[i] = start + o + 1, p.last[i] = share;
    });
  }
}

namespace {

// 1b. Share 0's tail, after its bundles: it waits for every other share's last contact on one of
//     its bodies, and becomes their last toucher.
void place_tail(const PlanInput& in, LanePlan& p) {
  if (!in.tail || in.shares == 1) return;
  for (const std::uint32_t i : *in.tail) {
    if (p.last[i] != kNone && p.last[i] != 0) p.scratch[0].v.waits.push_back({0, kTailStart, p.last[i], p.ready[i], i});
    if (p.first_share[i] == kNone) p.first_share[i] = 0, p.first_time[i] = kTailStart;
    p.ready[i] = kTailEnd, p.last[i] = 0;
  }
}

}  // namespace

// 2. A share's lanes renumbered busiest first (ties: in order), so that the idle ones are the
//    last; its span, and its bundles before each time (a time with every lane idle: none).
void plan_share(LanePlan& p, std::size_t u) {
  constexpr int K = ContactBundle::kLanes;
  SharePlan& s = p.shares[u];
  LanePlan::Scratch& x = p.scratch[u].v;
  const std::uint32_t *free_at = x.free_at, *load = x.load;
  int by_load[K];
  std::iota(by_load, by_load + K, 0);
  std::stable_sort(by_load, by_load + K, [&](int a, int b) { return load[a] > load[b]; });
  for (int j = 0; j < K; ++j) x.renumbered[j].swap(s.runs[by_load[j]]);
  for (int j = 0; j < K; ++j) s.runs[j].swap(x.renumbered[j]);
  s.span = *std::max_element(free_at, free_at + K);
  if (p.shares.size() == 1) {  // one share's lanes are never all idle before its span
    s.bundles = s.span;
    return;
  }
  s.bundle_at.assign(s.span + 1, 0);
  for (int j = 0; j < K; ++j)
    for (const LaneRun& r : s.runs[j])
      for (std::uint32_t t = r.start; t < r.end; ++t) s.bundle_at[t + 1] = 1;
  for (std::uint32_t t = 0; t < s.span; ++t) s.bundle_at[t + 1] += s.bundle_at[t];
  s.bundles = s.bundle_at[s.span];
}

namespace {

// a time on share u's clock as a step of its sweep
std::uint32_t step_at(const SharePlan& s, std::uint32_t t) {
  return t == kTailStart ? s.bundles : t == kTailEnd ? s.bundles + 1 : s.bundle_at[std::min(t, s.span)];
}

// 3. The stops: each wait at its step, for the other share's step (in this sweep; a body's
//    first toucher in the sweep, for its last toucher in the last sweep: need − steps), the
//    other share's publishing there, and the body fetched past the wait; sorted by step,
//    publishes first, a share's waits at one step merged (the latest).
void list_stops(const PlanInput& in, LanePlan& p) {
  auto wait = [&](std::uint32_t u, std::uint32_t at, std::uint32_t v, std::int32_t need, std::uint32_t body) {
    SharePlan& of = p.shares[v];
    const std::int32_t steps = static_cast<std::int32_t>(of.steps());
    const std::int32_t publish = need > 0 ? need : need + steps;
    if (publish < steps) of.stops.push_back({static_cast<std::uint32_t>(publish), ShareStop::kPublish, 0});
    p.shares[u].stops.push_back({at, v, need});
    p.shares[u].fetch.emplace_back(at, body);
  };
  for (const OwnLine<LanePlan::Scratch>& x : p.scratch)
    for (const LanePlan::Wait& w : x.v.waits)
      wait(w.share, step_at(p.shares[w.share], w.at), w.of, static_cast<std::int32_t>(step_at(p.shares[w.of], w.need)),
           w.body);
  for (std::uint32_t i = 0; i < p.ready.size(); ++i) {
    const std::uint32_t u = p.first_share[i], v = p.last[i];
    if (u == kNone || u == v) continue;
    const SharePlan& of = p.shares[v];
    wait(u, step_at(p.shares[u], p.first_time[i]), v,
         static_cast<std::int32_t>(step_at(of, p.ready[i])) - static_cast<std::int32_t>(of.steps()), i);
  }
  for (std::size_t u = 0; u < in.shares; ++u) {
    std::vector<ShareStop>& v = p.shares[u].stops;
    std::sort(v.begin(), v.end(), [](const ShareStop& x, const ShareStop& y) {
      if (x.at != y.at) return x.at < y.at;
      const bool px = x.share == ShareStop::kPublish, py = y.share == ShareStop::kPublish;
      return px != py ? px : x.share != y.share ? x.share < y.share : x.need > y.need;
    });
    v.erase(std::unique(v.begin(), v.end(),
                        [](const ShareStop& x, const ShareStop& y) { return x.at == y.at && x.share == y.share; }),
            v.end());
    std::vector<std::pair<std::uint32_t, std::uint32_t>>& f = p.shares[u].fetch;
    std::sort(f.begin(), f.end());
    f.erase(std::unique(f.begin(), f.end()), f.end());
  }
}

}  // namespace

void plan_start(const PlanInput& in, LanePlan& p) {
  p.shares.resize(in.shares);
  p.scratch.resize(in.shares);
  for (std::size_t u = 0; u < in.shares; ++u) {
    SharePlan& s = p.shares[u];
    for (auto& r : s.runs) r.clear();
    s.stops.clear();
    s.fetch.clear();
    LanePlan::Scratch& x = p.scratch[u].v;
    x.waits.clear();
    std::fill(std::begin(x.free_at), std::end(x.free_at), 0u);
    std::fill(std::begin(x.load), std::end(x.load), 0u);
  }
  p.ready.assign(in.n_bodies, 0);
  if (in.shares > 1) {
    p.last.assign(in.n_bodies, kNone);
    p.first_share.assign(in.n_bodies, kNone);
    p.first_time.resize(in.n_bodies);
  }
}

void plan_end(const PlanInput& in, LanePlan& p) {
  if (in.shares == 1) return;
  place_tail(in, p);
  list_stops(in, p);
}

void plan_lanes(const PlanInput& in, LanePlan& p) {
  plan_start(in, p);
  for (unsigned k = 0; k < in.colours; ++k)
    for (std::size_t u = 0; u < in.shares; ++u) plan_colour(in, p, k, u);
  for (std::size_t u = 0; u < in.shares; ++u) plan_share(p, u);
  plan_end(in, p);
}

}  // namespace nscd
