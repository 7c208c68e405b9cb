// nscd/solvers/moreau_jean.hpp — the Moreau–Jean θ-method time stepper (paper §2.2, §2.7).
//
// One step from (q_i, u_i) at t_i to (q_f, u_f) at t_f = t_i + h, in the order a driver sees:
//   1. begin_step  t_m = t_i + (1−θ)h, q_m = q_i + (1−θ)h u_i, external forces at t_m,
//                  u_free = u_i + h M⁻¹ F (imposed velocities: their value at t_f)
//   2. detect      PLPLx contacts at q_m (and the PTPT2 spring frames)
//   3. prepare     per contact: frame, W_αα, law shift, warm start from the last step;
//                  per spring link: frame at q_m, implicit VOIGT_ROD coefficients, last impulse
//   4. solve       the chosen ContactSolver (contact_solver.hpp: NLGS in a sequential or a
//                  colored order, or NEWTON_AC) on the step's ContactSystem: impulses P
//                  with u_f = u_free + M⁻¹ H P
//   5. end_step    q_f = q_m + θ h u_f, forces R = P / h back into the registry, t += h
// step() runs all five and returns the report (cost: sweeps, times; result: criteria,
// overlaps, the energy the contacts and the spring dampers dissipated in the step).
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "nscd/core/own_line.hpp"
#include "nscd/interactions/contact_history.hpp"
#include "nscd/interactions/plplx.hpp"
#include "nscd/registry/registry.hpp"
#include "nscd/solvers/contact_solver.hpp"
#include "nscd/solvers/thread_choice.hpp"
#include "nscd/solvers/position_projection.hpp"

namespace nscd {

struct StepperOptions {
  SolverKind solver = SolverKind::NLGS;  ///< which solver solve() runs
  NlgsOptions nlgs;                      ///< used when solver is NLGS
  NewtonOptions newton;                  ///< used when solver is NEWTON_AC
  /// Threads (OpenMP) of the detection's narrow phase and of the stepper's loops over a large
  /// system's contacts, in [1, 256]; the results do not depend on it. (The colored sweep's are
  /// NlgsOptions::threads.)
  int threads = 1;
  /// Threads of the loops around the solve (the free state, the detection, the records, the warm
  /// start, the layout's copy, the guard, the projection, the end of the step), in [0, threads]:
  /// 0 chooses them step by step from what the steps cost on this machine (ThreadChoice,
  /// thread_choice.hpp); a count fixes them. The results do not depend on it.
  int loop_threads = 0;
  /// Threads of the colored sweep's solve, in [0, nlgs.threads]: 0 chooses them step by step
  /// among 1, 2, 4, … and nlgs.threads from what a sweep costs (ThreadChoice), so that a core
  /// another program keeps busy, or more threads than a small system fills, does not slow the
  /// run; a count fixes them (what a measurement of the threads wants). The results do not
  /// depend on it.
  int solve_threads = 0;
  bool warm_start = true;
  /// The overlap projection after the solve (position_projection.hpp, docs/theory.md §8.4).
  ProjectionOptions projection;
  double big_ratio = 8.0;  ///< see PlplxDetector::big_ratio
  // The guard (step_guard.hpp). A non-finite value anywhere in a step always refuses it.
  std::string failure_dump;   ///< refused step after detection: write its problem here (empty: none)
  bool strict_alert = false;  ///< refuse a step in which a polygon travels farther than the alert distance
  /// Independent convergence check: the natural-map residual over ‖q‖ of the step's contact
  /// problem, every N steps (0: never; NEWTON_AC computes it every step anyway). Reads only.
  int residual_check_every = 50;
  double residual_flag = 1e-3;   ///< a checked step "converged" with a residual above this is flagged
  double residual_limit = 0.0;   ///< > 0: refuse a checked step whose residual is above this
};

struct StepReport {
  std::int64_t step = 0;        ///< index of the step just done (1-based)
  double time = 0.0;            ///< t_f
  SolverKind solver = SolverKind::NLGS;
  int sweeps = 0;               ///< NLGS sweeps, or NEWTON_AC Newton iterations
  int mixes = 0;                ///< NLGS: Anderson mixings (NlgsOptions::anderson)
  int mix_returns = 0;          ///< NLGS: times the mixing resumed after the relaxed sweeps stalled
  bool converged = true;
  Criteria criteria;            ///< NLGS's convergence sums at its last check
  double residual = -1.0;       ///< natural-map residual / ‖q‖ (NEWTON_AC, or a checked step; −1: not computed)
  bool residual_checked = false; ///< residual holds the natural-map residual of this step
  bool false_converged = false;  ///< converged by the solver's criterion, residual > residual_flag
  std::size_t alert_skips = 0;   ///< polygons that travelled farther than the alert distance
  double max_travel = 0.0;       ///< largest travel of a polygon in the step (m)
  std::int64_t fastest_body = -1;  ///< its body
  double position_resolution = 0.0;  ///< spacing of doubles at the largest coordinate (m)
  bool coarse_positions = false;   ///< position_resolution > alert / 1000 (far from the origin)
  int line_search_steps = 0;    ///< NEWTON_AC: step halvings
  int presweeps = 0;            ///< NEWTON_AC hybrid: NLGS sweeps before Newton
  int factorizations = 0;       ///< NEWTON_AC: full KLU factorisations
  double factor_seconds = 0.0;  ///< NEWTON_AC: time in KLU factorisations
  std::size_t contacts = 0;     ///< contact points detected
  std::size_t active = 0;       ///< with P_N > 0
  std::size_t warm_started = 0; ///< matched with the previous step
  double mean_overlap = 0.0;    ///< mean of −g_f over points with g_f < 0 (m)
  double max_overlap = 0.0;     ///< max of −g_f (m); g_f = g_m + θ h U_N the end-of-step gap
  double total_overlap = 0.0;   ///< sum of −g_f over points with g_f < 0 (m): the cumulated interpenetration
  /// The overlap projection (ProjectionOptions): the overlaps above are those left after it.
  int projection_sweeps = 0;        ///< 0: nothing was beyond the slop
  std::size_t projected = 0;        ///< contacts whose predicted gap was beyond the slop
  double projection_excess = 0.0;   ///< the largest excess beyond the slop before the projection (m)
  double projection_shift = 0.0;    ///< the largest displacement it gave a body (m)
  /// Energy the contact impulses removed in the step (J per metre of thickness): −Σ_α P_α·U_θ,
  /// U_θ = (1 − θ) U⁻ + θ U⁺ the relative velocity over the step (docs/theory.md §7.1).
  double contact_dissipation = 0.0;
  /// Energy the spring links' dampers removed in the step (J/m): Σ h ν U⁺_N U_θ,N (§7.1).
  double damper_dissipation = 0.0;
  /// Wall seconds of the step and of its phases: detection, prepare (the records, the warm
  /// start, the solver's layout), solve, end_step (the guard, the overlap projection, the
  /// records, the positions).
  double detect_seconds = 0.0, prepare_seconds = 0.0, solve_seconds = 0.0, end_seconds = 0.0, step_seconds = 0.0;
  int loop_threads = 1;   ///< the threads the loops around the solve ran on (StepperOptions::loop_threads)
  int solve_threads = 1;  ///< the threads the solve ran on (StepperOptions::solve_threads)
  SolveParts solve_parts;  ///< nlgs.profile with a colored order: the solve's threads' time by part
  DetectionStats detection;
};

class MoreauJean {
 public:
  explicit MoreauJean(Registry& reg, const StepperOptions& options = {});

  StepReport step();

  void begin_step();
  void detect();
  void prepare();
  void solve();
  void end_step();

  const StepReport& report() const { return report_; }
  const StepperOptions& options() const { return opt_; }
  void set_options(const StepperOptions& o);
  PlplxDetector& detector() { return det_; }

  /// The current step's contact problem (after prepare): W = H* M⁻¹ H assembled over the
  /// contacts, q = free relative velocities plus law shifts, mu. The contact order is the
  /// solver's: rows of Registry::contacts that carry a law, in row order, or with the colored
  /// order in its layout from prepare() on (system().rows maps each to its row). Spring links are not unknowns of
  /// this problem: their current impulses are folded into q (after solve(), the dumped
  /// problem's solution is the scene's contact impulses given the springs' final impulses).
  FrictionProblem2D local_problem() const;
  /// The impulses of the solver's contacts (2 per contact), in the same order.
  std::vector<double> impulses() const;
  /// The step's system (after prepare): the seam every solver works on.
  const ContactSystem& system() const { return sys_; }

  /// The warm-start memory (the contact history): last step's forces by polygon pair and
  /// touching features, sorted by (pair, feature). Saved in checkpoints so that a resumed run
  /// continues bit for bit. (The stepper keeps it in its own order with a hash index: this
  /// returns a sorted copy.)
  using WarmStartEntry = ContactMemory;
  ContactHistory warm_start_memory() const;
  /// Replaces the memory.
  void set_warm_start_memory(ContactHistory m);

 private:
  enum class Phase { Idle, Begun, Detected, Prepared, Solved };
  void require(Phase p, const char* call) const;
  /// The guard's exit: back to Idle, an Error naming the step and `what`; with `dump`, the
  /// step's problem is written to options().failure_dump first.
  [[noreturn]] void refuse(const std::string& what, bool dump);
  // prepare's steps: 1. the spring links (condensed or iterated), 2. the contact records,
  // 4. the contacts' warm start (3., the links' warm start, is in prepare itself)
  void prepare_links();
  void build_contacts();
  void warm_start_contacts();
  template <class Key, class Take>
  void warm_start_on_threads(int threads, const Key& key, const Take& take);
  /// A contact's own figures at the end of a step: the work of its impulse, its end gap g_f,
  /// what the warm start keeps of it, whether it pushes (P_N > 0) and whether it is kept (P ≠ 0).
  struct ContactEnd {
    double work = 0.0, gap = 0.0;
    ContactMemory memory;
    bool active = false, remembered = false;
  };
  /// The sums end_step makes over the contacts: overlaps (sum, count, largest), the impulses'
  /// work, the pushing and the remembered contacts.
  struct ContactSums {
    double overlap = 0.0, work = 0.0, max_overlap = 0.0;
    std::size_t overlaps = 0, active = 0, remembered = 0;
    void add(const ContactEnd& e) {
      active += e.active;
      if (e.gap < 0.0) {
        overlap += -e.gap;
        ++overlaps;
        max_overlap = std::max(max_overlap, -e.gap);
      }
      if (e.remembered) {
        work += e.work;
        ++remembered;
      }
    }
    void merge(const ContactSums& b) {
      overlap += b.overlap;
      work += b.work;
      max_overlap = std::max(max_overlap, b.max_overlap);
      overlaps += b.overlaps;
      active += b.active;
      remembered += b.remembered;
    }
  };
  /// end_step sums its contacts by blocks of this many, then the blocks in order, so that the
  /// sums do not depend on the threads.
  static constexpr std::size_t kEndBlock = 1024;
  // end_step's steps: the guard (refuses the step), the overlap projection on the solved system
  // (its report fields filled), the contacts' and the links' forces into the registry, q_f
  void reset_thread_choices(const StepperOptions& o);
  int next_loop_threads();
  void guard_solution();
  void project_overlaps();
  ContactEnd end_of_contact(std::size_t a);
  ContactSums finish_contacts();
  double finish_links();
  void advance_bodies();

  Registry& reg_;
  StepperOptions opt_;
  PlplxDetector det_;
  ThreadChoice loop_choice_;   ///< StepperOptions::loop_threads 0: the loops' threads, step by step
  ThreadChoice solve_choice_;  ///< StepperOptions::solve_threads 0: the solve's threads, step by step
  int loops_ = 1;                 ///< the threads of this step's loops around the solve
  double begin_seconds_ = 0.0;    ///< this step's begin_step, for loop_choice_
  Phase phase_ = Phase::Idle;
  StepReport report_;
  double t_m_ = 0.0;
  std::vector<double> qm_x_, qm_y_, qm_a_;
  std::vector<SolverBody> free_;       ///< u_free before the links are condensed
  ContactSystem sys_;                  ///< the step's system (solver bodies, contacts, links)
  std::unique_ptr<ContactSolver> solver_;  ///< the one opt_ names (contact_solver_name)
  PositionProjection projection_;
  std::vector<double> gaps_;            ///< end_step: each solver contact's gap at q_m, for the projection
  ContactHistory previous_;             ///< in the layout's order of the step that wrote it
  ContactHistoryIndex previous_index_;  ///< over previous_, rebuilt whenever it changes
  std::vector<OwnLine<std::vector<std::uint32_t>>> warm_ends_;  ///< prepare on threads: the found ends, by thread and owner
  std::vector<ContactEnd> end_own_;     ///< end_step on threads: each contact's, before the memory
  std::vector<ContactSums> end_blocks_;  ///< end_step: each block's sums
  std::vector<std::size_t> end_first_;   ///< end_step on threads: each thread's first row of the memory
};

}  // namespace nscd
