// nscd/solvers/position_projection.hpp — the overlap projection after a step's velocity solve
// (docs/theory.md §8.4): a post-stabilisation in positions only, in the spirit of Cline & Pai
// (2003) and of Siconos' MoreauJeanDirectProjectionOSI (Acary 2013), linearised in the step's
// frozen frames.
//
// IQS_CLB keeps an overlap from growing but never removes one, so every loosely converged step
// leaves a little behind for good. After the solve, each contact's gap is predicted to first
// order at the next detection, g'_α = g_α + h U_N,α (the law's own horizon, §8.2), and at the
// end of the step, e_α = g_α + θ h U_N,α. Where g'_α is below −s (the slop) or e_α below −k s
// (k = end_slops: a separating contact's overlap at q_f is gone at the next detection, so only a
// large one is worth a correction), a position correction Δq = M⁻¹ H Π is found, with
// pseudo-impulses Π = (Π_N ≥ 0, Π_T), such that, with d = H*_N Δq,
//
//     c_α = min(g'_α − G_α, e_α + k s) + d_α ≥ 0,   Π_N,α ≥ 0,   c_α Π_N,α = 0   for every α,
//     G_α = −s                             if g'_α ≥ −s (the correction may not push it past −s),
//     G_α = g'_α + β (−s − g'_α)           otherwise (a share β of the excess removed),
//
// with Coulomb's law on Π_T and the tangential displacements, so that sticking contacts do not
// slip under the correction: the step's contact problem in displacements, solved by Gauss–Seidel
// with the exact local solve. Δq is added to q_f; velocities are untouched, so the correction
// changes no kinetic energy and puts no speed into the packing. Contacts within the slop are
// never touched, so a resting packing whose overlaps stay below s does not move.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "nscd/core/own_line.hpp"
#include "nscd/solvers/contact_system.hpp"

namespace nscd {

struct ProjectionOptions {
  bool enabled = true;
  /// The overlap left alone, as a fraction of the alert distance (Registry params.alert):
  /// s = slop × alert; 1e-4 × the ballast's 1.25 mm is 125 nm.
  double slop = 1e-4;
  /// The end of step's overlap left alone, in slops: a separating contact is clear at the next
  /// detection, so its overlap at q_f is corrected only beyond this larger bound (theory §8.4).
  double end_slops = 10.0;
  double share = 1.0;    ///< β ∈ (0, 1]: the share of the excess beyond s removed in one step
  int max_sweeps = 1000; ///< Gauss–Seidel sweeps, at most (a column of N grains needs about N)
  double tol = 0.5;      ///< stop when every c_α ≥ −tol × s
};

/// Throws nscd::Error naming the first field out of range.
void validate(const ProjectionOptions& o);

struct ProjectionReport {
  int sweeps = 0;              ///< 0: no contact was beyond the slop
  std::size_t beyond = 0;      ///< contacts whose predicted gap was below −s
  double max_excess = 0.0;     ///< largest −s − g'_α before the correction (m)
  double max_residual = 0.0;   ///< largest −c_α after the last sweep (m; ≤ tol × s when converged)
  double max_shift = 0.0;      ///< largest |Δx|, |Δy| of a body (m)
};

/// Contacts from which the projection's sweeps run on the threads. Its sweeps skip most contacts
/// (a few nanoseconds each); below this, two threads' barriers cost more than they share
/// (docs/record/benchmarks-history.md §11.9: 1,750 contacts lost in the VM's slow state, a 7,000-grain
/// deposit's gained; §11.34: the paper sample's 2,300 lost in both states).
inline constexpr std::size_t kProjectionParallelMin = 4096;

/// The projection's state: per-body displacements and per-contact figures, reused step to step.
class PositionProjection {
 public:
  /// Solves the problem above on the step's system (after the velocity solve): `gaps[a]` is
  /// contact a's gap at q_m, `h` the step, `theta` the θ-method's θ, `s` the slop in metres.
  /// Afterwards shift(i) holds body i's Δq and normal_shift(a) contact a's (H*_N Δq)_a. The
  /// slacks and the displacements' start are computed on `threads` threads from
  /// kLightParallelMin contacts on; the sweeps from kProjectionParallelMin on where the system is
  /// laid out in `colors`, colour by colour in one parallel region, else on one thread: the same
  /// numbers for any threads.
  ProjectionReport project(const ContactSystem& sys, const std::vector<double>& gaps, double h, double theta, double s,
                           const ProjectionOptions& o, int threads = 1, ContactColors colors = {});

  bool moved() const { return moved_; }
  void reset() { moved_ = false; }
  /// Body i's correction (dx, dy, dθ in the vx, vy, w fields); zero when !moved().
  const SolverBody& shift(std::size_t i) const { return dq_[i]; }
  /// (H*_N Δq)_a for contact a; zero when !moved().
  double normal_shift(const ContactSystem& sys, std::size_t a) const;

 private:
  std::vector<SolverBody> dq_;     ///< displacement and the effective inverse masses
  std::vector<double> slack_;      ///< g'_α − G_α
  std::vector<double> pi_;         ///< pseudo-impulses Π
  std::vector<unsigned char> touched_;  ///< bodies the correction has moved
  struct Ends {
    std::uint32_t cd, an;
  };
  std::vector<Ends> ends_;              ///< each contact's two bodies (the sweeps' skip test)
  std::vector<ProjectionReport> part_;  ///< on threads: each thread's counts
  bool moved_ = false;
  struct SlackParams {
    double h, theta, s, share, end_bound;
  };
  void slacks(const ContactSystem& sys, const std::vector<double>& gaps, const SlackParams& q, std::size_t a0,
              std::size_t a1, ProjectionReport& r);
  double gauss_seidel_sweep(const ContactSystem& sys, std::size_t a0, std::size_t a1, std::uint32_t& visits);
  void colored_sweeps(const ContactSystem& sys, const ContactColors& colors, int threads, int max_sweeps,
                      double stop, ProjectionReport& r);
  std::vector<OwnLine<double>> worst_;  ///< on threads: each thread's largest −c_α of a sweep
  /// On threads: each block's work in the sweep before, by which the next shares out a colour's
  /// blocks; two, read and written in turn (even and odd sweeps), so that no thread writes what
  /// another may still read.
  std::vector<std::uint32_t> block_work_[2];
  double largest_shift(int threads) const;
};

}  // namespace nscd
