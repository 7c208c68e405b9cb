// nscd/solvers/convergence.hpp — NLGS convergence measures (LMGC90's definitions) and the
// paper's three policies.
//
// During a checked sweep, each contact visit gives r_k (the impulse before the visit) and
// r_i (the fresh single-contact solution). With W the contact's 2×2 block:
//     ΔV = W (r_k − r_i),  R̄ = (r_k + r_i)/2,
//     WRR = ½ (r_k·W r_k + r_i·W r_i),  WRWR = ½ (|W r_k|² + |W r_i|²),
// summed over the N_act contacts with R̄ != 0:
//     QuadWR  = sqrt(ΣWRWR / N_act)
//     QuadDV  = sqrt(Σ|ΔV|² / N_act) / (QuadWR tol)       MaxmDV  = max|ΔV| / (QuadWR tol)
//     MeanWRR = ΣWRR / N_act
//     QuadDVR = sqrt(Σ|ΔV|²|R̄|² / N_act) / (MeanWRR tol)  MaxmDVR = max(|ΔV||R̄|) / (MeanWRR tol)
//     MeanDVoR = Σ(R̄·ΔV) / (ΣWRR tol)
// Policies (all values below 1 unless said):
//     Quad:      |MeanDVoR|, QuadDV, QuadDVR          (LMGC90 "Quad ")
//     Maxm:      |MeanDVoR|, MaxmDV, MaxmDVR          (LMGC90 "Maxm ")
//     QM16:      Quad, and MaxmDV, MaxmDVR < 16.666   (LMGC90 "QM/16")
//     Strict:    MaxmDV      — every local correction below tol (paper: strict Gauss–Seidel)
//     NonStrict: QuadDV      — their quadratic mean below tol   (paper: non-strict)
//     Energy:    |MeanDVoR|  — the energy-weighted mean          (paper: energy criterion)
#pragma once

#include <algorithm>
#include <cmath>
#include <string_view>

#include "nscd/laws/coulomb2d.hpp"

namespace nscd {

enum class ConvergencePolicy { Quad, Maxm, QM16, Strict, NonStrict, Energy };

ConvergencePolicy parse_convergence_policy(std::string_view name);
std::string_view name_of(ConvergencePolicy p);

struct Criteria {
  double mean_dvor = 0.0, quad_dv = 0.0, maxm_dv = 0.0, quad_dvr = 0.0, maxm_dvr = 0.0;
  std::size_t n_active = 0;
};

/// Accumulates the sums of one checked sweep.
struct CriteriaAccumulator {
  double sum_wrwr = 0.0, sum_dv2 = 0.0, max_dv2 = 0.0, sum_dv2r2 = 0.0, max_dv2r2 = 0.0, sum_wrr = 0.0, sum_rdv = 0.0;
  std::size_t n_active = 0;

  void add(const Block2& W, double rk_n, double rk_t, double ri_n, double ri_t) {
    const double rbn = 0.5 * (rk_n + ri_n), rbt = 0.5 * (rk_t + ri_t);
    if (rbn == 0.0 && rbt == 0.0) return;
    const double wk_n = W.nn * rk_n + W.nt * rk_t, wk_t = W.nt * rk_n + W.tt * rk_t;
    const double wi_n = W.nn * ri_n + W.nt * ri_t, wi_t = W.nt * ri_n + W.tt * ri_t;
    const double dvn = wk_n - wi_n, dvt = wk_t - wi_t;
    const double dv2 = dvn * dvn + dvt * dvt, r2 = rbn * rbn + rbt * rbt;
    ++n_active;
    sum_wrwr += 0.5 * (wk_n * wk_n + wk_t * wk_t + wi_n * wi_n + wi_t * wi_t);
    sum_wrr += 0.5 * (rk_n * wk_n + rk_t * wk_t + ri_n * wi_n + ri_t * wi_t);
    sum_dv2 += dv2;
    max_dv2 = std::max(max_dv2, dv2);
    sum_dv2r2 += dv2 * r2;
    max_dv2r2 = std::max(max_dv2r2, dv2 * r2);
    sum_rdv += rbn * dvn + rbt * dvt;
  }

  /// Adds the sums of another accumulator (a block of contacts accumulated apart).
  void merge(const CriteriaAccumulator& o) {
    sum_wrwr += o.sum_wrwr;
    sum_dv2 += o.sum_dv2;
    max_dv2 = std::max(max_dv2, o.max_dv2);
    sum_dv2r2 += o.sum_dv2r2;
    max_dv2r2 = std::max(max_dv2r2, o.max_dv2r2);
    sum_wrr += o.sum_wrr;
    sum_rdv += o.sum_rdv;
    n_active += o.n_active;
  }

  Criteria finish(double tol) const {
    Criteria c;
    c.n_active = n_active;
    if (n_active == 0) return c;
    const double n = static_cast<double>(n_active);
    const double quad_wr = std::sqrt(sum_wrwr / n), mean_wrr = sum_wrr / n;
    const double tiny = 1e-300;
    c.quad_dv = std::sqrt(sum_dv2 / n) / std::max(quad_wr * tol, tiny);
    c.maxm_dv = std::sqrt(max_dv2) / std::max(quad_wr * tol, tiny);
    c.quad_dvr = std::sqrt(sum_dv2r2 / n) / std::max(mean_wrr * tol, tiny);
    c.maxm_dvr = std::sqrt(max_dv2r2) / std::max(mean_wrr * tol, tiny);
    c.mean_dvor = sum_rdv / std::max(sum_wrr * tol, tiny);
    return c;
  }
};

/// How far a policy is from holding: the largest of its criteria over its limit (the policy
/// holds below 1).
inline double policy_ratio(const Criteria& c, ConvergencePolicy p) {
  if (c.n_active == 0) return 0.0;
  const double mdvor = std::abs(c.mean_dvor);
  switch (p) {
    case ConvergencePolicy::Quad: return std::max({mdvor, c.quad_dv, c.quad_dvr});
    case ConvergencePolicy::Maxm: return std::max({mdvor, c.maxm_dv, c.maxm_dvr});
    case ConvergencePolicy::QM16:
      return std::max({mdvor, c.quad_dv, c.quad_dvr, c.maxm_dv / 16.666, c.maxm_dvr / 16.666});
    case ConvergencePolicy::Strict: return c.maxm_dv;
    case ConvergencePolicy::NonStrict: return c.quad_dv;
    case ConvergencePolicy::Energy: return mdvor;
  }
  return 0.0;
}

inline bool converged(const Criteria& c, ConvergencePolicy p) {
  if (c.n_active == 0) return true;
  const double mdvor = std::abs(c.mean_dvor);
  switch (p) {
    case ConvergencePolicy::Quad: return mdvor < 1.0 && c.quad_dv < 1.0 && c.quad_dvr < 1.0;
    case ConvergencePolicy::Maxm: return mdvor < 1.0 && c.maxm_dv < 1.0 && c.maxm_dvr < 1.0;
    case ConvergencePolicy::QM16:
      return mdvor < 1.0 && c.quad_dv < 1.0 && c.quad_dvr < 1.0 && c.maxm_dv < 16.666 && c.maxm_dvr < 16.666;
    case ConvergencePolicy::Strict: return c.maxm_dv < 1.0;
    case ConvergencePolicy::NonStrict: return c.quad_dv < 1.0;
    case ConvergencePolicy::Energy: return mdvor < 1.0;
  }
  return false;
}

}  // namespace nscd
