// nscd/solvers/contact_system.hpp — the per-step system every solver works on (the solver
// seam), apart from the mechanics that built it.
//
// MoreauJean::prepare() fills it: solver bodies (free velocities and inverse masses, with the
// condensed spring links folded in as effective masses), contact rows (frame, lever arms, own
// W block, law shift, warm-start impulse), and the iterated spring links. A solver either
// works on it in place (NLGS, through SceneBackend) or takes one of its two exports and hands
// its answer back with set_impulses():
//   local form   {W, q, μ}        W = H* M⁻¹ H in 2×2 blocks (FrictionProblem2D), as Siconos'
//                                 FrictionContactProblem;
//   global form  {M, H, f, b, μ}  M v = f + H r, U = H* v + b (Eigen sparse matrices), as
//                                 Siconos' GlobalFrictionContactProblem.
// Both are built from the one contact-Jacobian part (contact_part.hpp).
#pragma once

#include <Eigen/SparseCore>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "nscd/solvers/contact_part.hpp"
#include "nscd/solvers/local_problem.hpp"
#include "nscd/solvers/newton_ac.hpp"

namespace nscd {

/// From this many contacts on, the colored sweep's blocks of consecutive contacts are swept on
/// the threads asked for (below, a colour's blocks are too few for the barriers), a one-thread
/// sweep of strips or cells takes its colours one after the other, and the colouring's lightest
/// passes (a few nanoseconds a contact) go on the threads. The stepper's loops around the solve
/// go on the threads much sooner: kLoopParallelMin (thread_range.hpp).
inline constexpr std::size_t kParallelMin = 8192;

/// The global form over the free degrees of freedom (kinematic dofs are data, folded into b).
struct GlobalProblem {
  Eigen::SparseMatrix<double> M;        ///< n_dof × n_dof, diagonal (effective masses)
  Eigen::SparseMatrix<double> H;        ///< n_dof × 2nc (+ 2 columns per link: normal, unused tangent)
  Eigen::VectorXd f;                    ///< M v_free
  Eigen::VectorXd b;                    ///< U = H* v + b: kinematic dofs' share and the law shifts
  std::vector<double> mu;               ///< per contact (0 for links)
  std::vector<std::uint32_t> dof_body;  ///< body of each free dof
  std::vector<std::uint8_t> dof_kind;   ///< 0 vx, 1 vy, 2 ω
};

/// A system laid out in colours (a colored solver's prepare): colour c is blocks
/// color_start[c] … color_start[c+1], block b contacts block_start[b] … block_start[b+1]. No two
/// blocks of one colour share a dynamic body, except in the last colour (the overflow), whose
/// blocks go in order on one thread: a Gauss–Seidel pass over the contacts may take a colour's
/// blocks on any threads and gives the numbers of the pass in layout order.
struct ContactColors {
  const std::vector<std::uint32_t>* block_start = nullptr;
  const std::vector<std::uint32_t>* color_start = nullptr;
};

struct ContactSystem {
  std::vector<SolverBody> free;          ///< free state (u_free, effective inverse masses)
  std::vector<SolverBody> bodies;        ///< the velocities being solved for (u_f)
  std::vector<SolverContact> contacts;   ///< hot: what a contact visit reads and writes
  std::vector<std::uint32_t> rows;       ///< cold: each contact's row of Registry::contacts
  std::vector<ContactStatus> status;     ///< cold: each contact's status after the solve
  std::vector<SolverLink> links;         ///< iterated spring links
  std::vector<SolverLink> condensed;     ///< links folded into their pad's dof
  std::vector<double> body_x,
      body_y;  ///< cold: body centres at q_m (the colored order's cells); empty for a dumped problem

  /// {W, q, μ} over the contacts; the iterated links' current impulses are folded into q
  /// (the problem of the contacts given the springs).
  FrictionProblem2D local_problem() const;
  /// {W, q, μ} with each iterated link as a bilateral row after the contacts (μ = 0, its
  /// tangential slot unused); `rows` receives their affine laws.
  FrictionProblem2D local_problem_with_links(BilateralRows& rows) const;
  /// {M, H, f, b, μ}, links included as in local_problem_with_links.
  GlobalProblem global_problem() const;

  /// Current impulses: 2 per contact, then (with_links) 2 per link (normal, 0).
  std::vector<double> impulses(bool with_links) const;
  /// Any solver's answer becomes the step's state: impulses (contacts, then links if
  /// with_links), statuses, and u_f = u_free + M⁻¹ H r.
  void set_impulses(const std::vector<double>& r, bool with_links);
};

}  // namespace nscd
