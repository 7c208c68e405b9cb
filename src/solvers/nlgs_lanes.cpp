// nscd/solvers/nlgs_lanes.cpp — see nlgs_lanes.hpp.
//
// The lane arithmetic is written once (visit_lanes) with GCC's vector extensions, which the
// x86 intrinsic types are: element-wise + − × ÷, comparisons giving masks, and `mask ? a : b`
// selecting lane by lane. Only the gathers and scatters of the bodies use intrinsics.
#include "nscd/solvers/nlgs_lanes.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <fstream>
#include <numeric>
#include <type_traits>
#include <utility>

#include "nscd/core/math.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define NSCD_HAVE_LANES 1
#endif

namespace nscd {

bool lanes_available() {
#ifdef NSCD_HAVE_LANES
  return true;
#else
  return false;
#endif
}

int lane_width() {
#ifdef NSCD_HAVE_LANES
  static const int width = __builtin_cpu_supports("avx2") ? 4 : 2;
  return width;
#else
  return 0;
#endif
}

std::size_t stream_bytes() {
  // Linux's own account of the cache of the first CPU ("32768K"): glibc's sysconf reports
  // what the hypervisor's CPUID says, 320 MiB on the project's VM, whose L3 is 32 MiB.
  static const std::size_t bytes = [] {
    std::ifstream in("/sys/devices/system/cpu/cpu0/cache/index3/size");
    std::size_t size = 0;
    char unit = 0;
    if (in >> size) in >> unit;
    size *= unit == 'K' ? 1024 : unit == 'M' ? 1024 * 1024 : 1;
    return size >= (std::size_t{1} << 20) ? size / 2 : std::size_t{16} << 20;
  }();
  return bytes;
}

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
    B.cd[j] = c.cd;
    B.an[j] = c.an;
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
    B.nx[j] = c.nx, B.ny[j] = c.ny, B.cd_rn[j] = c.cd_rn, B.cd_rt[j] = c.cd_rt, B.an_rn[j] = c.an_rn, B.an_rt[j] = c.an_rt;
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

template <class Bundle>
void append_bundles(const std::vector<SolverContact>& contacts, const SolverBody* bodies,
                    const std::uint32_t* block_start, std::uint32_t b0, std::uint32_t b1, std::vector<Bundle>& out,
                    std::vector<std::uint32_t>& order) {
  constexpr int K = ContactBundle::kLanes;
  // the non-empty blocks dealt to the lanes so that the lanes end together (the blocks are
  // independent: any deal gives the same numbers). a. Longest first (ties: in order), each to
  // the lane with the least so far (LPT).
  order.clear();
  for (std::uint32_t b = b0; b < b1; ++b)
    if (block_start[b + 1] > block_start[b]) order.push_back(b);
  auto length = [&](std::uint32_t b) { return block_start[b + 1] - block_start[b]; };
  std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
    return length(x) != length(y) ? length(x) > length(y) : x < y;
  });
  constexpr int kLaneShift = 29;  // a block's lane in the top bits of its entry of `order`
  constexpr std::uint32_t kBlockMask = (std::uint32_t{1} << kLaneShift) - 1;
  std::uint32_t load[K] = {};
  for (std::uint32_t& e : order) {
    const int j = static_cast<int>(std::min_element(load, load + K) - load);
    load[j] += length(e);
    e |= static_cast<std::uint32_t>(j) << kLaneShift;
  }
  //    b. Then, while it shortens the longest lane, one of its blocks moved to another lane or
  //    swapped with a shorter block there (each change lowers the sum of the squared loads: it
  //    ends), since longest-first alone leaves the lanes unevenly loaded (docs/benchmarks.md §8).
  auto lane = [](std::uint32_t e) { return static_cast<int>(e >> kLaneShift); };
  std::uint32_t total = 0;
  for (const std::uint32_t l : load) total += l;
  // no deal ends before the longest block, nor before the contacts spread evenly
  const std::uint32_t bound = order.empty() ? 0 : std::max(length(order.front() & kBlockMask), (total + K - 1) / K);
  for (int round = 0; round < 4 * K; ++round) {
    const int a = static_cast<int>(std::max_element(load, load + K) - load);
    if (load[a] <= bound) break;
    std::uint32_t best = load[a];
    std::size_t from = order.size(), to = order.size();
    int target = -1;
    for (std::size_t p = 0; p < order.size(); ++p) {
      if (lane(order[p]) != a) continue;
      const std::uint32_t x = length(order[p] & kBlockMask);
      for (int b = 0; b < K; ++b)  // moved to lane b
        if (b != a && load[b] + x < best && load[a] - x < best) {
          best = std::max(load[b] + x, load[a] - x);
          from = p, to = order.size(), target = b;
        }
      for (std::size_t q = 0; q < order.size(); ++q) {  // swapped with a shorter block y of lane b
        const int b = lane(order[q]);
        const std::uint32_t y = length(order[q] & kBlockMask);
        if (b == a || y >= x) continue;
        const std::uint32_t grown = load[b] + (x - y), shrunk = load[a] - (x - y);
        if (grown < best && shrunk < best) {
          best = std::max(grown, shrunk);
          from = p, to = q, target = b;
        }
      }
    }
    if (target < 0) break;
    const std::uint32_t x = length(order[from] & kBlockMask);
    order[from] = (order[from] & kBlockMask) | static_cast<std::uint32_t>(target) << kLaneShift;
    load[a] -= x, load[target] += x;
    if (to < order.size()) {
      const std::uint32_t y = length(order[to] & kBlockMask);
      order[to] = (order[to] & kBlockMask) | static_cast<std::uint32_t>(a) << kLaneShift;
      load[target] -= y, load[a] += y;
    }
  }
  //    c. The lanes renumbered longest first, so that the lanes left idle at the colour's end
  //    are the last ones: where lanes 4 … 7 are all idle, the AVX2 sweep skips them.
  int rank[K];
  for (int j = 0; j < K; ++j) {
    rank[j] = 0;
    for (int i = 0; i < K; ++i) rank[j] += load[i] > load[j] || (load[i] == load[j] && i < j);
  }
  for (std::uint32_t& e : order) e = (e & kBlockMask) | static_cast<std::uint32_t>(rank[lane(e)]) << kLaneShift;
  //    d. Each lane's blocks, one range of `order` each, in block order.
  std::sort(order.begin(), order.end());
  std::size_t qnext[K] = {}, qend[K] = {};
  for (std::size_t p = 0; p < order.size(); ++p) ++qend[lane(order[p])];
  for (int j = 1; j < K; ++j) qend[j] += qend[j - 1];
  for (int j = 0; j < K; ++j) qnext[j] = j == 0 ? 0 : qend[j - 1];
  std::uint32_t cur[K] = {}, end[K] = {}, blk[K] = {};
  bool on[K] = {};
  int live = 0;
  auto refill = [&](int j) {  // lane j takes its next block, if any
    on[j] = qnext[j] < qend[j];
    if (on[j]) {
      blk[j] = order[qnext[j]++] & kBlockMask;
      cur[j] = block_start[blk[j]];
      end[j] = block_start[blk[j] + 1];
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

template <class Bundle>
void append_bundles_scheduled(const std::vector<SolverContact>& contacts, const SolverBody* bodies, std::size_t n_bodies,
                              const std::uint32_t* block_start, const std::uint32_t* colour_start, unsigned colours,
                              std::vector<Bundle>& out, LaneSchedule& x) {
  constexpr int K = ContactBundle::kLanes;
  // 1. Colour after colour, its blocks longest first (ties: in order; a colour's blocks share no
  //    dynamic body, so their order is free), each to a lane: it starts once every earlier
  //    block sharing a dynamic body with it has ended (`ready`), as early as a lane lets it. Of
  //    the lanes free by then, the one free the latest (the shortest gap); else the one free the
  //    soonest.
  x.ready.assign(n_bodies, 0);
  std::uint32_t free_at[K] = {}, load[K] = {};
  for (auto& r : x.runs) r.clear();
  auto length = [&](std::uint32_t b) { return block_start[b + 1] - block_start[b]; };
  for (unsigned k = 0; k < colours; ++k) {
    x.order.clear();
    for (std::uint32_t b = colour_start[k]; b < colour_start[k + 1]; ++b)
      if (length(b) > 0) x.order.push_back(b);
    std::stable_sort(x.order.begin(), x.order.end(), [&](std::uint32_t p, std::uint32_t q) { return length(p) > length(q); });
    for (const std::uint32_t b : x.order) {
      const std::uint32_t c0 = block_start[b], c1 = block_start[b + 1];
      std::uint32_t ready = 0;
      for (std::uint32_t a = c0; a < c1; ++a) {
        const SolverContact& c = contacts[a];
        if (c.cd_dynamic) ready = std::max(ready, x.ready[c.cd]);
        if (c.an_dynamic) ready = std::max(ready, x.ready[c.an]);
      }
      int lane = -1;
      for (int j = 0; j < K; ++j)
        if (free_at[j] <= ready && (lane < 0 || free_at[j] > free_at[lane])) lane = j;
      if (lane < 0) lane = static_cast<int>(std::min_element(free_at, free_at + K) - free_at);
      const std::uint32_t start = std::max(ready, free_at[lane]), end = start + (c1 - c0);
      free_at[lane] = end;
      load[lane] += c1 - c0;
      x.runs[lane].push_back({b, start, end});
      for (std::uint32_t a = c0; a < c1; ++a) {
        const SolverContact& c = contacts[a];
        if (c.cd_dynamic) x.ready[c.cd] = end;
        if (c.an_dynamic) x.ready[c.an] = end;
      }
    }
  }
  //    The lanes renumbered busiest first (ties: in order), so that the idle ones are the last:
  //    where lanes 4 … 7 are all idle, the AVX2 sweep skips them.
  int by_load[K];
  std::iota(by_load, by_load + K, 0);
  std::stable_sort(by_load, by_load + K, [&](int p, int q) { return load[p] > load[q]; });
  for (int j = 0; j < K; ++j) x.renumbered[j].swap(x.runs[by_load[j]]);  // lane j takes lane by_load[j]'s runs
  std::swap(x.runs, x.renumbered);
  // 2. Bundle t: each lane's contact at time t, idle in its gaps (no time has every lane idle:
  //    a block starts at 0 or where another ends).
  const std::uint32_t span = *std::max_element(free_at, free_at + K);  // (the lanes' order does not matter here)
  std::size_t next[K] = {};
  for (std::uint32_t t = 0; t < span; ++t) {
    bool on[K], last[K];
    std::uint32_t cur[K] = {}, blk[K] = {};
    bool any = false;
    for (int j = 0; j < K; ++j) {
      const std::vector<LaneSchedule::Run>& r = x.runs[j];
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
template void append_bundles_scheduled(const std::vector<SolverContact>&, const SolverBody*, std::size_t,
                                       const std::uint32_t*, const std::uint32_t*, unsigned,
                                       std::vector<ContactBundle>&, LaneSchedule&);
template void append_bundles_scheduled(const std::vector<SolverContact>&, const SolverBody*, std::size_t,
                                       const std::uint32_t*, const std::uint32_t*, unsigned, std::vector<MassBundle>&,
                                       LaneSchedule&);

template <class Bundle>
void bundle_results_to_contacts(const Bundle* first, const Bundle* last, SolverContact* contacts, ContactStatus* status) {
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

template <class Bundle>
void bundle_impulses_to(const Bundle* first, const Bundle* last, double* x) {
  double sink[2];
  for (const Bundle* b = first; b != last; ++b)
    for (int j = 0; j < ContactBundle::kLanes; j += 2) {
      ImpulsePair pn, pt;
      std::memcpy(&pn, b->pn + j, sizeof pn);
      std::memcpy(&pt, b->pt + j, sizeof pt);
      const ImpulsePair p0 = __builtin_shufflevector(pn, pt, 0, 2), p1 = __builtin_shufflevector(pn, pt, 1, 3);
      const std::uint32_t i0 = b->id[j], i1 = b->id[j + 1];
      std::memcpy(i0 != ContactBundle::kIdleLane ? x + 2 * std::size_t{i0} : sink, &p0, sizeof p0);
      std::memcpy(i1 != ContactBundle::kIdleLane ? x + 2 * std::size_t{i1} : sink, &p1, sizeof p1);
    }
}
template void bundle_impulses_to(const ContactBundle*, const ContactBundle*, double*);
template void bundle_impulses_to(const MassBundle*, const MassBundle*, double*);

template <class Bundle>
void bundle_impulses_from(Bundle* first, Bundle* last, const double* x) {
  const double zero[2] = {0.0, 0.0};
  for (Bundle* b = first; b != last; ++b)
    for (int j = 0; j < ContactBundle::kLanes; j += 2) {
      const std::uint32_t i0 = b->id[j], i1 = b->id[j + 1];
      ImpulsePair p0, p1;
      std::memcpy(&p0, i0 != ContactBundle::kIdleLane ? x + 2 * std::size_t{i0} : zero, sizeof p0);
      std::memcpy(&p1, i1 != ContactBundle::kIdleLane ? x + 2 * std::size_t{i1} : zero, sizeof p1);
      const ImpulsePair pn = __builtin_shufflevector(p0, p1, 0, 2), pt = __builtin_shufflevector(p0, p1, 1, 3);
      std::memcpy(b->pn + j, &pn, sizeof pn);
      std::memcpy(b->pt + j, &pt, sizeof pt);
    }
}
template void bundle_impulses_from(ContactBundle*, ContactBundle*, const double*);
template void bundle_impulses_from(MassBundle*, MassBundle*, const double*);

#ifdef NSCD_HAVE_LANES
// The 4-lane helpers below take and return 32-byte vectors; they are always inlined into the
// AVX2 kernel, so GCC's note that such values change the ABI without AVX does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"
namespace {

typedef double V2 __attribute__((vector_size(16)));
typedef double V4 __attribute__((vector_size(32)));

template <class V>
NSCD_HOT_INLINE inline V load(const double* p) {
  V v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// CriteriaAccumulator, one per lane: lane j adds up the contacts of its block in order.
template <class V>
struct LaneSums {
  V wrwr{}, dv2{}, max_dv2{}, dv2r2{}, max_dv2r2{}, wrr{}, rdv{}, n_active{};
};

/// nlgs_visit (steps 1–4) for the lanes h … h+|V|−1 of a bundle: the scalar visit's operations
/// in its order, lane by lane. Updates the bodies' velocities (c*, a*) and the bundle's
/// impulses; a checked sweep (Check) adds to the lanes' sums and returns the statuses' codes.
template <bool Check, class V>
NSCD_HOT_INLINE inline void visit_lanes(ContactBundle& b, int h, V& cvx, V& cvy, V& cw, const V (&cinv)[3], V& avx,
                                        V& avy, V& aw, const V (&ainv)[3], double omega, double keep,
                                        LaneSums<V>& sums, V& status) {
  const V nx = load<V>(b.nx + h), ny = load<V>(b.ny + h);
  const V crn = load<V>(b.cd_rn + h), crt = load<V>(b.cd_rt + h), arn = load<V>(b.an_rn + h), art = load<V>(b.an_rt + h);
  const V wnn = load<V>(b.wnn + h), wnt = load<V>(b.wnt + h), wtt = load<V>(b.wtt + h), mu = load<V>(b.mu + h);
  const V pn = load<V>(b.pn + h), pt = load<V>(b.pt + h);
  const V zero = V{} * 0.0, one = zero + 1.0, lowest = zero - HUGE_VAL;
  // 1. The contact's velocity without its own impulse: b = U + s − W P (contact_velocity).
  const V dvx = cvx - avx, dvy = cvy - avy;
  V un = nx * dvx + ny * dvy + cw * crn - aw * arn;
  V ut = -ny * dvx + nx * dvy + cw * crt - aw * art;
  un += load<V>(b.sn + h);
  ut += load<V>(b.st + h);
  const V bn = un - (wnn * pn + wnt * pt);
  const V bt = ut - (wnt * pn + wtt * pt);
  // 2. solve_coulomb_2d: every case evaluated, then the first consistent one in its order.
  //    Stick (U = 0), valid inside the cone:
  const V inv_det = load<V>(b.inv_det + h);
  const V spn = (-wtt * bn + wnt * bt) * inv_det;
  const V spt = (wnt * bn - wnn * bt) * inv_det;
  const V abs_spt = spt < zero ? -spt : spt;
  const auto stick = (inv_det > zero) & (spn >= zero) & (abs_spt <= mu * spn);
  //    Slide with sense s (P_T = −s μ P_N, U_N = 0): first the sense of b_T, then the other.
  const V inv_fwd = load<V>(b.inv_fwd + h), inv_bwd = load<V>(b.inv_bwd + h);
  const V s1 = bt >= zero ? one : -one, s2 = -s1;
  const V id1 = s1 > zero ? inv_fwd : inv_bwd, id2 = s2 > zero ? inv_fwd : inv_bwd;
  const V pn1 = -bn * id1, pn2 = -bn * id2;
  const V m1 = s1 * (bt + (wnt - s1 * mu * wtt) * pn1);  // s U_T of each slide
  const V m2 = s2 * (bt + (wnt - s2 * mu * wtt) * pn2);
  const V pt1 = -s1 * mu * pn1, pt2 = -s2 * mu * pn2;
  const auto ok1 = (id1 > zero) & (pn1 >= zero), ok2 = (id2 > zero) & (pn2 >= zero);
  //    On the cone's edge, the slide with the least negative s U_T; else frictionless closure.
  const auto near1 = ok1 & (m1 > lowest);
  V margin = near1 ? m1 : lowest;
  V lpn = near1 ? pn1 : zero, lpt = near1 ? pt1 : zero;
  const auto near2 = ok2 & (m2 > margin);
  lpn = near2 ? pn2 : lpn;
  lpt = near2 ? pt2 : lpt;
  margin = near2 ? m2 : margin;
  const auto has_near = margin > lowest;
  lpn = has_near ? lpn : (wnn > zero ? -bn / wnn : zero);
  lpt = has_near ? lpt : zero;
  //    The order of precedence: open, stick, slide s1, slide s2, nearest slide, closure.
  const auto slide2 = ok2 & (m2 >= zero), slide1 = ok1 & (m1 >= zero), open = bn >= zero;
  lpn = slide2 ? pn2 : lpn;
  lpt = slide2 ? pt2 : lpt;
  lpn = slide1 ? pn1 : lpn;
  lpt = slide1 ? pt1 : lpt;
  lpn = stick ? spn : lpn;
  lpt = stick ? spt : lpt;
  lpn = open ? zero : lpn;
  lpt = open ? zero : lpt;
  // 3. Relaxed impulse (w = ω between checks, 1 on a checked sweep).
  const V npn = omega * lpn + keep * pn, npt = omega * lpt + keep * pt;
  if constexpr (Check) {
    //  CriteriaAccumulator::add(W, P before the visit, local P), for the lanes with an impulse
    const V rbn = 0.5 * (pn + lpn), rbt = 0.5 * (pt + lpt);
    const auto active = (rbn != zero) | (rbt != zero);
    const V wk_n = wnn * pn + wnt * pt, wk_t = wnt * pn + wtt * pt;
    const V wi_n = wnn * lpn + wnt * lpt, wi_t = wnt * lpn + wtt * lpt;
    const V dvn = wk_n - wi_n, dvt = wk_t - wi_t;
    const V dv2 = dvn * dvn + dvt * dvt, r2 = rbn * rbn + rbt * rbt;
    sums.n_active = active ? sums.n_active + 1.0 : sums.n_active;
    sums.wrwr = active ? sums.wrwr + 0.5 * (wk_n * wk_n + wk_t * wk_t + wi_n * wi_n + wi_t * wi_t) : sums.wrwr;
    sums.wrr = active ? sums.wrr + 0.5 * (pn * wk_n + pt * wk_t + lpn * wi_n + lpt * wi_t) : sums.wrr;
    sums.dv2 = active ? sums.dv2 + dv2 : sums.dv2;
    sums.max_dv2 = active & (sums.max_dv2 < dv2) ? dv2 : sums.max_dv2;
    const V dv2r2 = dv2 * r2;
    sums.dv2r2 = active ? sums.dv2r2 + dv2r2 : sums.dv2r2;
    sums.max_dv2r2 = active & (sums.max_dv2r2 < dv2r2) ? dv2r2 : sums.max_dv2r2;
    sums.rdv = active ? sums.rdv + (rbn * dvn + rbt * dvt) : sums.rdv;
    //  the status of the case taken (ContactStatus codes)
    const V fwd = zero + double(ContactStatus::SlipForward), bwd = zero + double(ContactStatus::SlipBackward);
    const V sense1 = s1 > zero ? fwd : bwd, sense2 = s2 > zero ? fwd : bwd;
    status = has_near ? (near2 ? sense2 : sense1) : fwd;
    status = slide2 ? sense2 : status;
    status = slide1 ? sense1 : status;
    status = stick ? zero + double(ContactStatus::Stick) : status;
    status = open ? zero + double(ContactStatus::Open) : status;
  }
  // 4. Its change applied to the two bodies (apply_impulse); kinematic bodies are not stored.
  const V dpn = npn - pn, dpt = npt - pt;
  const V fx = dpn * nx - dpt * ny, fy = dpn * ny + dpt * nx;
  cvx += cinv[0] * fx;
  cvy += cinv[1] * fy;
  cw += cinv[2] * (dpn * crn + dpt * crt);
  avx -= ainv[0] * fx;
  avy -= ainv[1] * fy;
  aw -= ainv[2] * (dpn * arn + dpt * art);
  std::memcpy(b.pn + h, &npn, sizeof npn);
  std::memcpy(b.pt + h, &npt, sizeof npt);
}

/// After a checked visit of lanes h …: statuses recorded, and each lane whose block ends hands
/// its sums to the block and starts again from zero.
template <class V>
NSCD_HOT_INLINE inline void close_lanes(ContactBundle& b, int h, LaneSums<V>& sums, const V& status,
                                        CriteriaAccumulator* block_sums) {
  constexpr int n = sizeof(V) / sizeof(double);
  for (int i = 0; i < n; ++i) b.status[h + i] = static_cast<std::uint8_t>(status[i]);
  for (unsigned ends = (b.ends >> h) & ((1u << n) - 1); ends != 0; ends &= ends - 1) {  // lanes whose block ends
    const int i = std::countr_zero(ends), j = h + i;
    CriteriaAccumulator& a = block_sums[b.block[j]];
    a.sum_wrwr = sums.wrwr[i], a.sum_dv2 = sums.dv2[i], a.max_dv2 = sums.max_dv2[i];
    a.sum_dv2r2 = sums.dv2r2[i], a.max_dv2r2 = sums.max_dv2r2[i], a.sum_wrr = sums.wrr[i], a.sum_rdv = sums.rdv[i];
    a.n_active = static_cast<std::size_t>(sums.n_active[i]);
    sums.wrwr[i] = sums.dv2[i] = sums.max_dv2[i] = sums.dv2r2[i] = sums.max_dv2r2[i] = 0.0;
    sums.wrr[i] = sums.rdv[i] = sums.n_active[i] = 0.0;
  }
}

/// Rows (vx, vy, ω, 1/m_x) of four bodies ⇄ four vectors of a field each (its own inverse).
__attribute__((target("avx2"))) NSCD_HOT_INLINE inline void transpose4(V4& r0, V4& r1, V4& r2, V4& r3) {
  const __m256d t0 = _mm256_unpacklo_pd(__m256d(r0), __m256d(r1)), t1 = _mm256_unpackhi_pd(__m256d(r0), __m256d(r1));
  const __m256d t2 = _mm256_unpacklo_pd(__m256d(r2), __m256d(r3)), t3 = _mm256_unpackhi_pd(__m256d(r2), __m256d(r3));
  r0 = V4(_mm256_permute2f128_pd(t0, t2, 0x20));
  r1 = V4(_mm256_permute2f128_pd(t1, t3, 0x20));
  r2 = V4(_mm256_permute2f128_pd(t0, t2, 0x31));
  r3 = V4(_mm256_permute2f128_pd(t1, t3, 0x31));
}

__attribute__((target("avx2"))) NSCD_HOT_INLINE inline V4 row(const SolverBody& b) { return V4(_mm256_load_pd(&b.vx)); }
__attribute__((target("avx2"))) NSCD_HOT_INLINE inline void store_row(SolverBody& b, const V4& r) {
  _mm256_store_pd(&b.vx, __m256d(r));
}

/// Four lanes j0 … j0+3 of a bundle: fields (vx, vy, ω) of the candidates and the antagonists,
/// and their inverse masses (1/m_x, 1/m_y, 1/I): 1/m_x with the velocities, the others from the
/// bundle (MassBundle), or for streamed bundles from the bodies' cache lines, already loaded.
struct Gathered4 {
  V4 c[4], a[4];
  V4 cinv[3], ainv[3];
};
/// (1/m_y, 1/I) of four bodies, as two vectors of a field each.
__attribute__((target("avx2"))) NSCD_HOT_INLINE inline void inverse_masses(const SolverBody& p0, const SolverBody& p1,
                                                                          const SolverBody& p2, const SolverBody& p3,
                                                                          V4& imy, V4& ii) {
  const __m256d r0 = _mm256_loadu2_m128d(&p2.inv_my, &p0.inv_my), r1 = _mm256_loadu2_m128d(&p3.inv_my, &p1.inv_my);
  imy = V4(_mm256_unpacklo_pd(r0, r1));
  ii = V4(_mm256_unpackhi_pd(r0, r1));
}
template <class Bundle>
__attribute__((target("avx2"))) NSCD_HOT_INLINE inline Gathered4 gather4(const Bundle& b, int j0,
                                                                        const SolverBody* B) {
  Gathered4 g;
  const std::uint32_t* cd = b.cd + j0;
  const std::uint32_t* an = b.an + j0;
  for (int i = 0; i < 4; ++i) {
    g.c[i] = row(B[cd[i]]);
    g.a[i] = row(B[an[i]]);
  }
  transpose4(g.c[0], g.c[1], g.c[2], g.c[3]);
  transpose4(g.a[0], g.a[1], g.a[2], g.a[3]);
  g.cinv[0] = g.c[3];
  g.ainv[0] = g.a[3];
  if constexpr (!std::is_same_v<Bundle, MassBundle>) {
    inverse_masses(B[cd[0]], B[cd[1]], B[cd[2]], B[cd[3]], g.cinv[1], g.cinv[2]);
    inverse_masses(B[an[0]], B[an[1]], B[an[2]], B[an[3]], g.ainv[1], g.ainv[2]);
  } else {
    g.cinv[1] = load<V4>(b.cd_imy + j0), g.cinv[2] = load<V4>(b.cd_ii + j0);
    g.ainv[1] = load<V4>(b.an_imy + j0), g.ainv[2] = load<V4>(b.an_ii + j0);
  }
  return g;
}
/// …and back: the dynamic bodies of the live lanes get their rows (1/m_x unchanged).
__attribute__((target("avx2"))) NSCD_HOT_INLINE inline void scatter4(const ContactBundle& b, int j0, Gathered4& g,
                                                                    SolverBody* B) {
  transpose4(g.c[0], g.c[1], g.c[2], g.c[3]);
  transpose4(g.a[0], g.a[1], g.a[2], g.a[3]);
  for (int i = 0; i < 4; ++i) {
    if (b.write_cd[j0 + i]) store_row(B[b.cd[j0 + i]], g.c[i]);
    if (b.write_an[j0 + i]) store_row(B[b.an[j0 + i]], g.a[i]);
  }
}

/// Streamed bundles (larger than the cache): the bundle kAhead places on is asked for, every
/// cache line of it, while this one is visited.
constexpr std::ptrdiff_t kAhead = 2;
template <class Bundle>
NSCD_HOT_INLINE inline void fetch_ahead(const Bundle* b, const Bundle* last) {
  if constexpr (!std::is_same_v<Bundle, MassBundle>)
    if (last - b > kAhead)
      for (std::size_t off = 0; off < sizeof(Bundle); off += 64)
        _mm_prefetch(reinterpret_cast<const char*>(b + kAhead) + off, _MM_HINT_T0);
}

template <bool Check, class Bundle>
__attribute__((target("avx2"))) void sweep_avx2(Bundle* first, Bundle* last, SolverBody* B,
                                                double omega, CriteriaAccumulator* block_sums) {
  const double keep = 1.0 - omega;
  constexpr int K = ContactBundle::kLanes;
  LaneSums<V4> sums[K / 4];
  V4 status{};
  for (Bundle* b = first; b != last; ++b) {
    fetch_ahead(b, last);
    const int halves_end = b->idle_high ? K / 2 : K;
    for (int h = 0; h < halves_end; h += 4) {  // the bundle's two halves, independent (the second skipped if idle)
      Gathered4 g = gather4(*b, h, B);
      visit_lanes<Check>(*b, h, g.c[0], g.c[1], g.c[2], g.cinv, g.a[0], g.a[1], g.a[2], g.ainv, omega, keep, sums[h / 4],
                         status);
      scatter4(*b, h, g, B);
      if constexpr (Check) close_lanes(*b, h, sums[h / 4], status, block_sums);
    }
  }
}

/// Two bodies' fields (vx, vy, ω) and inverse masses (1/m_x, 1/m_y, 1/I) of lanes j, j+1: from
/// their pairs (vx, vy), (ω, 1/m_x), and (1/m_y, 1/I) for streamed bundles, else from the
/// MassBundle's fields …
struct Pair {
  V2 vx, vy, w, inv[3];
};
template <class Bundle>
NSCD_HOT_INLINE inline Pair gather2(const SolverBody& p, const SolverBody& q, const Bundle& b, int j, bool cd) {
  const __m128d x0 = _mm_load_pd(&p.vx), x1 = _mm_load_pd(&q.vx), y0 = _mm_load_pd(&p.w), y1 = _mm_load_pd(&q.w);
  Pair f{V2(_mm_unpacklo_pd(x0, x1)), V2(_mm_unpackhi_pd(x0, x1)), V2(_mm_unpacklo_pd(y0, y1)), {}};
  f.inv[0] = V2(_mm_unpackhi_pd(y0, y1));
  if constexpr (!std::is_same_v<Bundle, MassBundle>) {
    (void)b, (void)j, (void)cd;
    const __m128d z0 = _mm_load_pd(&p.inv_my), z1 = _mm_load_pd(&q.inv_my);
    f.inv[1] = V2(_mm_unpacklo_pd(z0, z1));
    f.inv[2] = V2(_mm_unpackhi_pd(z0, z1));
  } else {
    f.inv[1] = load<V2>((cd ? b.cd_imy : b.an_imy) + j);
    f.inv[2] = load<V2>((cd ? b.cd_ii : b.an_ii) + j);
  }
  return f;
}
/// … and the velocities scattered back to those that are written (1/m_x untouched).
NSCD_HOT_INLINE inline void scatter2(const Pair& f, SolverBody& p, bool write_p, SolverBody& q, bool write_q) {
  if (write_p) {
    _mm_store_pd(&p.vx, _mm_unpacklo_pd(__m128d(f.vx), __m128d(f.vy)));
    _mm_store_sd(&p.w, __m128d(f.w));
  }
  if (write_q) {
    _mm_store_pd(&q.vx, _mm_unpackhi_pd(__m128d(f.vx), __m128d(f.vy)));
    _mm_storeh_pd(&q.w, __m128d(f.w));
  }
}

template <bool Check, class Bundle>
void sweep_sse2(Bundle* first, Bundle* last, SolverBody* B, double omega,
                CriteriaAccumulator* block_sums) {
  const double keep = 1.0 - omega;
  constexpr int K = ContactBundle::kLanes;
  LaneSums<V2> sums[K / 2];
  V2 status{};
  for (Bundle* b = first; b != last; ++b) {
    fetch_ahead(b, last);
    for (int h = 0; h < K; h += 2) {  // pairs of lanes, independent
      SolverBody& c0 = B[b->cd[h]];
      SolverBody& c1 = B[b->cd[h + 1]];
      SolverBody& a0 = B[b->an[h]];
      SolverBody& a1 = B[b->an[h + 1]];
      Pair c = gather2(c0, c1, *b, h, true), a = gather2(a0, a1, *b, h, false);
      visit_lanes<Check>(*b, h, c.vx, c.vy, c.w, c.inv, a.vx, a.vy, a.w, a.inv, omega, keep, sums[h / 2], status);
      // the dynamic bodies of the live lanes: the candidates' rows, then the antagonists'
      scatter2(c, c0, b->write_cd[h], c1, b->write_cd[h + 1]);
      scatter2(a, a0, b->write_an[h], a1, b->write_an[h + 1]);
      if constexpr (Check) close_lanes(*b, h, sums[h / 2], status, block_sums);
    }
  }
}

}  // namespace
#endif

namespace {
template <class Bundle>
void sweep_any(Bundle* first, Bundle* last, SolverBody* bodies, double omega, bool check,
               CriteriaAccumulator* block_sums, int width) {
#ifdef NSCD_HAVE_LANES
  width = std::min(width, lane_width());
  const double w = check ? 1.0 : omega;
  if (width >= 4)
    check ? sweep_avx2<true>(first, last, bodies, w, block_sums)
          : sweep_avx2<false>(first, last, bodies, w, static_cast<CriteriaAccumulator*>(nullptr));
  else
    check ? sweep_sse2<true>(first, last, bodies, w, block_sums)
          : sweep_sse2<false>(first, last, bodies, w, static_cast<CriteriaAccumulator*>(nullptr));
#else
  (void)first, (void)last, (void)bodies, (void)omega, (void)check, (void)block_sums, (void)width;
#endif
}
}  // namespace

void sweep_bundles(MassBundle* first, MassBundle* last, SolverBody* bodies, double omega, bool check,
                   CriteriaAccumulator* block_sums, int width) {
  sweep_any(first, last, bodies, omega, check, block_sums, width);
}
void sweep_bundles(ContactBundle* first, ContactBundle* last, SolverBody* bodies, double omega, bool check,
                   CriteriaAccumulator* block_sums, int width) {
  sweep_any(first, last, bodies, omega, check, block_sums, width);
}

}  // namespace nscd
