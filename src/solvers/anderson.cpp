// nscd/solvers/anderson.cpp — see anderson.hpp.
#include "nscd/solvers/anderson.hpp"

#include <algorithm>
#include <cmath>

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

// Eight partial sums (index mod 8), added in a fixed order: the same result everywhere, and
// the loop vectorises instead of waiting on one long chain of additions.
NSCD_MIX_CLONES double dot(const double* __restrict a, const double* __restrict b, std::size_t n) {
  double s[8] = {};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
    for (int k = 0; k < 8; ++k) s[k] += a[i + k] * b[i + k];
  for (int k = 0; i < n; ++i, ++k) s[k] += a[i] * b[i];
  return ((s[0] + s[4]) + (s[1] + s[5])) + ((s[2] + s[6]) + (s[3] + s[7]));
}

// y −= Σ_j γ_j columns[j] (columns of length n, stored one after the other): each y[i] gets
// its K subtractions in column order, in one pass over y (K columns read once, y once).
template <int K>
NSCD_MIX_CLONES void subtract_k(double* __restrict y, const double* __restrict columns, const double* gamma, std::size_t n) {
  double g[K];
  for (int j = 0; j < K; ++j) g[j] = gamma[j];
  for (std::size_t i = 0; i < n; ++i) {
    double v = y[i];
    for (int j = 0; j < K; ++j) v -= g[j] * columns[static_cast<std::size_t>(j) * n + i];
    y[i] = v;
  }
}
void subtract_columns(double* y, const double* columns, const double* gamma, int k, std::size_t n) {
  static_assert(AndersonMixer::kMaxDepth == 8);
  switch (k) {
    case 1: return subtract_k<1>(y, columns, gamma, n);
    case 2: return subtract_k<2>(y, columns, gamma, n);
    case 3: return subtract_k<3>(y, columns, gamma, n);
    case 4: return subtract_k<4>(y, columns, gamma, n);
    case 5: return subtract_k<5>(y, columns, gamma, n);
    case 6: return subtract_k<6>(y, columns, gamma, n);
    case 7: return subtract_k<7>(y, columns, gamma, n);
    case 8: return subtract_k<8>(y, columns, gamma, n);
    default: return;
  }
}

// This period's residual f = x − x0 over the impulses: ΔF = f − f_last into df, f_last = f;
// returns ‖f‖² (eight partial sums, as dot()).
NSCD_MIX_CLONES double residual_column(const double* __restrict x, const double* __restrict x0, double* __restrict f_last,
                                       double* __restrict df, std::size_t n) {
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
  return ((s[0] + s[4]) + (s[1] + s[5])) + ((s[2] + s[6]) + (s[3] + s[7]));
}

// ΔG (impulses and velocities) = xv − gv_last into dgv, gv_last = xv.
NSCD_MIX_CLONES void result_column(const double* __restrict xv, double* __restrict gv_last, double* __restrict dgv,
                                   std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    dgv[i] = xv[i] - gv_last[i];
    gv_last[i] = xv[i];
  }
}

}  // namespace

void AndersonMixer::start(std::size_t contacts, std::size_t links, std::size_t velocities, int depth) {
  if (depth < 1 || depth > kMaxDepth)
    throw Error("Anderson mixing: depth must lie in [1, " + std::to_string(kMaxDepth) + "], got " + std::to_string(depth));
  nc_ = contacts;
  nx_ = 2 * contacts + links;
  nv_ = velocities;
  depth_ = depth;
  xv_.resize(nx_ + nv_);
  gv_last_.resize(nx_ + nv_);
  x0_.resize(nx_);
  f_last_.resize(nx_);
  dF_.resize(static_cast<std::size_t>(depth) * nx_);
  dGV_.resize(static_cast<std::size_t>(depth) * (nx_ + nv_));
  moved_.clear();
  mixes_ = restarts_ = 0;
}

void AndersonMixer::begin() {
  std::copy(xv_.begin(), xv_.begin() + static_cast<std::ptrdiff_t>(nx_), x0_.begin());
  count_ = head_ = 0;
  have_last_ = false;
}

bool AndersonMixer::mix(const double* mu) {
  moved_.clear();
  const std::size_t nxv = nx_ + nv_;
  // 1. This period's residual f = G(x0) − x0 and the differences with the last period's, written
  //    in the history's next column: ΔF = f − f_last, ΔG and ΔV = the results' differences.
  const std::size_t h = static_cast<std::size_t>(head_);
  double* df = dF_.data() + h * nx_;
  const double norm2 = residual_column(xv_.data(), x0_.data(), f_last_.data(), df, nx_);
  result_column(xv_.data(), gv_last_.data(), dGV_.data() + h * nxv, nxv);
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
    for (int j = 0; j < count_; ++j) {
      if (static_cast<std::size_t>(j) == h) {
        gram_[h][h] = dot(df, df, nx_);
        rhs_[h] = dot(df, f_last_.data(), nx_);
      } else {
        gram_[h][j] = gram_[j][h] = dot(df, dF_.data() + static_cast<std::size_t>(j) * nx_, nx_);
        rhs_[j] += gram_[h][j];
      }
    }
  }
  last_norm_ = norm2;
  have_last_ = true;
  const int k = count_;
  auto keep_unmixed = [&] {
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
  double gamma[kMaxDepth];
  for (int c = k - 1; c >= 0; --c) {
    double s = a[c][k];
    for (int j = c + 1; j < k; ++j) s -= a[c][j] * gamma[j];
    gamma[c] = s / a[c][c];
  }
  // 4. The mixed iterate, impulses and velocities with the same weights.
  subtract_columns(xv_.data(), dGV_.data(), gamma, k, nxv);
  // 5. Back on the cones (the links' impulses are free); the next period starts here.
  double* x = xv_.data();
  for (std::size_t c = 0; c < nc_; ++c) {
    const double pn = x[2 * c], pt = x[2 * c + 1];
    const double n = std::max(pn, 0.0), t = std::clamp(pt, -mu[c] * n, mu[c] * n);
    if (n != pn || t != pt) {
      moved_.push_back({static_cast<std::uint32_t>(c), n - pn, t - pt});
      x[2 * c] = n;
      x[2 * c + 1] = t;
    }
  }
  std::copy(x, x + nx_, x0_.begin());
  ++mixes_;
  return true;
}

}  // namespace nscd
