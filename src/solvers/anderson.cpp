// nscd/solvers/anderson.cpp — see anderson.hpp.
#include "nscd/solvers/anderson.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include "nscd/core/error.hpp"

namespace nscd {
namespace {

// The vector loops also in an AVX2 clone, chosen at run time where the CPU has it (GCC's
// target_clones); without FMA (the file is built with -ffp-contract=off), so both clones give
// the same numbers.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define NSCD_MIX_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define NSCD_MIX_CLONES
#endif

// The eight partial sums of a dot product (index mod 8), added in a fixed order: the same
// result everywhere, and the loop vectorises instead of waiting on one long chain of additions.
inline double add_partials(const double* s) {
  return ((s[0] + s[4]) + (s[1] + s[5])) + ((s[2] + s[6]) + (s[3] + s[7]));
}

// out[j] = a · b[j] for K vectors b[j] in one pass over a, each with its own eight partial sums
// (index mod 8, two vectors of four), so each is what a dot product alone would give.
using Double4 = double __attribute__((vector_size(32)));
template <int K>
NSCD_MIX_CLONES void dots_k(const double* __restrict a, const double* const* b, double* out, std::size_t n) {
  Double4 lo[K] = {}, hi[K] = {};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    Double4 a0, a1, b0, b1;  // unaligned loads
    std::memcpy(&a0, a + i, sizeof a0);
    std::memcpy(&a1, a + i + 4, sizeof a1);
    for (int j = 0; j < K; ++j) {
      std::memcpy(&b0, b[j] + i, sizeof b0);
      std::memcpy(&b1, b[j] + i + 4, sizeof b1);
      lo[j] += a0 * b0;
      hi[j] += a1 * b1;
    }
  }
  for (int j = 0; j < K; ++j) {
    double s[8] = {lo[j][0], lo[j][1], lo[j][2], lo[j][3], hi[j][0], hi[j][1], hi[j][2], hi[j][3]};
    for (std::size_t r = i, k = 0; r < n; ++r, ++k) s[k] += a[r] * b[j][r];
    out[j] = add_partials(s);
  }
}
void dots(const double* a, const double* const* b, double* out, int k, std::size_t n) {
  static_assert(AndersonMixer::kMaxDepth + 1 == 9);
  switch (k) {
    case 1: return dots_k<1>(a, b, out, n);
    case 2: return dots_k<2>(a, b, out, n);
    case 3: return dots_k<3>(a, b, out, n);
    case 4: return dots_k<4>(a, b, out, n);
    case 5: return dots_k<5>(a, b, out, n);
    case 6: return dots_k<6>(a, b, out, n);
    case 7: return dots_k<7>(a, b, out, n);
    case 8: return dots_k<8>(a, b, out, n);
    case 9: return dots_k<9>(a, b, out, n);
    default: return;
  }
}

// The mixed iterate, in one pass: column h of the history gets this period's results' difference
// ΔG_h = y − last (and last = y), then y −= Σ_j γ_j ΔG_j, each y[i] its K subtractions in column
// order (n entries from the columns' start, the columns `stride` apart; h < K). Each entry on its
// own: a range gives the same numbers as the whole.
template <int K>
NSCD_MIX_CLONES void mix_columns_k(double* __restrict y, double* __restrict last, double* __restrict columns, int h,
                                   const double* gamma, std::size_t n, std::size_t stride) {
  double g[K];
  for (int j = 0; j < K; ++j) g[j] = gamma[j];
  double* column_h = columns + static_cast<std::size_t>(h) * stride;
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {  // four at a time (Double4: the other columns are only read)
    Double4 r, l, c;
    std::memcpy(&r, y + i, sizeof r);
    std::memcpy(&l, last + i, sizeof l);
    const Double4 d = r - l;
    std::memcpy(last + i, &r, sizeof r);
    std::memcpy(column_h + i, &d, sizeof d);
    Double4 v = r;
    for (int j = 0; j < K; ++j) {
      if (j == h)
        c = d;
      else
        std::memcpy(&c, columns + static_cast<std::size_t>(j) * stride + i, sizeof c);
      v -= g[j] * c;
    }
    std::memcpy(y + i, &v, sizeof v);
  }
  for (; i < n; ++i) {
    const double r = y[i], d = r - last[i];
    last[i] = r;
    column_h[i] = d;
    double v = r;
    for (int j = 0; j < K; ++j) v -= g[j] * (j == h ? d : columns[static_cast<std::size_t>(j) * stride + i]);
    y[i] = v;
  }
}
void mix_columns(double* y, double* last, double* columns, int h, const double* gamma, int k, std::size_t n,
                 std::size_t stride) {
  static_assert(AndersonMixer::kMaxDepth == 8);
  switch (k) {
    case 1: return mix_columns_k<1>(y, last, columns, h, gamma, n, stride);
    case 2: return mix_columns_k<2>(y, last, columns, h, gamma, n, stride);
    case 3: return mix_columns_k<3>(y, last, columns, h, gamma, n, stride);
    case 4: return mix_columns_k<4>(y, last, columns, h, gamma, n, stride);
    case 5: return mix_columns_k<5>(y, last, columns, h, gamma, n, stride);
    case 6: return mix_columns_k<6>(y, last, columns, h, gamma, n, stride);
    case 7: return mix_columns_k<7>(y, last, columns, h, gamma, n, stride);
    case 8: return mix_columns_k<8>(y, last, columns, h, gamma, n, stride);
    default: return;
  }
}

// This period's residual f = x − x0 over the impulses: ΔF = f − f_last into df, f_last = f;
// returns ‖f‖² (eight partial sums, as dots_k).
NSCD_MIX_CLONES double residual_column(const double* __restrict x, const double* __restrict x0,
                                       double* __restrict f_last, double* __restrict df, std::size_t n) {
  double s[8] = {};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
    for (int k = 0; k < 8; ++k) {
      const double f = x[i + k] - x0[i + k];
      s[k] += f * f;
      df[i + k] = f - f_last[i + k];
      f_last[i + k] = f;
    }
  for (int k = 0; i < n; ++i, ++k) {
    const double f = x[i] - x0[i];
    s[k] += f * f;
    df[i] = f - f_last[i];
    f_last[i] = f;
  }
  return add_partials(s);
}

// Chunks i0 … i1−1 of the impulses (chunk i: entries begins[i] … ends[i] − 1), in one pass
// each: the residual's column as residual_column (f = x − x0, d = f − f_last into df, f_last =
// f) and, for K > 0, d's products with the K − 1 history columns `cols` (stride apart; df, the
// one being written, among them: read back once d is stored) and with f. Each sum in four lanes (entry mod 4 from the chunk's start), added
// as (s0 + s2) + (s1 + s3), into out[i × stride_out …]: ‖f‖² then the K products. Small chunks
// (a block of a colored layout: tens of contacts) pay little more than their entries.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // (its lambdas pass vectors: local, no ABI to keep)
#endif
template <int K>
NSCD_MIX_CLONES void chunk_sums_k(const double* __restrict x, const double* __restrict x0, double* __restrict f_last,
                                  double* df, const double* cols, std::size_t stride, const std::size_t* begins,
                                  const std::size_t* ends, std::size_t i0, std::size_t i1, double* out,
                                  std::size_t stride_out) {
  for (std::size_t c = i0; c < i1; ++c) {
    Double4 acc[K + 1] = {};
    std::size_t i = begins[c];
    const std::size_t end = ends[c], body = i + (end - i) / 4 * 4;
    auto entries = [&](auto load, auto store, std::size_t at) {
      const Double4 f = load(x, at) - load(x0, at), d = f - load(f_last, at);
      store(df, at, d);
      store(f_last, at, f);
      acc[0] += f * f;
      for (int j = 0; j + 1 < K; ++j) acc[j + 1] += d * load(cols + static_cast<std::size_t>(j) * stride, at);
      if constexpr (K > 0) acc[K] += d * f;
    };
    auto load4 = [](const double* p, std::size_t at) {
      Double4 v;
      std::memcpy(&v, p + at, sizeof v);
      return v;
    };
    auto store4 = [](double* p, std::size_t at, const Double4& v) { std::memcpy(p + at, &v, sizeof v); };
    for (; i < body; i += 4) entries(load4, store4, i);
    if (end - i == 2) {  // a contact's two entries (a chunk of contacts ends so or on a multiple of 4)
      auto load2 = [](const double* p, std::size_t at) {
        Double4 v = {};
        std::memcpy(&v, p + at, 2 * sizeof(double));
        return v;
      };
      auto store2 = [](double* p, std::size_t at, const Double4& v) { std::memcpy(p + at, &v, 2 * sizeof(double)); };
      entries(load2, store2, i);
    } else if (i < end) {  // the last 1 … 3 entries in lanes 0 … 2, the others zero
      const std::size_t r = end - i;
      auto load_r = [r](const double* p, std::size_t at) {
        Double4 v = {};
        for (std::size_t q = 0; q < r; ++q) v[q] = p[at + q];
        return v;
      };
      auto store_r = [r](double* p, std::size_t at, const Double4& v) {
        for (std::size_t q = 0; q < r; ++q) p[at + q] = v[q];
      };
      entries(load_r, store_r, i);
    }
    for (int j = 0; j <= K; ++j)
      out[c * stride_out + static_cast<std::size_t>(j)] = (acc[j][0] + acc[j][2]) + (acc[j][1] + acc[j][3]);
  }
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
void chunk_sums(const double* x, const double* x0, double* f_last, double* df, const double* cols, std::size_t stride,
                int k, const std::size_t* begins, const std::size_t* ends, std::size_t i0, std::size_t i1, double* out,
                std::size_t stride_out) {
  static_assert(AndersonMixer::kMaxDepth + 1 == 9);
  // each chunk's sums on the lines decide() read on another core at the last mixing: all asked
  // for at once, not one at a time as each chunk ends (docs/record/benchmarks-history.md §11.14)
  for (std::size_t c = i0; c < i1; ++c)
    for (int j = 0; j <= k; j += static_cast<int>(kCacheLine / sizeof(double))) claim_line(out + c * stride_out + j);
  switch (k) {
#define NSCD_CHUNK_SUMS(K) \
  case K:                  \
    return chunk_sums_k<K>(x, x0, f_last, df, cols, stride, begins, ends, i0, i1, out, stride_out);
    NSCD_CHUNK_SUMS(0)
    NSCD_CHUNK_SUMS(1)
    NSCD_CHUNK_SUMS(2) NSCD_CHUNK_SUMS(3) NSCD_CHUNK_SUMS(4) NSCD_CHUNK_SUMS(5) NSCD_CHUNK_SUMS(6) NSCD_CHUNK_SUMS(7)
        NSCD_CHUNK_SUMS(8) NSCD_CHUNK_SUMS(9)
#undef NSCD_CHUNK_SUMS
            default : return;
  }
}

// ΔG (impulses and velocities) = xv − gv_last into dgv, gv_last = xv.
NSCD_MIX_CLONES void result_column(const double* __restrict xv, double* __restrict gv_last, double* __restrict dgv,
                                   std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    dgv[i] = xv[i] - gv_last[i];
    gv_last[i] = xv[i];
  }
}

// Every contact's impulse x projected on its cone in place (P_N ≥ 0, |P_T| ≤ μ P_N: std::max and
// std::clamp's comparisons, written so that the loop vectorises); x0 gets the impulse before the
// projection (the same as after, but where flag[c] = 1: the contact moved), for list_moves. No
// branch: most contacts do not move, and the others are scattered.
NSCD_MIX_CLONES void project_cones(double* __restrict x, double* __restrict x0, const double* __restrict mu,
                                   std::uint64_t* __restrict flag, std::size_t nc) {
  for (std::size_t c = 0; c < nc; ++c) {
    const double pn = x[2 * c], pt = x[2 * c + 1];
    const double n = pn < 0.0 ? 0.0 : pn;  // std::max(pn, 0.0)
    const double lo = -mu[c] * n, hi = mu[c] * n;
    const double t = pt < lo ? lo : (hi < pt ? hi : pt);  // std::clamp(pt, lo, hi)
    flag[c] = static_cast<std::uint64_t>((n != pn) | (t != pt));
    x[2 * c] = n;
    x[2 * c + 1] = t;
    x0[2 * c] = pn;  // the impulse before, until list_moves has read it
    x0[2 * c + 1] = pt;
  }
}

// The contacts c0 … c1−1 that project_cones moved, in contact order, with their change (the
// contact's number: its index less `shift`); x0 gets their projected impulse (as every other
// contact's). Four flags at a time: four zeros are skipped.
void list_moves(const double* x, double* x0, const std::uint64_t* flag, std::size_t c0, std::size_t c1,
                std::ptrdiff_t shift, std::vector<AndersonMixer::Move>& moved) {
  auto take = [&](std::size_t from, std::size_t to) {
    for (std::size_t k = from; k < to; ++k)
      if (flag[k]) {
        moved.push_back({static_cast<std::uint32_t>(static_cast<std::ptrdiff_t>(k) - shift), x[2 * k] - x0[2 * k],
                         x[2 * k + 1] - x0[2 * k + 1]});
        x0[2 * k] = x[2 * k];
        x0[2 * k + 1] = x[2 * k + 1];
      }
  };
  std::size_t c = c0;
  for (; c + 4 <= c1; c += 4)
    if ((flag[c] | flag[c + 1] | flag[c + 2] | flag[c + 3]) != 0) take(c, c + 4);
  take(c, c1);
}

}  // namespace

void AndersonMixer::start(std::size_t contacts, std::size_t links, std::size_t velocities, int depth) {
  if (depth < 1 || depth > kMaxDepth)
    throw Error("Anderson mixing: depth must lie in [1, " + std::to_string(kMaxDepth) + "], got " +
                std::to_string(depth));
  constexpr std::size_t page = kPage / sizeof(double);
  nc_ = contacts;
  nx_ = 2 * contacts + links;
  nv_ = velocities;
  // Each array, and each history column, a few lines apart in a page from every other (column j
  // of dF at 8 + 2j lines, of dGV at 24 + 4j: up to 52 of a page's 64 lines).
  constexpr std::size_t line = kCacheLine / sizeof(double), kColumnSkew = 2;
  sx_ = round_up(nx_, page) + kColumnSkew * line;
  sv_ = round_up(nv_, page) + kColumnSkew * line;
  depth_ = depth;
  xv_.resize(sx_ + sv_, 0);
  gv_last_.resize(sx_ + sv_, 2);
  x0_.resize(sx_, 4);
  f_last_.resize(sx_, 6);
  dF_.resize(static_cast<std::size_t>(depth) * sx_, 8);
  dGV_.resize(static_cast<std::size_t>(depth) * (sx_ + sv_), 24);
  moved_flag_.resize(contacts, 56);
  bounds_.assign({0});
  ends_.assign({nx_});
  partial_.resize(kSumStride);
  moved_.clear();
  mixes_ = restarts_ = 0;
}

void AndersonMixer::set_chunks(const std::vector<std::size_t>& bounds) {
  if (bounds.size() < 2 || bounds.front() != 0 || bounds.back() != nx_ || !std::is_sorted(bounds.begin(), bounds.end()))
    throw Error("Anderson mixing: the chunks must run from 0 to the impulses' end (" + std::to_string(nx_) +
                ") in increasing order");
  bounds_.assign(bounds.begin(), bounds.end() - 1);
  ends_.assign(bounds.begin() + 1, bounds.end());
  partial_.resize(chunks() * kSumStride);
}

void AndersonMixer::set_chunks(const std::vector<std::size_t>& begins, const std::vector<std::size_t>& ends) {
  bool ok = !begins.empty() && begins.size() == ends.size();
  std::vector<std::pair<std::size_t, std::size_t>>& spans = spans_;
  spans.clear();
  for (std::size_t i = 0; ok && i < begins.size(); ++i) {
    ok = begins[i] <= ends[i] && ends[i] <= nx_;
    spans.emplace_back(begins[i], ends[i]);
  }
  std::sort(spans.begin(), spans.end());
  for (std::size_t i = 1; ok && i < spans.size(); ++i) ok = spans[i - 1].second <= spans[i].first;
  if (!ok)
    throw Error("Anderson mixing: each chunk must begin before it ends, within the " + std::to_string(nx_) +
                " impulses, and overlap no other");
  bounds_ = begins;
  ends_ = ends;
  partial_.resize(chunks() * kSumStride);
}

void AndersonMixer::begin_history() {
  count_ = head_ = 0;
  have_last_ = restart_at_next_ = false;
}

void AndersonMixer::begin_range(std::size_t from, std::size_t to) {
  std::copy(xv_.data() + from, xv_.data() + to, x0_.data() + from);
}

bool AndersonMixer::mix(const double* mu) {
  moved_.clear();
  if (!restarting()) sums(0, chunks());
  const Verdict v = decide(mu);
  apply_x(0, nx_, moved_);
  apply_v(0, nv_);
  return v == Verdict::Mixed;
}

// 1. This period's residual f = G(x0) − x0 and its difference with the last period's, written in
//    the history's next column h: ΔF = f − f_last (ΔG and ΔV, the results' differences, are
//    written in the same column by apply_x and apply_v). With a history, the new column's
//    products with the columns it will have (itself included) and with f, should it join.
//    Chunk by chunk: chunk i's sums into partial_ (‖f‖², then the products).
void AndersonMixer::sums(std::size_t i0, std::size_t i1) {
  const std::size_t h = static_cast<std::size_t>(head_);
  double* df = dF_.data() + h * sx_;
  const int k = have_last_ ? std::min(count_ + 1, depth_) : 0;
  if (chunks() > 1)  // (k columns, f among them: k + 1 products)
    return chunk_sums(xv_.data(), x0_.data(), f_last_.data(), df, dF_.data(), sx_, k > 0 ? k + 1 : 0, bounds_.data(),
                      ends_.data(), i0, i1, partial_.data(), kSumStride);
  // one chunk (the sequential orders): eight partial sums from its first entry, the loops of
  // the mixer's first form
  if (i1 <= i0) return;
  const std::size_t b = bounds_[0], n = ends_[0] - b;
  partial_[0] = residual_column(xv_.data() + b, x0_.data() + b, f_last_.data() + b, df + b, n);
  if (k == 0) return;
  const double* with[kMaxDepth + 1];
  for (int j = 0; j < k; ++j) with[j] = dF_.data() + static_cast<std::size_t>(j) * sx_ + b;
  with[k] = f_last_.data() + b;
  dots(df + b, with, partial_.data() + 1, k + 1, n);
}

// γ from the normal equations (ΔFᵀΔF + λ I) γ = ΔFᵀ f, λ a 1e-10 of the trace (nearly parallel
// columns), by Gaussian elimination with partial pivoting; false where a pivot vanishes.
static bool solve_weights(const double (&gram)[AndersonMixer::kMaxDepth][AndersonMixer::kMaxDepth], const double* rhs,
                          int k, double* gamma) {
  double a[AndersonMixer::kMaxDepth][AndersonMixer::kMaxDepth + 1];
  double trace = 0.0;
  for (int i = 0; i < k; ++i) trace += gram[i][i];
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) a[i][j] = gram[i][j];
    a[i][i] += 1e-10 * trace;
    a[i][k] = rhs[i];
  }
  for (int c = 0; c < k; ++c) {
    int p = c;
    for (int r = c + 1; r < k; ++r)
      if (std::abs(a[r][c]) > std::abs(a[p][c])) p = r;
    if (!(std::abs(a[p][c]) > 0.0)) return false;
    if (p != c) std::swap(a[p], a[c]);
    for (int r = c + 1; r < k; ++r) {
      const double m = a[r][c] / a[c][c];
      for (int j = c; j <= k; ++j) a[r][j] -= m * a[c][j];
    }
  }
  for (int c = k - 1; c >= 0; --c) {
    double s = a[c][k];
    for (int j = c + 1; j < k; ++j) s -= a[c][j] * gamma[j];
    gamma[c] = s / a[c][c];
  }
  return true;
}

// 2. The chunks' sums added in chunk order. The new column joins the history (the oldest goes
//    when it is full), unless this is the first period or the residual more than doubled: then
//    the history restarts from here. With it, its row of ΔFᵀΔF, and ΔFᵀ f by recurrence
//    (f = f_last + ΔF_new: each older column's product grows by its product with the new
//    column; the new one's is computed). 3. γ (solve_weights).
AndersonMixer::Verdict AndersonMixer::decide(const double* mu) {
  mu_ = mu;
  mix_h_ = head_;
  if (restart_at_next_) {
    count_ = head_ = 0;
    have_last_ = restart_at_next_ = false;
    return verdict_ = Verdict::Restart;
  }
  const std::size_t h = static_cast<std::size_t>(head_);
  const int with = have_last_ ? std::min(count_ + 1, depth_) : 0;
  double total[kSums] = {};
  std::copy(partial_.begin(), partial_.begin() + with + 2, total);
  for (std::size_t i = 1; i < chunks(); ++i)
    for (int j = 0; j < with + 2; ++j) total[j] += partial_[i * kSumStride + static_cast<std::size_t>(j)];
  const double norm2 = total[0], *product = total + 1;
  if (!have_last_) {
    count_ = head_ = 0;
  } else if (norm2 > 4.0 * last_norm_) {
    count_ = head_ = 0;
    ++restarts_;
  } else {
    count_ = with;
    head_ = (head_ + 1) % depth_;
    for (int j = 0; j < count_; ++j) {
      gram_[h][j] = gram_[j][h] = product[j];
      if (static_cast<std::size_t>(j) != h) rhs_[j] += product[j];
    }
    rhs_[h] = product[count_];
  }
  last_norm_ = norm2;
  have_last_ = true;
  mix_k_ = count_;
  if (mix_k_ == 0 || norm2 == 0.0 || !solve_weights(gram_, rhs_, mix_k_, gamma_)) return verdict_ = Verdict::Unmixed;
  ++mixes_;
  return verdict_ = Verdict::Mixed;
}

// 4. Restart: the impulses are the first iterate. Unmixed: the results' difference ΔG is still
//    recorded, and the next period starts here. Mixed: the mixed iterate (impulses and
//    velocities with the same weights, and ΔG, ΔV), 5. back on the cones (the links' impulses
//    are free); the next period starts here.
void AndersonMixer::apply_x(std::size_t from, std::size_t to, std::vector<Move>& moves, std::ptrdiff_t shift) {
  if (to <= from) return;
  const std::size_t nxv = sx_ + sv_, h = static_cast<std::size_t>(mix_h_);
  auto keep = [&](std::size_t a, std::size_t b) {
    std::copy(xv_.data() + a, xv_.data() + b, x0_.data() + a);
  };
  if (verdict_ == Verdict::Restart) return keep(from, to);
  if (verdict_ == Verdict::Unmixed) {
    result_column(xv_.data() + from, gv_last_.data() + from, dGV_.data() + h * nxv + from, to - from);
    return keep(from, to);
  }
  mix_columns(xv_.data() + from, gv_last_.data() + from, dGV_.data() + from, mix_h_, gamma_, mix_k_, to - from, nxv);
  const std::size_t c0 = from / 2, c1 = std::min(to, 2 * nc_) / 2;
  if (c1 > c0) {
    project_cones(xv_.data() + 2 * c0, x0_.data() + 2 * c0, mu_ + c0, moved_flag_.data() + c0, c1 - c0);
    list_moves(xv_.data(), x0_.data(), moved_flag_.data(), c0, c1, shift, moves);
  }
  if (to > 2 * nc_) keep(std::max(from, 2 * nc_), to);
}

void AndersonMixer::apply_v(std::size_t from, std::size_t to) {
  if (to <= from || verdict_ == Verdict::Restart) return;
  const std::size_t nxv = sx_ + sv_, h = static_cast<std::size_t>(mix_h_);
  from += sx_;
  to += sx_;
  if (verdict_ == Verdict::Unmixed)
    return result_column(xv_.data() + from, gv_last_.data() + from, dGV_.data() + h * nxv + from, to - from);
  mix_columns(xv_.data() + from, gv_last_.data() + from, dGV_.data() + from, mix_h_, gamma_, mix_k_, to - from, nxv);
}

}  // namespace nscd
