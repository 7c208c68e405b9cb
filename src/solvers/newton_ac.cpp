// nscd/solvers/newton_ac.cpp — see newton_ac.hpp. The only file that includes SuiteSparse.
#include "nscd/solvers/newton_ac.hpp"

#include <klu.h>
#include <umfpack.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "nscd/core/error.hpp"
#include "nscd/solvers/nlgs.hpp"

namespace nscd {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Which piece of the Alart–Curnier function a contact is on, as the coefficients of its two
/// Jacobian rows: row N = dr_n e_N + cn (W row N); row T = tn e_N + tt e_T + ctn (W row N) +
/// ctt (W row T).
struct Branch {
  double dr_n = 1.0, cn = 0.0;
  double tn = 0.0, tt = 1.0, ctn = 0.0, ctt = 0.0;
};

/// Owns KLU's symbolic and numeric objects for one solve.
class KluSolver {
 public:
  explicit KluSolver(bool reuse = true) : reuse_(reuse) { klu_defaults(&common_); }
  ~KluSolver() {
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    if (symbolic_) klu_free_symbolic(&symbolic_, &common_);
  }
  KluSolver(const KluSolver&) = delete;
  KluSolver& operator=(const KluSolver&) = delete;

  /// Pattern analysis (once per pattern): KLU is given Jᵀ in compressed columns, i.e. J in
  /// compressed rows.
  /// Analysing a new pattern drops the old one's objects and factors.
  void analyze(int n, std::vector<int>& ap, std::vector<int>& ai) {
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    if (symbolic_) klu_free_symbolic(&symbolic_, &common_);
    factored_.clear();
    n_ = n;
    symbolic_ = klu_analyze(n, ap.data(), ai.data(), &common_);
    if (!symbolic_) throw Error("NEWTON_AC: KLU could not analyse the Jacobian's pattern (status " + std::to_string(common_.status) + ")");
  }
  /// Numeric factorisation; reuses the last pivot order when it is still well conditioned.
  /// Returns false if the matrix is numerically singular.
  bool factor(std::vector<int>& ap, std::vector<int>& ai, std::vector<double>& ax, int& full_factorizations) {
    // The same matrix as the last factorisation (no contact changed piece and η did not change:
    // a step the line search cut short, so the next iteration starts from the same pieces):
    // its factors are still exact, and the solve gives the same direction bit for bit.
    if (reuse_ && numeric_ && ax == factored_) {
      ++reused_;
      return true;
    }
    if (reuse_) factored_ = ax;
    if (numeric_) {
      if (klu_refactor(ap.data(), ai.data(), ax.data(), symbolic_, numeric_, &common_) &&
          klu_rcond(symbolic_, numeric_, &common_) && common_.rcond > 1e-12)
        return true;
      klu_free_numeric(&numeric_, &common_);
    }
    ++full_factorizations;
    numeric_ = klu_factor(ap.data(), ai.data(), ax.data(), symbolic_, &common_);
    if (!numeric_) factored_.clear();
    return numeric_ != nullptr;
  }
  int reused() const { return reused_; }
  /// Solves J x = b in place (b holds x on return).
  bool solve(std::vector<double>& b) {
    return klu_tsolve(symbolic_, numeric_, n_, 1, b.data(), &common_) != 0;
  }

 private:
  klu_common common_{};
  klu_symbolic* symbolic_ = nullptr;
  klu_numeric* numeric_ = nullptr;
  std::vector<double> factored_;  ///< the values of the matrix factored last
  int reused_ = 0;                ///< factorisations skipped: the matrix had not changed
  bool reuse_ = true;
  int n_ = 0;
};

/// The same three calls on UMFPACK (multifrontal, BLAS-based), kept to measure the choice:
/// NewtonOptions::linear_solver = LinearSolver::UMFPACK.
class UmfpackSolver {
 public:
  ~UmfpackSolver() {
    if (numeric_) umfpack_di_free_numeric(&numeric_);
    if (symbolic_) umfpack_di_free_symbolic(&symbolic_);
  }
  UmfpackSolver() = default;
  UmfpackSolver(const UmfpackSolver&) = delete;
  UmfpackSolver& operator=(const UmfpackSolver&) = delete;

  void analyze(int n, std::vector<int>& ap, std::vector<int>& ai) {
    if (numeric_) umfpack_di_free_numeric(&numeric_);
    if (symbolic_) umfpack_di_free_symbolic(&symbolic_);
    numeric_ = nullptr;
    symbolic_ = nullptr;
    std::vector<double> ones(ai.size(), 1.0);
    if (umfpack_di_symbolic(n, n, ap.data(), ai.data(), ones.data(), &symbolic_, nullptr, nullptr) != UMFPACK_OK)
      throw Error("NEWTON_AC: UMFPACK could not analyse the Jacobian's pattern");
  }
  bool factor(std::vector<int>& ap, std::vector<int>& ai, std::vector<double>& ax, int& full_factorizations) {
    if (numeric_) umfpack_di_free_numeric(&numeric_);
    ++full_factorizations;
    ap_ = &ap;
    ai_ = &ai;
    ax_ = &ax;
    return umfpack_di_numeric(ap.data(), ai.data(), ax.data(), symbolic_, &numeric_, nullptr, nullptr) == UMFPACK_OK;
  }
  bool solve(std::vector<double>& b) {
    std::vector<double> x(b.size());
    // the matrix given is Jᵀ (J in compressed rows): solve (Jᵀ)ᵀ x = b
    const int st = umfpack_di_solve(UMFPACK_At, ap_->data(), ai_->data(), ax_->data(), x.data(), b.data(), numeric_,
                                    nullptr, nullptr);
    b.swap(x);
    return st == UMFPACK_OK;
  }

 private:
  void* symbolic_ = nullptr;
  void* numeric_ = nullptr;
  std::vector<int>* ap_ = nullptr;
  std::vector<int>* ai_ = nullptr;
  std::vector<double>* ax_ = nullptr;
};

/// Dispatch between the two (once per solve and per iteration: not in a loop over contacts).
class SparseLu {
 public:
  SparseLu(LinearSolver kind, bool reuse) : kind_(kind), klu_(reuse) {}
  void analyze(int n, std::vector<int>& ap, std::vector<int>& ai) {
    kind_ == LinearSolver::KLU ? klu_.analyze(n, ap, ai) : umf_.analyze(n, ap, ai);
  }
  bool factor(std::vector<int>& ap, std::vector<int>& ai, std::vector<double>& ax, int& full) {
    return kind_ == LinearSolver::KLU ? klu_.factor(ap, ai, ax, full) : umf_.factor(ap, ai, ax, full);
  }
  bool solve(std::vector<double>& b) { return kind_ == LinearSolver::KLU ? klu_.solve(b) : umf_.solve(b); }
  int reused() const { return kind_ == LinearSolver::KLU ? klu_.reused() : 0; }

 private:
  LinearSolver kind_;
  KluSolver klu_;
  UmfpackSolver umf_;
};

struct Evaluation {
  double merit = 0.0;      ///< ½‖Φ‖² of the proximal subproblem
  double sub_residual = 0.0;  ///< natural map / ‖q‖ of the subproblem
  double residual = 0.0;   ///< natural map / ‖q‖ of the problem itself (the stop test)
  bool finite = true;
};

/// The Alart–Curnier function of the proximal subproblem centred at c:
///     u = W r + q + η_α (r − c)    (η_α = η W_NN,α on both rows of contact α)
/// With η = 0 it is the problem itself. Every evaluation also gives the problem's own
/// natural-map residual (u − η(r − c) is the true velocity).
class AlartCurnier {
 public:
  AlartCurnier(const FrictionProblem2D& p, const BilateralRows& bil, const NewtonOptions& o) : p_(p), o_(o) {
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

  const std::vector<double>& phi() const { return phi_; }

  /// True when contact i's two rows of J are the identity's (+ε): an open contact (Φ = r).
  bool identity_rows(std::size_t i) const { return !is_link_[i] && branch_[i].cn == 0.0; }

  /// Sets the proximal subproblem: centre c and relative weight η (0: the problem itself).
  void set_proximal(const std::vector<double>& c, double eta) {
    centre_ = c;
    eta_ = eta;
  }

  /// Φ(r) of the subproblem, its branches, and both residuals. u receives W r.
  Evaluation evaluate(const std::vector<double>& r, std::vector<double>& u) {
    p_.multiply(r, u);
    return evaluate_with(r, u);
  }

  /// The same with u = W r already known (a line-search trial: W r + t W d).
  Evaluation evaluate_with(const std::vector<double>& r, const std::vector<double>& u) {
    Evaluation e;
    double merit2 = 0.0, nat2 = 0.0, sub2 = 0.0;
    for (std::size_t i = 0; i < p_.nc; ++i) {
      const double rn = r[2 * i], rt = r[2 * i + 1];
      const double un0 = u[2 * i] + p_.q[2 * i], ut0 = u[2 * i + 1] + p_.q[2 * i + 1];
      const double eta = eta_ * wnn_[i];
      const double un = un0 + eta * (rn - centre_[2 * i]);
      const double ut = ut0 + (is_link_[i] ? 0.0 : eta * (rt - centre_[2 * i + 1]));
      Branch& b = branch_[i];
      double fn, ft;
      if (is_link_[i]) {
        // P = h a − h b U: Φ_N = r_N − h a + h b u_N, Φ_T = r_T
        fn = rn - ha_[i] + hb_[i] * un;
        ft = rt;
        b = Branch{1.0, hb_[i], 0.0, 1.0, 0.0, 0.0};
        sub2 += fn * fn + ft * ft;
        const double f0 = rn - ha_[i] + hb_[i] * un0;
        nat2 += f0 * f0 + ft * ft;
      } else {
        const double rho = o_.rho_factor / (wnn_[i] * (1.0 + eta_)), mu = p_.mu[i];
        const double a = rn - rho * un;
        const double bound = mu * std::max(0.0, a);
        const double tau = rt - rho * ut;
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
        nat2 += natural_map2(rn, rt, un0, ut0, mu);
        sub2 += eta_ > 0.0 ? natural_map2(rn, rt, un, ut, mu) : 0.0;
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

  /// Fills the values of J + ε I (J of the subproblem) in the layout built by pattern(), on
  /// the rows of the contacts listed (the others' values are left as they were).
  void jacobian(double eps, const std::vector<int>& ap, const std::vector<std::uint32_t>& contacts,
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

  /// The compressed-row pattern of J: W's block pattern, scalar.
  void pattern(std::vector<int>& ap, std::vector<int>& ai) const {
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

  /// ‖r − P_K(r − (u + μ|u_T| e_N))‖² of one contact (natural_map_error's formula).
  static double natural_map2(double rn, double rt, double un, double ut, double mu) {
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

 private:
  const FrictionProblem2D& p_;
  const NewtonOptions& o_;
  std::vector<double> wnn_, ha_, hb_;
  std::vector<std::uint8_t> is_link_;
  std::vector<Branch> branch_;
  std::vector<double> phi_, centre_;
  double eta_ = 0.0, q_norm_ = 1.0, kink_ = 0.0;
};

/// The rows of J that go to the sparse LU. An open contact's two rows of J are the
/// identity's (+ε on the diagonal, nothing else): its share of the direction is known without a
/// solve, d_j = −Φ_j/(1 + ε), and moves to the right-hand side of the other rows. Only the
/// contacts that are closed (or links) are factorised: J_SS d_S = −Φ_S − J_SO d_O. The set S
/// only grows within a solve (a contact that opens keeps its identity rows in it), so the
/// pattern is analysed again only when a contact outside S closes (docs/solvers.md §4.7).
class FactoredRows {
 public:
  FactoredRows(const FrictionProblem2D& p, const std::vector<int>& ap_full) : p_(p), ap_full_(ap_full) {
    local_.assign(p.nc, -1);
  }

  /// Adds every contact that J needs factorised (all of them with `all`) and is not in S yet;
  /// true when S grew (the caller then analyses pattern() again).
  bool grow(const AlartCurnier& ac, bool all) {
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

  int size() const { return static_cast<int>(2 * members_.size()); }
  const std::vector<std::uint32_t>& members() const { return members_; }
  std::vector<int>& ap() { return ap_; }
  std::vector<int>& ai() { return ai_; }

  /// J_SS's values, taken from the full J's (ax_full, in the full pattern's layout).
  void gather(const std::vector<double>& ax_full, std::vector<double>& ax) const {
    ax.resize(pick_.size());
    for (std::size_t k = 0; k < pick_.size(); ++k) ax[k] = ax_full[pick_[k]];
  }

  /// Given d = −Φ (full), puts the open contacts' directions in d and J_SS's right-hand side
  /// in x (size 2|S|); ax_full holds J + εI on S's rows, the others are (1 + ε) I.
  void rhs(const std::vector<double>& ax_full, double eps, std::vector<double>& d, std::vector<double>& x) const {
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

  /// Puts J_SS's solution x back into d.
  void scatter(const std::vector<double>& x, std::vector<double>& d) const {
    for (std::size_t m = 0; m < members_.size(); ++m) {
      d[2 * members_[m]] = x[2 * m];
      d[2 * members_[m] + 1] = x[2 * m + 1];
    }
  }

 private:
  void build_pattern() {
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

  const FrictionProblem2D& p_;
  const std::vector<int>& ap_full_;
  std::vector<int> local_;                ///< contact → its place in S, −1 outside
  std::vector<std::uint32_t> members_;    ///< S, in the problem's order
  std::vector<int> ap_, ai_;              ///< J_SS's pattern (compressed rows)
  std::vector<std::size_t> pick_;         ///< each J_SS entry's place in the full J
};

}  // namespace

bool newton_ac_available() { return true; }

void validate(const NewtonOptions& o) {
  if (!(o.tol > 0.0)) throw Error("NEWTON_AC: tolerance must be > 0, got " + std::to_string(o.tol));
  if (o.max_iterations < 1) throw Error("NEWTON_AC: max_iterations must be >= 1, got " + std::to_string(o.max_iterations));
  if (!(o.rho_factor > 0.0)) throw Error("NEWTON_AC: rho_factor must be > 0");
  if (o.max_inner < 1) throw Error("NEWTON_AC: max_inner must be >= 1");
  if (o.stall_inner < 0) throw Error("NEWTON_AC: stall_inner must be >= 0 (0: never give up before max_inner)");
  if (!(o.reg_min >= 0.0 && o.prox_min > 0.0 && o.prox_initial >= o.prox_min && o.prox_max >= o.prox_initial))
    throw Error("NEWTON_AC: need reg_min >= 0 and 0 < prox_min <= prox_initial <= prox_max");
  if (!(o.prox_shrink > 0.0 && o.prox_shrink <= 1.0 && o.inner_ratio > 0.0 && o.inner_ratio < 1.0))
    throw Error("NEWTON_AC: need prox_shrink in (0, 1] and inner_ratio in (0, 1)");
  if (o.presweeps < 0 || !(o.presweep_tol > 0.0)) throw Error("NEWTON_AC: need presweeps >= 0 and presweep_tol > 0");
  if (o.max_line_search < 0 || !(o.armijo > 0.0 && o.armijo < 0.5))
    throw Error("NEWTON_AC: need max_line_search >= 0 and the Armijo constant in (0, 0.5)");
}

double newton_residual(const FrictionProblem2D& p, const std::vector<double>& r, const BilateralRows& bilateral) {
  NewtonOptions o;
  AlartCurnier ac(p, bilateral, o);
  std::vector<double> u;
  return ac.evaluate(r, u).residual;
}

NewtonResult newton_ac_solve(const FrictionProblem2D& p, std::vector<double>& r, const NewtonOptions& o,
                             const BilateralRows& bilateral) {
  validate(o);
  NewtonResult res;
  const std::size_t n = 2 * p.nc;
  if (r.size() != n) r.assign(n, 0.0);
  for (double v : r)
    if (!std::isfinite(v)) {
      r.assign(n, 0.0);  // a non-finite start is replaced by a cold one
      break;
    }
  if (p.nc == 0) {
    res.converged = true;
    return res;
  }
  if (o.presweeps > 0 && bilateral.empty()) {  // the hybrid: NLGS first
    res.presweeps = nlgs_solve(p, r, presweep_options(o)).sweeps;
  }
  const bool trace = o.trace || std::getenv("NSCD_NEWTON_TRACE") != nullptr;
  AlartCurnier ac(p, bilateral, o);
  // u = W r at the current iterate r (multiplied afresh at each subproblem's start, updated
  // along the line search as W r + t W d in between), wt the trial's, wd = W d
  std::vector<double> u(n), wt(n), wd(n), trial(n), d(n), centre = r, best = r;
  Evaluation cur = ac.evaluate(r, u);
  if (!cur.finite) {
    res.failure = "non-finite residual at the start (check W and q)";
    res.residual = cur.residual;
    return res;
  }
  double best_residual = cur.residual;
  std::vector<int> ap, ai;
  ac.pattern(ap, ai);
  std::vector<double> ax(ai.size()), ax_s, x;
  SparseLu klu(o.linear_solver, o.reuse_factorization);
  FactoredRows rows(p, ap);

  // Proximal point outer loop: each subproblem (W + ηD) r + q − ηD c is well posed even where
  // W is rank-deficient; its solution moves the centre c. When the residual stalls (the
  // hyperstatic forces must drift along W's kernel until a contact changes status) η shrinks,
  // lengthening the drift per outer step; when an inner solve fails, η grows back.
  double eta = o.prox_initial;
  int hold_until = 0;  // no shrinking of η before this outer iteration (set by a failure)
  double centre_residual = cur.residual;
  while (cur.residual > o.tol && res.iterations < o.max_iterations) {
    ++res.outer_iterations;
    centre = r;
    ac.set_proximal(centre, eta);
    Evaluation sub = ac.evaluate_with(r, u);  // u = W r from cur's evaluation
    const double inner_tol = std::max(0.1 * o.tol, o.inner_ratio * centre_residual);
    bool inner_ok = false;
    int inner = 0;
    const double start_sub = sub.sub_residual;
    while (res.iterations < o.max_iterations) {
      if (sub.sub_residual <= inner_tol || sub.residual <= o.tol) {
        inner_ok = true;
        break;
      }
      if (inner == o.max_inner) break;
      // No headway: a subproblem whose residual has not halved in stall_inner iterations will
      // not reach its tolerance soon (η too small here, the line search crawling): more
      // proximal weight now, not after the rest of max_inner (docs/solvers.md §4.6).
      if (o.stall_inner > 0 && inner == o.stall_inner && sub.sub_residual > 0.5 * start_sub) break;
      ++inner;
      ++res.iterations;
      // 1. Generalized Jacobian of the subproblem's Alart–Curnier function at r.
      auto t0 = Clock::now();
      if (rows.grow(ac, !o.eliminate_open)) {  // a contact outside S closed: S's new pattern
        ++res.analyses;
        if (rows.size() > 0) klu.analyze(rows.size(), rows.ap(), rows.ai());
      }
      ac.jacobian(o.reg_min, ap, rows.members(), ax);
      rows.gather(ax, ax_s);
      res.assemble_seconds += seconds_since(t0);
      // 2. Newton direction: J d = −Φ, the open contacts' part directly, the rest by KLU on
      //    J_SS (pivots reused while well conditioned, factors while J_SS is unchanged).
      t0 = Clock::now();
      const bool factored = rows.size() == 0 || klu.factor(rows.ap(), rows.ai(), ax_s, res.refactorizations);
      res.factor_seconds += seconds_since(t0);
      if (!factored) break;
      t0 = Clock::now();
      for (std::size_t k = 0; k < n; ++k) d[k] = -ac.phi()[k];
      rows.rhs(ax, o.reg_min, d, x);
      const bool solved = rows.size() == 0 || klu.solve(x);
      rows.scatter(x, d);
      res.solve_seconds += seconds_since(t0);
      res.factored_rows += rows.size();
      if (!solved) break;
      // 3. Armijo line search on the subproblem's ½‖Φ‖²: t = 1, ½, ¼, ... (one product W d)
      p.multiply(d, wd);
      double t = 1.0;
      Evaluation next;
      bool accepted = false;
      for (int ls = 0; ls <= o.max_line_search; ++ls) {
        for (std::size_t k = 0; k < n; ++k) {
          trial[k] = r[k] + t * d[k];
          wt[k] = u[k] + t * wd[k];
        }
        next = ac.evaluate_with(trial, wt);
        // Armijo on ½‖Φ‖²; or, as ½‖Φ‖² is not smooth at the kinks (where a step can be good
        // and still fail Armijo), a decrease of the subproblem's natural-map residual itself.
        if (next.finite && (next.merit <= (1.0 - 2.0 * o.armijo * t) * sub.merit ||
                            next.sub_residual <= (1.0 - o.armijo * t) * sub.sub_residual)) {
          accepted = true;
          break;
        }
        ++res.line_search_steps;
        t *= 0.5;
      }
      if (accepted && t < 1e-4 && sub.sub_residual > inner_tol) {
        // a step cut below 1e-4 makes no headway: the subproblem needs more proximal weight
        r.swap(trial);
        u.swap(wt);
        sub = next;
        if (sub.residual < best_residual) {
          best_residual = sub.residual;
          best = r;
        }
        break;
      }
      if (!accepted) {
        if (trace) std::fprintf(stderr, "    inner: no descent (merit %.3e)\n", sub.merit);
        ac.evaluate_with(r, u);  // restore the branches at r
        break;
      }
      if (trace) std::fprintf(stderr, "    inner t %.3g merit %.3e -> %.3e residual %.3e\n", t, sub.merit, next.merit, next.residual);
      r.swap(trial);
      u.swap(wt);
      sub = next;
      if (sub.residual < best_residual) {
        best_residual = sub.residual;
        best = r;
      }
    }
    if (trace)
      std::fprintf(stderr, "NEWTON_AC outer %d eta %.1e inner %d ok %d residual %.3e (sub %.3e)\n", res.outer_iterations,
                   eta, inner, int(inner_ok), sub.residual, sub.sub_residual);
    if (!inner_ok) {
      // Not solved to its tolerance. Fair progress (the residual at least halved): keep η and
      // recentre. Otherwise the subproblem is too hard from here (η too small for how singular
      // or inconsistent W is locally): ten times more proximal weight.
      const bool progress = sub.residual <= 0.5 * centre_residual;
      if (!progress) {
        eta = std::min(eta * 10.0, o.prox_max);
        hold_until = res.outer_iterations + o.prox_hold;  // remember: smaller failed here
      }
      ac.set_proximal(r, 0.0);
      cur = ac.evaluate(r, u);
      centre_residual = cur.residual;
      if (!progress && inner == 0 && eta >= o.prox_max) {
        res.failure = "the regularised Jacobian is singular";
        break;
      }
      continue;
    }
    // Solved: shrink η (towards plain Newton, fast on consistent problems; and a longer drift
    // along W's kernel where the residual stalls), unless the subproblem was already hard.
    if (inner <= o.max_inner / 2 && res.outer_iterations >= hold_until) eta = std::max(eta * o.prox_shrink, o.prox_min);
    centre_residual = sub.residual;
    ac.set_proximal(r, 0.0);
    cur = ac.evaluate(r, u);
  }
  if (best_residual < cur.residual) {
    r = best;
    cur.residual = best_residual;
  }
  res.residual = cur.residual;
  res.final_prox = eta;
  res.reused_factorizations = klu.reused();
  res.converged = cur.residual <= o.tol;
  if (res.converged) res.failure.clear();
  else if (res.failure.empty()) res.failure = "iteration cap reached";
  return res;
}

}  // namespace nscd
