// nscd/solvers/anderson.cpp — see anderson.hpp.
#include "nscd/solvers/anderson.hpp"

#include <algorithm>
#include <cmath>

#include "nscd/core/error.hpp"

namespace nscd {
namespace {

// Eight partial sums (index mod 8), added in a fixed order: the same result everywhere, and
// the loop vectorises instead of waiting on one long chain of additions.
double dot(const double* __restrict a, const double* __restrict b, std::size_t n) {
  double s[8] = {};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
    for (int k = 0; k < 8; ++k) s[k] += a[i + k] * b[i + k];
  for (int k = 0; i < n; ++i, ++k) s[k] += a[i] * b[i];
  return ((s[0] + s[4]) + (s[1] + s[5])) + ((s[2] + s[6]) + (s[3] + s[7]));
}

// Two dot products in one pass: a·c and b·c (eight partial sums each, as dot()).
void dot2(const double* __restrict a, const double* __restrict b, const double* __restrict c, std::size_t n, double& ac,
          double& bc) {
  double s[8] = {}, t[8] = {};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
    for (int k = 0; k < 8; ++k) {
      s[k] += a[i + k] * c[i + k];
      t[k] += b[i + k] * c[i + k];
    }
  for (int k = 0; i < n; ++i, ++k) {
    s[k] += a[i] * c[i];
    t[k] += b[i] * c[i];
  }
  ac = ((s[0] + s[4]) + (s[1] + s[5])) + ((s[2] + s[6]) + (s[3] + s[7]));
  bc = ((t[0] + t[4]) + (t[1] + t[5])) + ((t[2] + t[6]) + (t[3] + t[7]));
}

// y −= Σ_j γ_j columns[j] (columns of length n, stored one after the other), a column at a
// time (each pass vectorises).
void subtract_columns(double* __restrict y, const double* __restrict columns, const double* gamma, int k, std::size_t n) {
  for (int j = 0; j < k; ++j) {
    const double g = gamma[j];
    const double* __restrict c = columns + static_cast<std::size_t>(j) * n;
    for (std::size_t i = 0; i < n; ++i) y[i] -= g * c[i];
  }
}

// The history's new column from this period's results x (and residual f = x − x0): ΔF = f −
// f_last, ΔG = x − g_last; f_last and g_last take this period's values.
void new_column(const double* __restrict x, const double* __restrict x0, double* __restrict f_last,
                double* __restrict g_last, double* __restrict df, double* __restrict dg, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const double f = x[i] - x0[i];
    df[i] = f - f_last[i];
    dg[i] = x[i] - g_last[i];
    f_last[i] = f;
    g_last[i] = x[i];
  }
}

void difference(const double* __restrict v, double* __restrict v_last, double* __restrict dv, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    dv[i] = v[i] - v_last[i];
    v_last[i] = v[i];
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
  for (auto* b : {&x_, &x0_, &f_last_, &g_last_}) b->resize(nx_);
  for (auto* b : {&v_, &v_last_}) b->resize(nv_);
  dF_.resize(static_cast<std::size_t>(depth) * nx_);
  dG_.resize(dF_.size());
  dV_.resize(static_cast<std::size_t>(depth) * nv_);
  moved_.clear();
  mixes_ = restarts_ = 0;
}

void AndersonMixer::begin() {
  std::copy(x_.begin(), x_.end(), x0_.begin());
  count_ = head_ = 0;
  have_last_ = false;
}

bool AndersonMixer::mix(const double* mu) {
  moved_.clear();
  // 1. This period's residual f = G(x0) − x0 and its difference with the last one's, written in
  //    the history's next column (one pass): ΔF = f − f_last, ΔG = g − g_last, ΔV = v − v_last.
  const std::size_t h = static_cast<std::size_t>(head_);
  double* df = dF_.data() + h * nx_;
  double* dg = dG_.data() + h * nx_;
  double* dv = dV_.data() + h * nv_;
  new_column(x_.data(), x0_.data(), f_last_.data(), g_last_.data(), df, dg, nx_);
  difference(v_.data(), v_last_.data(), dv, nv_);
  const double norm2 = dot(f_last_.data(), f_last_.data(), nx_);
  // 2. The column joins the history (the oldest goes when it is full), unless this is the first
  //    period or the residual more than doubled: then the history restarts from here.
  if (!have_last_) {
    count_ = head_ = 0;
  } else if (norm2 > 4.0 * last_norm_) {
    count_ = head_ = 0;
    ++restarts_;
  } else {
    count_ = std::min(count_ + 1, depth_);
    head_ = (head_ + 1) % depth_;
  }
  last_norm_ = norm2;
  have_last_ = true;
  const int k = count_;
  if (k == 0 || norm2 == 0.0) {
    std::copy(x_.begin(), x_.end(), x0_.begin());
    return false;
  }
  // 3. The normal equations (ΔFᵀΔF + λ I) γ = ΔFᵀ f, λ a 1e-10 of the trace (nearly parallel
  //    columns): the new column's row of ΔFᵀΔF and the right-hand side in one pass per column,
  //    then Gaussian elimination with partial pivoting.
  double rhs[kMaxDepth];
  for (int j = 0; j < k; ++j) {
    const double* c = dF_.data() + static_cast<std::size_t>(j) * nx_;
    double g = 0.0;
    dot2(df, f_last_.data(), c, nx_, g, rhs[j]);
    gram_[h][j] = gram_[j][h] = g;
  }
  double a[kMaxDepth][kMaxDepth + 1];
  double trace = 0.0;
  for (int i = 0; i < k; ++i) trace += gram_[i][i];
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) a[i][j] = gram_[i][j];
    a[i][i] += 1e-10 * trace;
    a[i][k] = rhs[i];
  }
  for (int c = 0; c < k; ++c) {
    int p = c;
    for (int r = c + 1; r < k; ++r)
      if (std::abs(a[r][c]) > std::abs(a[p][c])) p = r;
    if (!(std::abs(a[p][c]) > 0.0)) {
      std::copy(x_.begin(), x_.end(), x0_.begin());
      return false;
    }
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
  // 4. The mixed iterate, impulses and velocities with the same weights (one pass each).
  subtract_columns(x_.data(), dG_.data(), gamma, k, nx_);
  subtract_columns(v_.data(), dV_.data(), gamma, k, nv_);
  // 5. Back on the cones (the links' impulses are free); the next period starts here.
  for (std::size_t c = 0; c < nc_; ++c) {
    const double pn = x_[2 * c], pt = x_[2 * c + 1];
    const double n = std::max(pn, 0.0), t = std::clamp(pt, -mu[c] * n, mu[c] * n);
    if (n != pn || t != pt) {
      moved_.push_back({static_cast<std::uint32_t>(c), n - pn, t - pt});
      x_[2 * c] = n;
      x_[2 * c + 1] = t;
    }
  }
  std::copy(x_.begin(), x_.end(), x0_.begin());
  ++mixes_;
  return true;
}

}  // namespace nscd
