// nscd/solvers/anderson.cpp — see anderson.hpp.
#include "nscd/solvers/anderson.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

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

// The contacts project_cones moved, in contact order, with their change; x0 gets their projected
// impulse (as every other contact's). Four flags at a time: four zeros are skipped.
void list_moves(const double* x, double* x0, const std::uint64_t* flag, std::size_t nc,
                std::vector<AndersonMixer::Move>& moved) {
  auto take = [&](std::size_t from, std::size_t to) {
    for (std::size_t k = from; k < to; ++k)
      if (flag[k]) {
        moved.push_back({static_cast<std::uint32_t>(k), x[2 * k] - x0[2 * k], x[2 * k + 1] - x0[2 * k + 1]});
        x0[2 * k] = x[2 * k];
        x0[2 * k + 1] = x[2 * k + 1];
      }
  };
  std::size_t c = 0;
  for (; c + 4 <= nc; c += 4)
    if ((flag[c] | flag[c + 1] | flag[c + 2] | flag[c + 3]) != 0) take(c, c + 4);
  take(c, nc);
}

}  // namespace

void AndersonMixer::start(std::size_t contacts, std::size_t links, std::size_t velocities, int depth) {
  if (depth < 1 || depth > kMaxDepth)
    throw Error("Anderson mixing: depth must lie in [1, " + std::to_string(kMaxDepth) + "], got " +
                std::to_string(depth));
  nc_ = contacts;
  nx_ = 2 * contacts + links;
  nv_ = velocities;
  depth_ = depth;
  xv_.resize(nx_ + nv_);
  gv_last_.resize(nx_ + nv_);
  x0_.resize(nx_);
  f_last_.resize(nx_);
  moved_flag_.resize(contacts);
  dF_.resize(static_cast<std::size_t>(depth) * nx_);
  dGV_.resize(static_cast<std::size_t>(depth) * (nx_ + nv_));
  moved_.clear();
  mixes_ = restarts_ = 0;
}

void AndersonMixer::begin() {
  std::copy(xv_.begin(), xv_.begin() + static_cast<std::ptrdiff_t>(nx_), x0_.begin());
  count_ = head_ = 0;
  have_last_ = restart_at_next_ = false;
}

bool AndersonMixer::mix(const double* mu) {
  if (!mix_begin(mu)) return false;
  mix_range(0, nx_ + nv_);
  project_range(0, nc_);
  mix_end();
  return true;
}

bool AndersonMixer::mix_begin(const double* mu) {
  moved_.clear();
  mu_ = mu;
  if (restart_at_next_) {
    begin();
    return false;
  }
  const std::size_t nxv = nx_ + nv_;
  // 1. This period's residual f = G(x0) − x0 and its difference with the last period's, written
  //    in the history's next column: ΔF = f − f_last (ΔG and ΔV, the results' differences, are
  //    written in the same column by the pass of step 4, or by keep_unmixed).
  const std::size_t h = static_cast<std::size_t>(head_);
  double* df = dF_.data() + h * nx_;
  const double norm2 = residual_column(xv_.data(), x0_.data(), f_last_.data(), df, nx_);
  // 2. The column joins the history (the oldest goes when it is full), unless this is the first
  //    period or the residual more than doubled: then the history restarts from here. With it,
  //    its row of ΔFᵀΔF, and ΔFᵀ f by recurrence (f = f_last + ΔF_new: each older column's
  //    product grows by its product with the new column; the new one's is computed).
  if (!have_last_) {
    count_ = head_ = 0;
  } else if (norm2 > 4.0 * last_norm_) {
    count_ = head_ = 0;
    ++restarts_;
  } else {
    count_ = std::min(count_ + 1, depth_);
    head_ = (head_ + 1) % depth_;
    // the new column's products with every column (itself included) and with f, in one pass
    const double* with[kMaxDepth + 1];
    double product[kMaxDepth + 1];
    for (int j = 0; j < count_; ++j) with[j] = dF_.data() + static_cast<std::size_t>(j) * nx_;
    with[count_] = f_last_.data();
    dots(df, with, product, count_ + 1, nx_);
    for (int j = 0; j < count_; ++j) {
      gram_[h][j] = gram_[j][h] = product[j];
      if (static_cast<std::size_t>(j) != h) rhs_[j] += product[j];
    }
    rhs_[h] = product[count_];
  }
  last_norm_ = norm2;
  have_last_ = true;
  const int k = count_;
  auto keep_unmixed = [&] {  // (the results' difference ΔG is still recorded)
    result_column(xv_.data(), gv_last_.data(), dGV_.data() + h * nxv, nxv);
    std::copy(xv_.begin(), xv_.begin() + static_cast<std::ptrdiff_t>(nx_), x0_.begin());
    return false;
  };
  if (k == 0 || norm2 == 0.0) return keep_unmixed();
  // 3. γ from the normal equations (ΔFᵀΔF + λ I) γ = ΔFᵀ f, λ a 1e-10 of the trace (nearly
  //    parallel columns), by Gaussian elimination with partial pivoting.
  double a[kMaxDepth][kMaxDepth + 1];
  double trace = 0.0;
  for (int i = 0; i < k; ++i) trace += gram_[i][i];
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) a[i][j] = gram_[i][j];
    a[i][i] += 1e-10 * trace;
    a[i][k] = rhs_[i];
  }
  for (int c = 0; c < k; ++c) {
    int p = c;
    for (int r = c + 1; r < k; ++r)
      if (std::abs(a[r][c]) > std::abs(a[p][c])) p = r;
    if (!(std::abs(a[p][c]) > 0.0)) return keep_unmixed();
    if (p != c) std::swap(a[p], a[c]);
    for (int r = c + 1; r < k; ++r) {
      const double m = a[r][c] / a[c][c];
      for (int j = c; j <= k; ++j) a[r][j] -= m * a[c][j];
    }
  }
  for (int c = k - 1; c >= 0; --c) {
    double s = a[c][k];
    for (int j = c + 1; j < k; ++j) s -= a[c][j] * gamma_[j];
    gamma_[c] = s / a[c][c];
  }
  mix_k_ = k;
  mix_h_ = static_cast<int>(h);
  return true;
}

// 4. The mixed iterate, impulses and velocities with the same weights (and ΔG, ΔV).
void AndersonMixer::mix_range(std::size_t from, std::size_t to) {
  if (to <= from) return;
  mix_columns(xv_.data() + from, gv_last_.data() + from, dGV_.data() + from, mix_h_, gamma_, mix_k_, to - from,
              nx_ + nv_);
}

// 5. Back on the cones (the links' impulses are free); the next period starts here.
void AndersonMixer::project_range(std::size_t from, std::size_t to) {
  if (to <= from) return;
  project_cones(xv_.data() + 2 * from, x0_.data() + 2 * from, mu_ + from, moved_flag_.data() + from, to - from);
}

void AndersonMixer::mix_end() {
  std::copy(xv_.begin() + static_cast<std::ptrdiff_t>(2 * nc_), xv_.begin() + static_cast<std::ptrdiff_t>(nx_),
            x0_.begin() + static_cast<std::ptrdiff_t>(2 * nc_));
  list_moves(xv_.data(), x0_.data(), moved_flag_.data(), nc_, moved_);
  ++mixes_;
}

}  // namespace nscd
