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
  const V crn = load<V>(b.cd_rn + h), crt = load<V>(b.cd_rt + h), arn = load<V>(b.an_rn + h),
          art = load<V>(b.an_rt + h);
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
  const std::uint32_t* cd = b.cd_word + j0;
  const std::uint32_t* an = b.an_word + j0;
  for (int i = 0; i < 4; ++i) {
    g.c[i] = row(body_at(B, cd[i]));
    g.a[i] = row(body_at(B, an[i]));
  }
  transpose4(g.c[0], g.c[1], g.c[2], g.c[3]);
  transpose4(g.a[0], g.a[1], g.a[2], g.a[3]);
  g.cinv[0] = g.c[3];
  g.ainv[0] = g.a[3];
  if constexpr (!std::is_same_v<Bundle, MassBundle>) {
    inverse_masses(body_at(B, cd[0]), body_at(B, cd[1]), body_at(B, cd[2]), body_at(B, cd[3]), g.cinv[1], g.cinv[2]);
    inverse_masses(body_at(B, an[0]), body_at(B, an[1]), body_at(B, an[2]), body_at(B, an[3]), g.ainv[1], g.ainv[2]);
  } else {
    // (the intrinsic, not load<V4>: Clang refuses a 32-byte vector returned by a function
    // compiled without AVX, even inlined here)
    g.cinv[1] = V4(_mm256_loadu_pd(b.cd_imy + j0)), g.cinv[2] = V4(_mm256_loadu_pd(b.cd_ii + j0));
    g.ainv[1] = V4(_mm256_loadu_pd(b.an_imy + j0)), g.ainv[2] = V4(_mm256_loadu_pd(b.an_ii + j0));
  }
  return g;
}
/// …and back: the dynamic bodies of the live lanes get their rows (1/m_x unchanged).
__attribute__((target("avx2"))) NSCD_HOT_INLINE inline void scatter4(const ContactBundle& b, int j0, Gathered4& g,
                                                                    SolverBody* B) {
  // Four live lanes between dynamic bodies, most halves of a pile: their eight rows stored
  // untested (one test for the half where each row took a test and a branch). Tested first, so
  // that elsewhere each row's half of the transpose is still made only where it is stored.
  if (b.writes_all[j0 / 4]) {
    transpose4(g.c[0], g.c[1], g.c[2], g.c[3]);
    transpose4(g.a[0], g.a[1], g.a[2], g.a[3]);
    for (int i = 0; i < 4; ++i) {
      store_row(body_at(B, b.cd_word[j0 + i]), g.c[i]);
      store_row(body_at(B, b.an_word[j0 + i]), g.a[i]);
    }
    return;
  }
  transpose4(g.c[0], g.c[1], g.c[2], g.c[3]);
  transpose4(g.a[0], g.a[1], g.a[2], g.a[3]);
  for (int i = 0; i < 4; ++i) {
    if (b.write_cd[j0 + i]) store_row(body_at(B, b.cd_word[j0 + i]), g.c[i]);
    if (b.write_an[j0 + i]) store_row(body_at(B, b.an_word[j0 + i]), g.a[i]);
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
__attribute__((target("avx2"))) void sweep_avx2(Bundle* first, Bundle* last, SolverBody* B, double omega,
                                                CriteriaAccumulator* block_sums, LaneCarry* carry) {
  const double keep = 1.0 - omega;
  constexpr int K = ContactBundle::kLanes;
  LaneSums<V4> sums[K / 4];
  static_assert(sizeof sums == sizeof carry->v);
  if (Check && carry) std::memcpy(sums, carry->v, sizeof sums);
  V4 status{};
  for (Bundle* b = first; b != last; ++b) {
    fetch_ahead(b, last);
    const int halves_end = b->idle_high ? K / 2 : K;
    for (int h = 0; h < halves_end; h += 4) {  // the bundle's two halves, independent (the second skipped if idle)
      Gathered4 g = gather4(*b, h, B);
      visit_lanes<Check>(*b, h, g.c[0], g.c[1], g.c[2], g.cinv, g.a[0], g.a[1], g.a[2], g.ainv, omega, keep,
                         sums[h / 4], status);
      scatter4(*b, h, g, B);
      if constexpr (Check) close_lanes(*b, h, sums[h / 4], status, block_sums);
    }
  }
  if (Check && carry) std::memcpy(carry->v, sums, sizeof sums);
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
void sweep_sse2(Bundle* first, Bundle* last, SolverBody* B, double omega, CriteriaAccumulator* block_sums,
                LaneCarry* carry) {
  const double keep = 1.0 - omega;
  constexpr int K = ContactBundle::kLanes;
  LaneSums<V2> sums[K / 2];
  static_assert(sizeof sums == sizeof carry->v);
  if (Check && carry) std::memcpy(sums, carry->v, sizeof sums);
  V2 status{};
  for (Bundle* b = first; b != last; ++b) {
    fetch_ahead(b, last);
    for (int h = 0; h < K; h += 2) {  // pairs of lanes, independent
      SolverBody& c0 = body_at(B, b->cd_word[h]);
      SolverBody& c1 = body_at(B, b->cd_word[h + 1]);
      SolverBody& a0 = body_at(B, b->an_word[h]);
      SolverBody& a1 = body_at(B, b->an_word[h + 1]);
      Pair c = gather2(c0, c1, *b, h, true), a = gather2(a0, a1, *b, h, false);
      visit_lanes<Check>(*b, h, c.vx, c.vy, c.w, c.inv, a.vx, a.vy, a.w, a.inv, omega, keep, sums[h / 2], status);
      // the dynamic bodies of the live lanes: the candidates' rows, then the antagonists'
      scatter2(c, c0, b->write_cd[h], c1, b->write_cd[h + 1]);
      scatter2(a, a0, b->write_an[h], a1, b->write_an[h + 1]);
      if constexpr (Check) close_lanes(*b, h, sums[h / 2], status, block_sums);
    }
  }
  if (Check && carry) std::memcpy(carry->v, sums, sizeof sums);
}

}  // namespace
#endif

namespace {
template <class Bundle>
void sweep_any(Bundle* first, Bundle* last, SolverBody* bodies, double omega, bool check,
               CriteriaAccumulator* block_sums, int width, LaneCarry* carry) {
#ifdef NSCD_HAVE_LANES
  width = std::min(width, lane_width());
  const double w = check ? 1.0 : omega;
  if (width >= 4)
    check ? sweep_avx2<true>(first, last, bodies, w, block_sums, carry)
          : sweep_avx2<false>(first, last, bodies, w, static_cast<CriteriaAccumulator*>(nullptr), carry);
  else
    check ? sweep_sse2<true>(first, last, bodies, w, block_sums, carry)
          : sweep_sse2<false>(first, last, bodies, w, static_cast<CriteriaAccumulator*>(nullptr), carry);
#else
  (void)first, (void)last, (void)bodies, (void)omega, (void)check, (void)block_sums, (void)width, (void)carry;
#endif
}
}  // namespace

void sweep_bundles(MassBundle* first, MassBundle* last, SolverBody* bodies, double omega, bool check,
                   CriteriaAccumulator* block_sums, int width, LaneCarry* carry) {
  sweep_any(first, last, bodies, omega, check, block_sums, width, carry);
}
void sweep_bundles(ContactBundle* first, ContactBundle* last, SolverBody* bodies, double omega, bool check,
                   CriteriaAccumulator* block_sums, int width, LaneCarry* carry) {
  sweep_any(first, last, bodies, omega, check, block_sums, width, carry);
}

}  // namespace nscd
