// nscd/solvers/newton_ac.hpp — NEWTON_AC: the global semismooth Newton solver on the 2D
// Alart–Curnier function, all contacts (and the iterated spring links) at once.
//
// Unknowns r (2 per contact: r_N, r_T; the problem's own order), u = W r + q. Per contact,
// with ρ = ρ_factor / W_NN (the contact's own scale), a = r_N − ρ u_N, τ = r_T − ρ u_T:
//     Φ_N = r_N − max(0, a)
//     Φ_T = r_T − proj_[−μ max(0,a), μ max(0,a)] (τ)
// Φ(r) = 0 is exactly Signorini–Coulomb (Alart & Curnier 1991). A bilateral row (a spring
// link of the stepper, see NewtonProblem::links) has the affine law P = h a − h b U:
//     Φ_N = r_N − h a + h b u_N,   Φ_T = r_T (its tangential slot is unused).
// Each iteration solves (J + η I) d = −Φ with J an element of Clarke's generalized Jacobian
// of Φ, J = D_r + D_u W (same sparsity as W), by a sparse LU on the rows of the closed contacts
// and links (an open contact's rows are the identity's: its part of d is −Φ, known without the
// LU; SuiteSparse KLU: the pattern is analysed again only when a contact outside it closes,
// otherwise only the numbers change), then an Armijo line search on ½‖Φ‖².
// η is the proximal regularisation: it keeps J + ηI invertible when W is rank-deficient
// (hyperstatic piles, face–face stacks) and shrinks with the residual, η = min(η_max, c‖Φ‖),
// so convergence stays fast near a solution (a Levenberg–Marquardt-type rule; see
// docs/theory.md). The stop test is the natural-map residual over ‖q‖ (natural_map_error),
// the measure shared with NLGS.
//
// Only newton_ac.cpp includes SuiteSparse. A build without it (NSCD_WITH_SUITESPARSE=OFF)
// keeps this interface; calling the solver then throws nscd::Error saying so.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "nscd/solvers/local_problem.hpp"
#include "nscd/solvers/nlgs.hpp"

namespace nscd {

/// True when this build has SuiteSparse (NEWTON_AC can run).
bool newton_ac_available();

/// The sparse LU behind NEWTON_AC (both SuiteSparse): KLU (default: left-looking, pivots reused
/// between iterations) or UMFPACK (multifrontal, refactorised each iteration), kept to measure
/// the choice (docs/solvers.md).
enum class LinearSolver { KLU, UMFPACK };

struct NewtonOptions {
  double tol = 1e-8;            ///< stop when natural-map residual / ‖q‖ <= tol
  int max_iterations = 500;
  int max_inner = 10;           ///< Newton iterations per proximal subproblem
  /// A subproblem whose residual has not halved after this many iterations is given up (more
  /// proximal weight, as after max_inner) instead of running to max_inner (0: never).
  int stall_inner = 3;
  double rho_factor = 1.0;      ///< ρ_α = rho_factor / W_NN,α
  double prox_initial = 1e-6;   ///< η of the first proximal subproblem (relative to W_NN,α)
  double prox_min = 1e-12;      ///< η never below this
  double prox_max = 1e2;        ///< η never above this
  double prox_shrink = 0.1;     ///< η ← η × this after a subproblem solved in <= max_inner/2 iterations
  int prox_hold = 20;           ///< after a failed subproblem, η is not shrunk for this many outer iterations
  double inner_ratio = 0.1;     ///< a subproblem is solved to this × the residual at its centre
  double reg_min = 1e-14;       ///< ε added to J's diagonal (a guard against exact singularity)
  int max_line_search = 30;     ///< halvings of the step
  double armijo = 1e-4;         ///< σ of the Armijo test ½‖Φ(r+td)‖² <= (1 − 2σt) ½‖Φ(r)‖²
  bool trace = false;           ///< one line per outer iteration on stderr
  /// The hybrid: at most this many NLGS sweeps first (0: pure Newton), stopping early when
  /// NLGS's Quad criterion reaches presweep_tol; Newton then polishes. Gauss–Seidel settles
  /// the many status changes of an impact cheaply, where Newton's line search crawls.
  int presweeps = 0;
  double presweep_tol = 1e-3;
  LinearSolver linear_solver = LinearSolver::KLU;
  /// KLU: an iteration whose matrix equals the last one factored (no contact changed piece, η
  /// unchanged) solves with those factors instead of factorising again; the result is the same
  /// bit for bit (false: factorise every iteration, to check that).
  bool reuse_factorization = true;
  /// Open contacts' rows of J are the identity's: their part of the Newton direction is taken
  /// without the LU, which factorises only the other contacts' rows (false: all rows, to
  /// check; the direction is the same up to rounding).
  bool eliminate_open = true;
};

/// The NLGS setting of the hybrid's sweeps: Quad at presweep_tol, at most presweeps sweeps.
inline NlgsOptions presweep_options(const NewtonOptions& o) {
  NlgsOptions no;
  no.policy = ConvergencePolicy::Quad;
  no.tol = o.presweep_tol;
  no.max_sweeps = o.presweeps;
  no.check_every = o.presweeps < 10 ? o.presweeps : 10;
  return no;
}

/// Throws nscd::Error on a non-positive tolerance, max_iterations < 1, or bad regularisation.
void validate(const NewtonOptions& o);

struct NewtonResult {
  int presweeps = 0;            ///< NLGS sweeps done first (the hybrid)
  int iterations = 0;           ///< Newton iterations (linear solves), all subproblems together
  int outer_iterations = 0;     ///< proximal subproblems
  double final_prox = 0.0;      ///< η of the last subproblem
  int line_search_steps = 0;    ///< step halvings, all iterations together
  int refactorizations = 0;     ///< full (pivoting) factorisations; the others reuse the pivots
  int reused_factorizations = 0;  ///< iterations whose matrix equalled the last one factored (KLU): no factorisation
  int analyses = 0;             ///< pattern analyses of the factorised rows (one, plus one per growth)
  long long factored_rows = 0;  ///< rows given to the LU, summed over the iterations (÷ iterations: the mean)
  double residual = 0.0;        ///< natural-map residual / ‖q‖ at the returned r
  bool converged = false;
  double assemble_seconds = 0.0, factor_seconds = 0.0, solve_seconds = 0.0;
  std::string failure;          ///< why it stopped without converging (empty if converged)
};

/// Bilateral rows of a problem: the spring links a stepper solves with the contacts. Row
/// `index[k]` of the problem (a pseudo-contact with μ = 0) follows P = ha[k] − hb[k] U_N.
struct BilateralRows {
  std::vector<std::uint32_t> index;
  std::vector<double> ha, hb;
  bool empty() const { return index.empty(); }
};

/// Solves p from the impulses in r (size 2·nc; zeros for a cold start), after
/// options.presweeps NLGS sweeps when there are no bilateral rows; r receives the answer
/// (the best iterate seen if it did not converge). Never returns NaN: a non-finite iterate
/// stops the solve with `failure` set and r at the last finite iterate.
NewtonResult newton_ac_solve(const FrictionProblem2D& p, std::vector<double>& r, const NewtonOptions& options,
                             const BilateralRows& bilateral = {});

/// The combined residual the Newton solver stops on: the natural-map residual of the contact
/// rows and |Φ_N| of the bilateral rows, over ‖q‖.
double newton_residual(const FrictionProblem2D& p, const std::vector<double>& r, const BilateralRows& bilateral = {});

}  // namespace nscd
