// nscd/solvers/newton_ac_jacobian.cpp — see newton_ac_jacobian.hpp.
#include "nscd/solvers/newton_ac_jacobian.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "nscd/core/error.hpp"

namespace nscd::newton_ac_detail {

AlartCurnier::AlartCurnier(const FrictionProblem2D& p, const BilateralRows& bil, const NewtonOptions& o)
    : p_(p), o_(o) {
  const std::size_t nc = p.nc;
  wnn_.assign(nc, 1.0);
  is_link_.assign(nc, 0);
  ha_.assign(nc, 0.0);
  hb_.assign(nc, 0.0);
  for (std::size_t k = 0; k < bil.index.size(); ++k) {
    const std::uint32_t i = bil.index[k];
    if (i >= nc) throw Error("NEWTON_AC: bilateral row index " + std::to_string(i) + " outside the problem");
    is_link_[i] = 1;
    ha_[i] = bil.ha[k];
    hb_[i] = bil.hb[k];
  }
  double q2 = 0.0, rq_max = 0.0;
  for (std::size_t i = 0; i < nc; ++i) {
    const double wnn = p.block[p.diag[i]][0];
    if (wnn > 0.0 && std::isfinite(wnn)) wnn_[i] = wnn;
    q2 += p.q[2 * i] * p.q[2 * i] + p.q[2 * i + 1] * p.q[2 * i + 1];
    rq_max = std::max({rq_max, std::abs(p.q[2 * i]) / wnn_[i], std::abs(p.q[2 * i + 1]) / wnn_[i]});
  }
  kink_ = 1e-7 * rq_max;  // impulse scale of the problem × 1e-7
  q_norm_ = std::max(std::sqrt(q2), 1e-300);
  branch_.resize(nc);
  phi_.resize(2 * nc);
  centre_.assign(2 * nc, 0.0);
}

Evaluation AlartCurnier::evaluate_with(const std::vector<double>& r, const std::vector<double>& u) {
  Evaluation e;
  double merit2 = 0.0, nat2 = 0.0, sub2 = 0.0;
  for (std::size_t i = 0; i < p_.nc; ++i) {
    const double rn = r[2 * i], rt = r[2 * i + 1];
    const double un0 = u[2 * i] + p_.q[2 * i], ut0 = u[2 * i + 1] + p_.q[2 * i + 1];
    const double eta = eta_ * wnn_[i];
    const double un = un0 + eta * (rn - centre_[2 * i]);
    const double ut = ut0 + (is_link_[i] ? 0.0 : eta * (rt - centre_[2 * i + 1]));
    double fn, ft;
    if (is_link_[i]) {
      // P = h a − h b U: Φ_N = r_N − h a + h b u_N, Φ_T = r_T
      fn = rn - ha_[i] + hb_[i] * un;
      ft = rt;
      branch_[i] = Branch{1.0, hb_[i], 0.0, 1.0, 0.0, 0.0};
      sub2 += fn * fn + ft * ft;
      const double f0 = rn - ha_[i] + hb_[i] * un0;
      nat2 += f0 * f0 + ft * ft;
    } else {
      friction_rows(i, rn, rt, un, ut, fn, ft);
      nat2 += natural_map2(rn, rt, un0, ut0, p_.mu[i]);
      sub2 += eta_ > 0.0 ? natural_map2(rn, rt, un, ut, p_.mu[i]) : 0.0;
    }
    phi_[2 * i] = fn;
    phi_[2 * i + 1] = ft;
    merit2 += fn * fn + ft * ft;
  }
  e.merit = 0.5 * merit2;
  e.residual = std::sqrt(nat2) / q_norm_;
  e.sub_residual = eta_ > 0.0 ? std::sqrt(sub2) / q_norm_ : e.residual;
  e.finite = std::isfinite(e.merit) && std::isfinite(e.residual);
  return e;
}

void AlartCurnier::friction_rows(std::size_t i, double rn, double rt, double un, double ut, double& fn, double& ft) {
  const double rho = o_.rho_factor / (wnn_[i] * (1.0 + eta_)), mu = p_.mu[i];
  const double a = rn - rho * un;
  const double bound = mu * std::max(0.0, a);
  const double tau = rt - rho * ut;
  Branch& b = branch_[i];
  b = Branch{};
  // Φ on its exact pieces.
  const double s = tau > 0.0 ? 1.0 : -1.0;
  fn = a >= 0.0 ? rho * un : rn;
  ft = a < 0.0 ? rt : (std::abs(tau) <= bound ? rho * ut : rt - s * bound);
  // The Jacobian's piece. At the kinks (a = 0, |τ| = bound) any element of the
  // generalized Jacobian will do; the closed and sticking one is taken. For a contact
  // that carries no impulse yet, "at the kink" allows for rounding (kink_, 1e-7 of the
  // problem's impulse scale): a touching contact with no relative velocity (the inner
  // interfaces of a resting column at r = 0, whose gap shift is 1e-11 instead of 0) then
  // enters the very first Newton step, instead of being activated one per iteration.
  // A contact that carries an impulse takes its exact piece: a tolerance there would
  // pick a Jacobian that is not Φ's on the side the step goes, and the line search
  // would crawl (the 595-grain pile: 97 iterations with it, 30 without; docs/solvers.md).
  // Φ itself stays exact, so is the solution.
  const double kink = (rn == 0.0 && rt == 0.0) ? kink_ : 0.0;
  if (a >= -kink) {  // closed: Φ_N = ρ u_N
    b.dr_n = 0.0;
    b.cn = rho;
    if (std::abs(tau) <= bound + kink) {  // stick: Φ_T = ρ u_T
      b.tt = 0.0;
      b.ctt = rho;
    } else {  // slide: Φ_T = r_T − s μ (r_N − ρ u_N)
      b.tn = -s * mu;
      b.ctn = s * mu * rho;
    }
  }  // else open: Φ_N = r_N, Φ_T = r_T
}

void AlartCurnier::jacobian(double eps, const std::vector<int>& ap, const std::vector<std::uint32_t>& contacts,
                            std::vector<double>& ax) const {
  for (const std::uint32_t i : contacts) {
    std::size_t k = static_cast<std::size_t>(ap[2 * i]);
    const Branch& b = branch_[i];
    const double eta = eta_ * wnn_[i];
    for (int row = 0; row < 2; ++row)
      for (std::uint32_t blk = p_.row_start[i]; blk < p_.row_start[i + 1]; ++blk) {
        std::array<double, 4> w = p_.block[blk];
        const bool diag = p_.col[blk] == i;
        if (diag) {
          w[0] += eta;
          if (!is_link_[i]) w[3] += eta;
        }
        for (int c = 0; c < 2; ++c) {
          double v;
          if (row == 0) {
            v = b.cn * w[c];
            if (diag && c == 0) v += b.dr_n;
          } else {
            v = b.ctn * w[c] + b.ctt * w[2 + c];
            if (diag) v += c == 0 ? b.tn : b.tt;
          }
          if (diag && c == row) v += eps;
          ax[k++] = v;
        }
      }
  }
}

void AlartCurnier::pattern(std::vector<int>& ap, std::vector<int>& ai) const {
  ap.assign(2 * p_.nc + 1, 0);
  ai.clear();
  ai.reserve(4 * p_.block.size());
  for (std::size_t i = 0; i < p_.nc; ++i)
    for (int row = 0; row < 2; ++row) {
      for (std::uint32_t blk = p_.row_start[i]; blk < p_.row_start[i + 1]; ++blk) {
        ai.push_back(static_cast<int>(2 * p_.col[blk]));
        ai.push_back(static_cast<int>(2 * p_.col[blk] + 1));
      }
      ap[2 * i + row + 1] = static_cast<int>(ai.size());
    }
}

double AlartCurnier::natural_map2(double rn, double rt, double un, double ut, double mu) {
  double zn = rn - (un + mu * std::abs(ut)), zt = rt - ut;
  if (zn >= 0.0 && std::abs(zt) <= mu * zn) {
  } else if (mu * std::abs(zt) <= -zn || (mu == 0.0 && zn <= 0.0)) {
    zn = 0.0;
    zt = 0.0;
  } else {
    const double s = zt >= 0.0 ? 1.0 : -1.0;
    const double d = (zn + mu * s * zt) / (1.0 + mu * mu);
    zn = d;
    zt = s * mu * d;
  }
  return (rn - zn) * (rn - zn) + (rt - zt) * (rt - zt);
}

bool FactoredRows::grow(const AlartCurnier& ac, bool all) {
  bool grew = false;
  for (std::size_t i = 0; i < p_.nc; ++i)
    if (local_[i] < 0 && (all || !ac.identity_rows(i))) {
      local_[i] = 0;  // numbered below
      grew = true;
    }
  if (!grew) return false;
  members_.clear();
  for (std::size_t i = 0; i < p_.nc; ++i)
    if (local_[i] >= 0) {
      local_[i] = static_cast<int>(members_.size());
      members_.push_back(static_cast<std::uint32_t>(i));
    }
  build_pattern();
  return true;
}

void FactoredRows::rhs(const std::vector<double>& ax_full, double eps, std::vector<double>& d,
                       std::vector<double>& x) const {
  const double diag = 1.0 + eps;
  for (std::size_t j = 0; j < p_.nc; ++j)
    if (local_[j] < 0) {
      d[2 * j] /= diag;
      d[2 * j + 1] /= diag;
    }
  x.resize(2 * members_.size());
  for (std::size_t m = 0; m < members_.size(); ++m) {
    const std::uint32_t i = members_[m];
    for (int row = 0; row < 2; ++row) {
      double v = d[2 * i + row];
      std::size_t k = ap_full_[2 * i + row];
      for (std::uint32_t blk = p_.row_start[i]; blk < p_.row_start[i + 1]; ++blk, k += 2) {
        const std::uint32_t j = p_.col[blk];
        if (local_[j] < 0) v -= ax_full[k] * d[2 * j] + ax_full[k + 1] * d[2 * j + 1];
      }
      x[2 * m + row] = v;
    }
  }
}

void FactoredRows::build_pattern() {
  ap_.assign(1, 0);
  ai_.clear();
  pick_.clear();
  for (const std::uint32_t i : members_)
    for (int row = 0; row < 2; ++row) {
      std::size_t k = ap_full_[2 * i + row];
      for (std::uint32_t blk = p_.row_start[i]; blk < p_.row_start[i + 1]; ++blk, k += 2) {
        const int lj = local_[p_.col[blk]];
        if (lj < 0) continue;
        ai_.push_back(2 * lj);
        ai_.push_back(2 * lj + 1);
        pick_.push_back(k);
        pick_.push_back(k + 1);
      }
      ap_.push_back(static_cast<int>(ai_.size()));
    }
}

}  // namespace nscd::newton_ac_detail
