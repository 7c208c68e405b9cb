// nscd/solvers/newton_ac.cpp — see newton_ac.hpp. The only file that includes SuiteSparse: the
// sparse LU and the proximal Newton iterations; the Alart–Curnier function they solve is in
// newton_ac_jacobian.cpp.
#include "nscd/solvers/newton_ac.hpp"

#include <klu.h>
#include <umfpack.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "nscd/core/error.hpp"
#include "nscd/solvers/newton_ac_jacobian.hpp"
#include "nscd/solvers/nlgs.hpp"

namespace nscd {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

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
    if (!symbolic_)
      throw Error("NEWTON_AC: KLU could not analyse the Jacobian's pattern (status " + std::to_string(common_.status) +
                  ")");
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

using newton_ac_detail::AlartCurnier;
using newton_ac_detail::Evaluation;
using newton_ac_detail::FactoredRows;

/// One solve: the iterate's workspace, the best iterate seen, the LU and the proximal weight η,
/// shared by the outer (proximal) and the inner (Newton) iterations.
class ProximalNewton {
 public:
  ProximalNewton(const FrictionProblem2D& p, std::vector<double>& r, const NewtonOptions& o,
                 const BilateralRows& bilateral, NewtonResult& res)
      : p_(p),
        o_(o),
        r_(r),
        res_(res),
        n_(2 * p.nc),
        trace_(o.trace || std::getenv("NSCD_NEWTON_TRACE") != nullptr),
        ac_(p, bilateral, o),
        u_(n_),
        wt_(n_),
        wd_(n_),
        trial_(n_),
        d_(n_),
        centre_(r),
        best_(r),
        klu_(o.linear_solver, o.reuse_factorization),
        rows_(p, ap_) {}

  /// Evaluates Φ at the start; false (res.failure set) when it is not finite.
  bool start();
  /// The proximal outer loop, until the residual is below the tolerance or the iterations run out.
  void run();
  /// The best iterate seen into r, and the result's last fields.
  void finish();

 private:
  bool inner_solve(Evaluation& sub, double inner_tol, int& inner);
  bool newton_direction();
  bool line_search_step(Evaluation& sub, double inner_tol);
  bool armijo(const Evaluation& sub, double& t, Evaluation& next);
  void take(Evaluation& sub, const Evaluation& next);
  bool recentre_after_miss(const Evaluation& sub, int inner);
  void recentre_after_solve(const Evaluation& sub, int inner);

  const FrictionProblem2D& p_;
  const NewtonOptions& o_;
  std::vector<double>& r_;
  NewtonResult& res_;
  const std::size_t n_;
  const bool trace_;
  AlartCurnier ac_;
  // u = W r at the current iterate r (multiplied afresh at each subproblem's start, updated
  // along the line search as W r + t W d in between), wt the trial's, wd = W d
  std::vector<double> u_, wt_, wd_, trial_, d_, centre_, best_;
  Evaluation cur_;
  double best_residual_ = 0.0;
  std::vector<int> ap_, ai_;
  std::vector<double> ax_, ax_s_, x_;
  SparseLu klu_;
  FactoredRows rows_;
  double eta_ = 0.0;
  int hold_until_ = 0;  ///< no shrinking of η before this outer iteration (set by a failure)
  double centre_residual_ = 0.0;
};

bool ProximalNewton::start() {
  cur_ = ac_.evaluate(r_, u_);
  if (!cur_.finite) {
    res_.failure = "non-finite residual at the start (check W and q)";
    res_.residual = cur_.residual;
    return false;
  }
  best_residual_ = cur_.residual;
  ac_.pattern(ap_, ai_);
  ax_.assign(ai_.size(), 0.0);
  eta_ = o_.prox_initial;
  centre_residual_ = cur_.residual;
  return true;
}

// Proximal point outer loop: each subproblem (W + ηD) r + q − ηD c is well posed even where
// W is rank-deficient; its solution moves the centre c. When the residual stalls (the
// hyperstatic forces must drift along W's kernel until a contact changes status) η shrinks,
// lengthening the drift per outer step; when an inner solve fails, η grows back.
void ProximalNewton::run() {
  while (cur_.residual > o_.tol && res_.iterations < o_.max_iterations) {
    ++res_.outer_iterations;
    centre_ = r_;
    ac_.set_proximal(centre_, eta_);
    Evaluation sub = ac_.evaluate_with(r_, u_);  // u = W r from cur's evaluation
    const double inner_tol = std::max(0.1 * o_.tol, o_.inner_ratio * centre_residual_);
    int inner = 0;
    const bool inner_ok = inner_solve(sub, inner_tol, inner);
    if (trace_)
      std::fprintf(stderr, "NEWTON_AC outer %d eta %.1e inner %d ok %d residual %.3e (sub %.3e)\n",
                   res_.outer_iterations, eta_, inner, int(inner_ok), sub.residual, sub.sub_residual);
    if (inner_ok) {
      recentre_after_solve(sub, inner);
    } else if (!recentre_after_miss(sub, inner)) {
      break;
    }
  }
}

// The Newton iterations on one subproblem, from sub (its evaluation at r); true when it
// reaches inner_tol or the problem's own tolerance.
bool ProximalNewton::inner_solve(Evaluation& sub, double inner_tol, int& inner) {
  const double start_sub = sub.sub_residual;
  while (res_.iterations < o_.max_iterations) {
    if (sub.sub_residual <= inner_tol || sub.residual <= o_.tol) return true;
    if (inner == o_.max_inner) return false;
    // No headway: a subproblem whose residual has not halved in stall_inner iterations will
    // not reach its tolerance soon (η too small here, the line search crawling): more
    // proximal weight now, not after the rest of max_inner (docs/solvers.md §4.6).
    if (o_.stall_inner > 0 && inner == o_.stall_inner && sub.sub_residual > 0.5 * start_sub) return false;
    ++inner;
    ++res_.iterations;
    if (!newton_direction() || !line_search_step(sub, inner_tol)) return false;
  }
  return false;
}

// Steps 1 and 2 of an iteration, the direction d; false when J_SS cannot be factorised or solved.
bool ProximalNewton::newton_direction() {
  // 1. Generalized Jacobian of the subproblem's Alart–Curnier function at r.
  auto t0 = Clock::now();
  if (rows_.grow(ac_, !o_.eliminate_open)) {  // a contact outside S closed: S's new pattern
    ++res_.analyses;
    if (rows_.size() > 0) klu_.analyze(rows_.size(), rows_.ap(), rows_.ai());
  }
  ac_.jacobian(o_.reg_min, ap_, rows_.members(), ax_);
  rows_.gather(ax_, ax_s_);
  res_.assemble_seconds += seconds_since(t0);
  // 2. Newton direction: J d = −Φ, the open contacts' part directly, the rest by KLU on
  //    J_SS (pivots reused while well conditioned, factors while J_SS is unchanged).
  t0 = Clock::now();
  const bool factored = rows_.size() == 0 || klu_.factor(rows_.ap(), rows_.ai(), ax_s_, res_.refactorizations);
  res_.factor_seconds += seconds_since(t0);
  if (!factored) return false;
  t0 = Clock::now();
  for (std::size_t k = 0; k < n_; ++k) d_[k] = -ac_.phi()[k];
  rows_.rhs(ax_, o_.reg_min, d_, x_);
  const bool solved = rows_.size() == 0 || klu_.solve(x_);
  rows_.scatter(x_, d_);
  res_.solve_seconds += seconds_since(t0);
  res_.factored_rows += rows_.size();
  return solved;
}

// Step 3 of an iteration: the step along d that the line search accepts, taken; false when the
// subproblem is to be given up (no descent, or a step cut so short it makes no headway).
bool ProximalNewton::line_search_step(Evaluation& sub, double inner_tol) {
  p_.multiply(d_, wd_);
  double t = 1.0;
  Evaluation next;
  if (!armijo(sub, t, next)) {
    if (trace_) std::fprintf(stderr, "    inner: no descent (merit %.3e)\n", sub.merit);
    ac_.evaluate_with(r_, u_);  // restore the branches at r
    return false;
  }
  // a step cut below 1e-4 makes no headway: the subproblem needs more proximal weight
  const bool crawling = t < 1e-4 && sub.sub_residual > inner_tol;
  if (!crawling && trace_)
    std::fprintf(stderr, "    inner t %.3g merit %.3e -> %.3e residual %.3e\n", t, sub.merit, next.merit,
                 next.residual);
  take(sub, next);
  return !crawling;
}

// Armijo line search on the subproblem's ½‖Φ‖²: t = 1, ½, ¼, ... (one product W d, done by the
// caller); the trial in trial_ and wt_, its evaluation in next. False when no step passes.
bool ProximalNewton::armijo(const Evaluation& sub, double& t, Evaluation& next) {
  for (int ls = 0; ls <= o_.max_line_search; ++ls) {
    for (std::size_t k = 0; k < n_; ++k) {
      trial_[k] = r_[k] + t * d_[k];
      wt_[k] = u_[k] + t * wd_[k];
    }
    next = ac_.evaluate_with(trial_, wt_);
    // Armijo on ½‖Φ‖²; or, as ½‖Φ‖² is not smooth at the kinks (where a step can be good
    // and still fail Armijo), a decrease of the subproblem's natural-map residual itself.
    if (next.finite && (next.merit <= (1.0 - 2.0 * o_.armijo * t) * sub.merit ||
                        next.sub_residual <= (1.0 - o_.armijo * t) * sub.sub_residual))
      return true;
    ++res_.line_search_steps;
    t *= 0.5;
  }
  return false;
}

// The trial becomes the iterate (the best one kept).
void ProximalNewton::take(Evaluation& sub, const Evaluation& next) {
  r_.swap(trial_);
  u_.swap(wt_);
  sub = next;
  if (sub.residual < best_residual_) {
    best_residual_ = sub.residual;
    best_ = r_;
  }
}

// A subproblem not solved to its tolerance. Fair progress (the residual at least halved): keep
// η and recentre. Otherwise the subproblem is too hard from here (η too small for how singular
// or inconsistent W is locally): ten times more proximal weight. False when the solve stops.
bool ProximalNewton::recentre_after_miss(const Evaluation& sub, int inner) {
  const bool progress = sub.residual <= 0.5 * centre_residual_;
  if (!progress) {
    eta_ = std::min(eta_ * 10.0, o_.prox_max);
    hold_until_ = res_.outer_iterations + o_.prox_hold;  // remember: smaller failed here
  }
  ac_.set_proximal(r_, 0.0);
  cur_ = ac_.evaluate(r_, u_);
  centre_residual_ = cur_.residual;
  if (!progress && inner == 0 && eta_ >= o_.prox_max) {
    res_.failure = "the regularised Jacobian is singular";
    return false;
  }
  return true;
}

// A subproblem solved: shrink η (towards plain Newton, fast on consistent problems; and a longer
// drift along W's kernel where the residual stalls), unless the subproblem was already hard.
void ProximalNewton::recentre_after_solve(const Evaluation& sub, int inner) {
  if (inner <= o_.max_inner / 2 && res_.outer_iterations >= hold_until_)
    eta_ = std::max(eta_ * o_.prox_shrink, o_.prox_min);
  centre_residual_ = sub.residual;
  ac_.set_proximal(r_, 0.0);
  cur_ = ac_.evaluate(r_, u_);
}

void ProximalNewton::finish() {
  if (best_residual_ < cur_.residual) {
    r_ = best_;
    cur_.residual = best_residual_;
  }
  res_.residual = cur_.residual;
  res_.final_prox = eta_;
  res_.reused_factorizations = klu_.reused();
  res_.converged = cur_.residual <= o_.tol;
  if (res_.converged)
    res_.failure.clear();
  else if (res_.failure.empty())
    res_.failure = "iteration cap reached";
}

}  // namespace

bool newton_ac_available() { return true; }

void validate(const NewtonOptions& o) {
  if (!(o.tol > 0.0)) throw Error("NEWTON_AC: tolerance must be > 0, got " + std::to_string(o.tol));
  if (o.max_iterations < 1)
    throw Error("NEWTON_AC: max_iterations must be >= 1, got " + std::to_string(o.max_iterations));
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
  ProximalNewton solve(p, r, o, bilateral, res);
  if (!solve.start()) return res;
  solve.run();
  solve.finish();
  return res;
}

}  // namespace nscd
