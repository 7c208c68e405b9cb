// nscd/solvers/contact_solver.hpp — the contact solver a time stepper holds: one interface over
// the step's ContactSystem, each implementation owning its buffers, chosen by name (as Siconos
// chooses a solver by its id).
//
// A step calls, in order:
//   prepare(sys)  the system is built (warm-start impulses in it): the solver may lay it out in
//                 its own order (the colored sweep's blocks), so that the step's problem reads
//                 the same before and after the solve;
//   solve(sys, t) impulses P with u_f = u_free + M⁻¹ H P, in place in sys, on at most t threads;
//   report()      what the solve did (iterations, convergence, the residual where it has one).
// Implementations (contact_solver.cpp): "NLGS" (a sequential sweep order, nlgs_sweep.hpp),
// "NLGS_COLORED" (colour by colour, on threads and SIMD lanes, with Anderson mixing:
// nlgs_colored.hpp) and "NEWTON_AC" (newton_ac.hpp, with the hybrid's NLGS sweeps first).
#pragma once

#include <memory>
#include <string_view>

#include "nscd/solvers/contact_system.hpp"
#include "nscd/solvers/convergence.hpp"
#include "nscd/solvers/newton_ac.hpp"
#include "nscd/solvers/nlgs.hpp"
#include "nscd/solvers/solver_kind.hpp"

namespace nscd {

/// What one solve did.
struct SolveReport {
  int sweeps = 0;               ///< NLGS sweeps, or NEWTON_AC Newton iterations
  int mixes = 0;                ///< NLGS: Anderson mixings
  int mix_returns = 0;          ///< NLGS: times the mixing resumed after the relaxed sweeps stalled
  bool converged = true;
  Criteria criteria;            ///< NLGS: the convergence sums at its last check
  double residual = -1.0;       ///< NEWTON_AC: natural-map residual / ‖q‖ (−1: not computed)
  int line_search_steps = 0;    ///< NEWTON_AC: step halvings
  int presweeps = 0;            ///< NEWTON_AC hybrid: NLGS sweeps before Newton
  int factorizations = 0;       ///< NEWTON_AC: full KLU factorisations
  double factor_seconds = 0.0;  ///< NEWTON_AC: time in KLU factorisations
  SolveParts parts;  ///< NLGS, a colored order, NlgsOptions::profile: the threads' time by part
};

/// The options every solver picks its own from.
struct ContactSolverOptions {
  NlgsOptions nlgs;
  NewtonOptions newton;
};

class ContactSolver {
 public:
  virtual ~ContactSolver() = default;
  /// The name the factory knows it by.
  virtual std::string_view name() const = 0;
  /// New options for the same solver (its buffers are kept).
  virtual void configure(const ContactSolverOptions& o) = 0;
  /// After the step's system is built and warm-started, before solve(); its loops on at most
  /// `loop_threads` threads (the stepper's choice for the loops around the solve).
  virtual void prepare(ContactSystem&, int /*loop_threads*/) {}
  /// On `threads` threads at most where the solver runs on threads (the colored sweep, up to its
  /// options' threads: the stepper's choice); the numbers do not depend on it.
  virtual void solve(ContactSystem& sys, int threads) = 0;
  /// The colours prepare laid `sys` out in; none (null) for a solver that keeps the contacts' order.
  virtual ContactColors colors(const ContactSystem&) const { return {}; }
  /// True when every solve computes the natural-map residual itself (report().residual).
  virtual bool reports_residual() const { return false; }
  const SolveReport& report() const { return report_; }

 protected:
  SolveReport report_;
};

/// The factory's name for a stepper's choice: "NEWTON_AC", "NLGS_COLORED" (a colored sweep
/// order) or "NLGS".
std::string_view contact_solver_name(SolverKind kind, const NlgsOptions& nlgs);
/// The solver of that name with these options; throws nscd::Error on an unknown name.
std::unique_ptr<ContactSolver> make_contact_solver(std::string_view name, const ContactSolverOptions& o);

}  // namespace nscd
