// nscd/solvers/nlgs.hpp — nonlinear Gauss–Seidel (NLGS) for the 2D frictional contact problem
// (paper §2.7): contacts are visited one after the other, each solving its single-contact
// Signorini–Coulomb problem exactly with the others' impulses fixed, until a convergence
// policy holds (convergence.hpp).
//
// The sweep is a template over a backend that knows how to read a contact's current
// relative velocity and how to apply an impulse change (nlgs_sweep.hpp): the scene backend
// updates two bodies' velocities (O(1) per contact), the problem backend a row of W.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "nscd/solvers/convergence.hpp"
#include "nscd/solvers/local_problem.hpp"
#include "nscd/solvers/solve_profile.hpp"

namespace nscd {

/// Fixed: detection order; Reversed; Shuffled (from a seed, every sweep); Alternating:
/// forward then backward (symmetric Gauss–Seidel).
/// Colored: contacts are coloured so that no two of a colour share a dynamic body and swept
/// colour by colour; the contacts of a colour are independent, so `threads` may visit them in
/// parallel and the result does not depend on the number of threads (a scene's NLGS only).
/// A small scene is cut into strips across its longer side (Colored) or into cells swept row
/// by row from the bottom (ColoredRows, "colored-rows"), or from the top with each cell's
/// contacts from the bottom up, so that on many threads the rows are swept at once
/// (ColoredCells, "colored-cells"): docs/theory.md §9.5.
enum class SweepOrder { Fixed, Reversed, Shuffled, Alternating, Colored, ColoredRows, ColoredCells };
/// Colored, ColoredRows or ColoredCells.
inline bool is_colored(SweepOrder o) {
  return o == SweepOrder::Colored || o == SweepOrder::ColoredRows || o == SweepOrder::ColoredCells;
}
/// ColoredRows or ColoredCells: a grid of cells.
inline bool is_cells(SweepOrder o) { return o == SweepOrder::ColoredRows || o == SweepOrder::ColoredCells; }
SweepOrder parse_sweep_order(std::string_view name);
std::string_view name_of(SweepOrder o);

struct NlgsOptions {
  ConvergencePolicy policy = ConvergencePolicy::QM16;
  double tol = 1.666e-4;
  int check_every = 10;    ///< sweeps between convergence checks
  int min_sweeps = 0;
  int max_sweeps = 1000;
  double relaxation = 1.0; ///< ω in (0, 2): P <- ω P_local + (1 − ω) P between checks; checked sweeps use ω = 1
  SweepOrder order = SweepOrder::Fixed;
  std::uint64_t seed = 1;  ///< for SweepOrder::Shuffled (reshuffled every sweep)
  /// LMGC90's skip rule: between convergence checks, a contact whose impulse stays zero is
  /// visited after 1, 3, 6, 10, ... sweeps only (checked sweeps visit every contact). Off by
  /// default: it shortens a run but raises the largest overlap, since a contact that becomes
  /// active late is visited late (docs/benchmarks.md §8).
  bool skip_zero = false;
  /// Threads of the colored orders (OpenMP); any other order is sequential and needs 1.
  int threads = 1;
  /// Colored order: contacts visited several at a time in SIMD lanes (nlgs_lanes.hpp), with
  /// the same numbers as the scalar visit: 4 (AVX2; SSE2's 2 where the CPU lacks AVX2), 2
  /// (SSE2) or 0 (scalar). Scalar with skip_zero, and off x86-64.
  int lanes = 4;
  /// A scene's NLGS, any order: Anderson mixing of depth `anderson` (1 … 8; 0: off) every 4 sweeps, the
  /// sweeps it mixes plain (ω = 1); where it stalls, sweeps relaxed by `relaxation`, and where
  /// those stall, the mixing again from a fresh history, in turn (anderson.hpp, docs/theory.md
  /// §9.5b; nlgs_mixing.hpp). Not with skip_zero, nor in nlgs_solve (a problem without bodies).
  int anderson = 0;
  /// Colored orders: each thread's time part by part (NlgsResult::parts, solve_profile.hpp);
  /// a few clock reads a sweep. The numbers do not change.
  bool profile = false;
};

/// Throws nscd::Error on tol <= 0, check_every < 1, max_sweeps < min_sweeps, relaxation outside (0, 2),
/// relaxation ≠ 1 with check_every = 1 (every sweep checked, hence plain: ω would do nothing),
/// lanes other than 0, 2, 4, threads outside [1, 256] or > 1 with a sequential order, anderson
/// outside [0, 8] or > 0 with skip_zero.
void validate(const NlgsOptions& o);

struct NlgsResult {
  int sweeps = 0;
  bool converged = false;
  Criteria criteria;       ///< at the last check
  int mixes = 0;           ///< Anderson mixings applied (NlgsOptions::anderson)
  int mix_returns = 0;     ///< Anderson: times the mixing resumed after the relaxed sweeps stalled
  SolveParts parts;  ///< NlgsOptions::profile with a colored order: where the threads' time went
};

/// Solves a stand-alone problem (e.g. read from a dump or a Siconos file), starting from
/// the impulses in r (size 2·nc; zeros for a cold start). r receives the solution.
NlgsResult nlgs_solve(const FrictionProblem2D& problem, std::vector<double>& r, const NlgsOptions& options);

}  // namespace nscd
