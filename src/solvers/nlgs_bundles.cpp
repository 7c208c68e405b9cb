// nscd/solvers/nlgs_bundles.cpp — see nlgs_lanes.hpp: the contacts dealt to the lanes and copied
// into bundles, and the impulses and statuses read back (the sweeps are nlgs_lanes.cpp).
#include <algorithm>
#include <cstring>
#include <functional>
#include <numeric>
#include <type_traits>
#include <utility>

#include "nscd/solvers/nlgs_lanes.hpp"
#include "nscd/solvers/nlgs_plan.hpp"

namespace nscd {

namespace {
/// Bundle B from the lanes' contacts: lane j live (on[j]) with contact cur[j] of block blk[j],
/// its block's last if last[j]; an idle lane reads the first live lane's bodies.
template <class Bundle>
void fill_bundle(Bundle& B, const std::vector<SolverContact>& contacts, const SolverBody* bodies, const bool* on,
                 const std::uint32_t* cur, const std::uint32_t* blk, const bool* last) {
  constexpr bool kMasses = std::is_same_v<Bundle, MassBundle>;
  constexpr int K = ContactBundle::kLanes;
  int any = 0;
  while (!on[any]) ++any;
  for (int j = 0; j < K; ++j) {
    const SolverContact& c = contacts[on[j] ? cur[j] : cur[any]];
    B.cd_word[j] = c.cd * kBodyWords;
    B.an_word[j] = c.an * kBodyWords;
    B.block[j] = blk[any];
    B.block_ends[j] = 0;
    B.write_cd[j] = B.write_an[j] = 0;
    if (!on[j]) {
      B.id[j] = ContactBundle::kIdleLane;
      B.nx[j] = B.ny[j] = B.cd_rn[j] = B.cd_rt[j] = B.an_rn[j] = B.an_rt[j] = 0.0;
      B.wnn[j] = 1.0;
      B.wnt[j] = B.wtt[j] = B.inv_det[j] = B.inv_fwd[j] = B.inv_bwd[j] = 0.0;
      B.sn[j] = B.st[j] = B.mu[j] = B.pn[j] = B.pt[j] = 0.0;
      if constexpr (kMasses) B.cd_imy[j] = B.cd_ii[j] = B.an_imy[j] = B.an_ii[j] = 0.0;
      continue;
    }
    B.id[j] = cur[j];
    B.block[j] = blk[j];
    B.nx[j] = c.nx, B.ny[j] = c.ny, B.cd_rn[j] = c.cd_rn, B.cd_rt[j] = c.cd_rt, B.an_rn[j] = c.an_rn,
    B.an_rt[j] = c.an_rt;
    B.wnn[j] = c.W.nn, B.wnt[j] = c.W.nt, B.wtt[j] = c.W.tt;
    B.inv_det[j] = c.f.inv_det, B.inv_fwd[j] = c.f.inv_den_fwd, B.inv_bwd[j] = c.f.inv_den_bwd;
    B.sn[j] = c.sn, B.st[j] = c.st, B.mu[j] = c.mu, B.pn[j] = c.pn, B.pt[j] = c.pt;
    if constexpr (kMasses) {
      B.cd_imy[j] = bodies[c.cd].inv_my, B.cd_ii[j] = bodies[c.cd].inv_i;
      B.an_imy[j] = bodies[c.an].inv_my, B.an_ii[j] = bodies[c.an].inv_i;
    }
    B.write_cd[j] = c.cd_dynamic;
    B.write_an[j] = c.an_dynamic;
  }
  B.idle_high = 1;
  for (int j = K / 2; j < K; ++j) B.idle_high &= static_cast<std::uint8_t>(B.id[j] == ContactBundle::kIdleLane);
  for (int h = 0; h < K / 4; ++h) {
    B.writes_all[h] = 1;
    for (int j = 4 * h; j < 4 * h + 4; ++j)
      B.writes_all[h] &= static_cast<std::uint8_t>(B.write_cd[j] && B.write_an[j]);
  }
  B.ends = 0;
  for (int j = 0; j < K; ++j) {
    B.status[j] = static_cast<std::uint8_t>(ContactStatus::Open);
    if (last[j]) {
      B.block_ends[j] = 1;
      B.ends |= static_cast<std::uint8_t>(1u << j);
    }
  }
}
}  // namespace

namespace {
constexpr int kLaneShift = 29;  // a block's lane in the top bits of its entry of `order`
constexpr std::uint32_t kBlockMask = (std::uint32_t{1} << kLaneShift) - 1;
inline int lane_of(std::uint32_t e) { return static_cast<int>(e >> kLaneShift); }

/// The deal of append_bundles: `order` lists the non-empty blocks, each with its lane in the top
/// bits; load[j] is lane j's count of contacts.
struct Deal {
  const std::uint32_t* block_start;
  std::vector<std::uint32_t>& order;
  std::uint32_t load[ContactBundle::kLanes] = {};
  std::uint32_t length(std::uint32_t b) const { return block_start[b + 1] - block_start[b]; }
};

// a. Longest first (ties: in order), each block to the lane with the least so far (LPT).
void deal_longest_first(Deal& d, std::uint32_t b0, std::uint32_t b1) {
  constexpr int K = ContactBundle::kLanes;
  d.order.clear();
  for (std::uint32_t b = b0; b < b1; ++b)
    if (d.length(b) > 0) d.order.push_back(b);
  std::sort(d.order.begin(), d.order.end(), [&](std::uint32_t x, std::uint32_t y) {
    return d.length(x) != d.length(y) ? d.length(x) > d.length(y) : x < y;
  });
  for (std::uint32_t& e : d.order) {
    const int j = static_cast<int>(std::min_element(d.load, d.load + K) - d.load);
    d.load[j] += d.length(e);
    e |= static_cast<std::uint32_t>(j) << kLaneShift;
  }
}

// b. The change that shortens lane a the most (below best): one of its blocks moved to another
//    lane (to = order.size()) or swapped with a shorter block `to` there. Returns the target
//    lane, −1 when none shortens it.
int best_change(const Deal& d, int a, std::size_t& from, std::size_t& to) {
  constexpr int K = ContactBundle::kLanes;
  const std::vector<std::uint32_t>& order = d.order;
  std::uint32_t best = d.load[a];
  int target = -1;
  for (std::size_t p = 0; p < order.size(); ++p) {
    if (lane_of(order[p]) != a) continue;
    const std::uint32_t x = d.length(order[p] & kBlockMask);
    for (int b = 0; b < K; ++b)  // moved to lane b
      if (b != a && d.load[b] + x < best && d.load[a] - x < best) {
        best = std::max(d.load[b] + x, d.load[a] - x);
        from = p, to = order.size(), target = b;
      }
    for (std::size_t q = 0; q < order.size(); ++q) {  // swapped with a shorter block y of lane b
      const int b = lane_of(order[q]);
      const std::uint32_t y = d.length(order[q] & kBlockMask);
      if (b == a || y >= x) continue;
      const std::uint32_t grown = d.load[b] + (x - y), shrunk = d.load[a] - (x - y);
      if (grown < best && shrunk < best) {
        best = std::max(grown, shrunk);
        from = p, to = q, target = b;
      }
    }
  }
  return target;
}

// b. Then, while it shortens the longest lane, one of its blocks moved to another lane or
//    swapped with a shorter block there (each change lowers the sum of the squared loads: it
//    ends), since longest-first alone leaves the lanes unevenly loaded (docs/benchmarks.md §8).
void rebalance(Deal& d) {
  constexpr int K = ContactBundle::kLanes;
  std::vector<std::uint32_t>& order = d.order;
  std::uint32_t total = 0;
  for (const std::uint32_t l : d.load) total += l;
  // no deal ends before the longest block, nor before the contacts spread evenly
  const std::uint32_t bound = order.empty() ? 0 : std::max(d.length(order.front() & kBlockMask), (total + K - 1) / K);
  for (int round = 0; round < 4 * K; ++round) {
    const int a = static_cast<int>(std::max_element(d.load, d.load + K) - d.load);
    if (d.load[a] <= bound) break;
    std::size_t from = order.size(), to = order.size();
    const int target = best_change(d, a, from, to);
    if (target < 0) break;
    const std::uint32_t x = d.length(order[from] & kBlockMask);
    order[from] = (order[from] & kBlockMask) | static_cast<std::uint32_t>(target) << kLaneShift;
    d.load[a] -= x, d.load[target] += x;
    if (to < order.size()) {
      const std::uint32_t y = d.length(order[to] & kBlockMask);
      order[to] = (order[to] & kBlockMask) | static_cast<std::uint32_t>(a) << kLaneShift;
      d.load[target] -= y, d.load[a] += y;
    }
  }
}

// c. The lanes renumbered longest first, so that the lanes left idle at the colour's end are
//    the last ones: where lanes 4 … 7 are all idle, the AVX2 sweep skips them. Then each lane's
//    blocks are one range of `order`, in block order.
void renumber_lanes(Deal& d) {
  constexpr int K = ContactBundle::kLanes;
  int rank[K];
  for (int j = 0; j < K; ++j) {
    rank[j] = 0;
    for (int i = 0; i < K; ++i) rank[j] += d.load[i] > d.load[j] || (d.load[i] == d.load[j] && i < j);
  }
  for (std::uint32_t& e : d.order) e = (e & kBlockMask) | static_cast<std::uint32_t>(rank[lane_of(e)]) << kLaneShift;
  std::sort(d.order.begin(), d.order.end());
}

// d. The bundles: each lane visits its blocks' contacts in order, one a bundle.
template <class Bundle>
void emit_bundles(const Deal& d, const std::vector<SolverContact>& contacts, const SolverBody* bodies,
                  std::vector<Bundle>& out) {
  constexpr int K = ContactBundle::kLanes;
  const std::vector<std::uint32_t>& order = d.order;
  std::size_t qnext[K] = {}, qend[K] = {};
  for (std::size_t p = 0; p < order.size(); ++p) ++qend[lane_of(order[p])];
  for (int j = 1; j < K; ++j) qend[j] += qend[j - 1];
  for (int j = 0; j < K; ++j) qnext[j] = j == 0 ? 0 : qend[j - 1];
  std::uint32_t cur[K] = {}, end[K] = {}, blk[K] = {};
  bool on[K] = {};
  int live = 0;
  auto refill = [&](int j) {  // lane j takes its next block, if any
    on[j] = qnext[j] < qend[j];
    if (on[j]) {
      blk[j] = order[qnext[j]++] & kBlockMask;
      cur[j] = d.block_start[blk[j]];
      end[j] = d.block_start[blk[j] + 1];
    }
    return on[j];
  };
  for (int j = 0; j < K; ++j) live += refill(j);
  while (live > 0) {
    bool last[K];
    for (int j = 0; j < K; ++j) last[j] = on[j] && cur[j] + 1 == end[j];
    fill_bundle(out.emplace_back(), contacts, bodies, on, cur, blk, last);
    for (int j = 0; j < K; ++j)
      if (on[j] && ++cur[j] == end[j] && !refill(j)) --live;
  }
}
}  // namespace

// The non-empty blocks dealt to the lanes so that the lanes end together (the blocks are
// independent: any deal gives the same numbers), then their bundles.
template <class Bundle>
void append_bundles(const std::vector<SolverContact>& contacts, const SolverBody* bodies,
                    const std::uint32_t* block_start, std::uint32_t b0, std::uint32_t b1, std::vector<Bundle>& out,
                    std::vector<std::uint32_t>& order) {
  Deal d{block_start, order};
  deal_longest_first(d, b0, b1);
  rebalance(d);
  renumber_lanes(d);
  emit_bundles(d, contacts, bodies, out);
}

std::uint32_t dealt_passes(const std::uint32_t* block_start, std::uint32_t b0, std::uint32_t b1, bool halves,
                           std::vector<std::uint32_t>& order) {
  constexpr int K = ContactBundle::kLanes;
  Deal d{block_start, order};
  deal_longest_first(d, b0, b1);
  rebalance(d);
  std::uint32_t* load = d.load;  // busiest first, as renumber_lanes numbers them
  std::sort(load, load + K, std::greater<>());
  return load[0] + (halves ? load[K / 2] : 0);
}

std::uint32_t planned_passes(const SharePlan& plan, bool halves,
                             std::vector<std::pair<std::uint32_t, std::uint32_t>>& spans) {
  constexpr int K = ContactBundle::kLanes;
  if (!halves) return plan.bundles;
  spans.clear();  // the times one of lanes 4 … 7 is busy, merged
  for (int j = K / 2; j < K; ++j)
    for (const LaneRun& r : plan.runs[j]) spans.emplace_back(r.start, r.end);
  std::sort(spans.begin(), spans.end());
  std::uint32_t busy = 0, reached = 0;
  for (const auto& [from, to] : spans) {
    if (to > std::max(from, reached)) busy += to - std::max(from, reached);
    reached = std::max(reached, to);
  }
  return plan.bundles + busy;
}

// Bundle i: each lane's contact at the i-th time some lane is busy (nlgs_plan.hpp); a time with
// every lane idle (a share waiting for another's block) gives no bundle.
template <class Bundle>
void append_planned(const std::vector<SolverContact>& contacts, const SolverBody* bodies,
                    const std::uint32_t* block_start, const SharePlan& plan, std::vector<Bundle>& out) {
  constexpr int K = ContactBundle::kLanes;
  std::size_t next[K] = {};
  for (std::uint32_t t = 0; t < plan.span; ++t) {
    bool on[K], last[K];
    std::uint32_t cur[K] = {}, blk[K] = {};
    bool any = false;
    for (int j = 0; j < K; ++j) {
      const std::vector<LaneRun>& r = plan.runs[j];
      while (next[j] < r.size() && r[next[j]].end <= t) ++next[j];
      on[j] = next[j] < r.size() && r[next[j]].start <= t;
      if (on[j]) {
        blk[j] = r[next[j]].block;
        cur[j] = block_start[blk[j]] + (t - r[next[j]].start);
        any = true;
      }
      last[j] = on[j] && cur[j] + 1 == block_start[blk[j] + 1];
    }
    if (any) fill_bundle(out.emplace_back(), contacts, bodies, on, cur, blk, last);
  }
}

template void append_bundles(const std::vector<SolverContact>&, const SolverBody*, const std::uint32_t*, std::uint32_t,
                             std::uint32_t, std::vector<ContactBundle>&, std::vector<std::uint32_t>&);
template void append_bundles(const std::vector<SolverContact>&, const SolverBody*, const std::uint32_t*, std::uint32_t,
                             std::uint32_t, std::vector<MassBundle>&, std::vector<std::uint32_t>&);
template void append_planned(const std::vector<SolverContact>&, const SolverBody*, const std::uint32_t*,
                             const SharePlan&, std::vector<ContactBundle>&);
template void append_planned(const std::vector<SolverContact>&, const SolverBody*, const std::uint32_t*,
                             const SharePlan&, std::vector<MassBundle>&);

template <class Bundle>
void bundle_results_to_contacts(const Bundle* first, const Bundle* last, SolverContact* contacts,
                                ContactStatus* status) {
  for (const Bundle* b = first; b != last; ++b)
    for (int j = 0; j < ContactBundle::kLanes; ++j)
      if (b->id[j] != ContactBundle::kIdleLane) {
        contacts[b->id[j]].pn = b->pn[j];
        contacts[b->id[j]].pt = b->pt[j];
        status[b->id[j]] = static_cast<ContactStatus>(b->status[j]);
      }
}
template void bundle_results_to_contacts(const ContactBundle*, const ContactBundle*, SolverContact*, ContactStatus*);
template void bundle_results_to_contacts(const MassBundle*, const MassBundle*, SolverContact*, ContactStatus*);

// Two lanes at a time: their (pn, pt) pairs are two 16-byte records of x. An idle lane's pair
// goes to a sink, and comes back as zeros, without a branch (a branch per lane mispredicts:
// docs/benchmarks.md §8).
typedef double ImpulsePair __attribute__((vector_size(16)));

namespace {
// where lane j's impulses sit in x (bundle_impulses_to)
template <bool Shifted, class Bundle>
inline std::size_t impulse_at(const Bundle& b, int j, const std::int64_t* block_shift) {
  if constexpr (Shifted) return 2 * static_cast<std::size_t>(std::int64_t{b.id[j]} + block_shift[b.block[j]]);
  return 2 * std::size_t{b.id[j]};
}

// (Shifted: with block_shift; one thread's layout has none, and its copies skip the lookup)
template <bool Shifted, class Bundle>
void impulses_to(const Bundle* first, const Bundle* last, double* x, const std::int64_t* block_shift) {
  double sink[2];
  for (const Bundle* b = first; b != last; ++b)
    for (int j = 0; j < ContactBundle::kLanes; j += 2) {
      ImpulsePair pn, pt;
      std::memcpy(&pn, b->pn + j, sizeof pn);
      std::memcpy(&pt, b->pt + j, sizeof pt);
      const ImpulsePair p0 = __builtin_shufflevector(pn, pt, 0, 2), p1 = __builtin_shufflevector(pn, pt, 1, 3);
      const std::uint32_t i0 = b->id[j], i1 = b->id[j + 1];
      std::memcpy(i0 != ContactBundle::kIdleLane ? x + impulse_at<Shifted>(*b, j, block_shift) : sink, &p0, sizeof p0);
      std::memcpy(i1 != ContactBundle::kIdleLane ? x + impulse_at<Shifted>(*b, j + 1, block_shift) : sink, &p1,
                  sizeof p1);
    }
}

template <bool Shifted, class Bundle>
void impulses_from(Bundle* first, Bundle* last, const double* x, const std::int64_t* block_shift) {
  const double zero[2] = {0.0, 0.0};
  for (Bundle* b = first; b != last; ++b)
    for (int j = 0; j < ContactBundle::kLanes; j += 2) {
      const std::uint32_t i0 = b->id[j], i1 = b->id[j + 1];
      ImpulsePair p0, p1;
      std::memcpy(&p0, i0 != ContactBundle::kIdleLane ? x + impulse_at<Shifted>(*b, j, block_shift) : zero, sizeof p0);
      std::memcpy(&p1, i1 != ContactBundle::kIdleLane ? x + impulse_at<Shifted>(*b, j + 1, block_shift) : zero,
                  sizeof p1);
      const ImpulsePair pn = __builtin_shufflevector(p0, p1, 0, 2), pt = __builtin_shufflevector(p0, p1, 1, 3);
      std::memcpy(b->pn + j, &pn, sizeof pn);
      std::memcpy(b->pt + j, &pt, sizeof pt);
    }
}
}  // namespace

template <class Bundle>
void bundle_impulses_to(const Bundle* first, const Bundle* last, double* x, const std::int64_t* block_shift) {
  block_shift ? impulses_to<true>(first, last, x, block_shift) : impulses_to<false>(first, last, x, nullptr);
}
template void bundle_impulses_to(const ContactBundle*, const ContactBundle*, double*, const std::int64_t*);
template void bundle_impulses_to(const MassBundle*, const MassBundle*, double*, const std::int64_t*);

template <class Bundle>
void bundle_impulses_from(Bundle* first, Bundle* last, const double* x, const std::int64_t* block_shift) {
  block_shift ? impulses_from<true>(first, last, x, block_shift) : impulses_from<false>(first, last, x, nullptr);
}
template void bundle_impulses_from(ContactBundle*, ContactBundle*, const double*, const std::int64_t*);
template void bundle_impulses_from(MassBundle*, MassBundle*, const double*, const std::int64_t*);

}  // namespace nscd
