// nscd/solvers/anderson.hpp — Anderson mixing of NLGS sweeps (theory §9.5b; its phases in a
// solve: nlgs_mixing.hpp).
//
// A Gauss–Seidel sweep is a map x ← G(x) on the impulses x (2 per contact, P_N then P_T, then 1
// per spring link). Deep in a pile it contracts slowly: a load needs about one sweep per layer
// of grains to travel. Anderson's method (Anderson 1965; Walker & Ni 2011) looks at the last
// depth + 1 results g_i = G(x_i) and residuals f_i = g_i − x_i and takes, in place of the last
// result g_k, the combination of them whose residuals cancel best in least squares:
//     γ = argmin ‖f_k − ΔF γ‖,   x_{k+1} = g_k − ΔG γ
// with ΔF, ΔG the differences of successive residuals and results. The combination's weights
// add up to 1 and the body velocities are affine in the impulses (u = u_free + M⁻¹ H x), so the
// same γ on the velocities' history gives the velocities of the mixed impulses: nothing is
// propagated again. The mixed impulses are then projected on the Coulomb cones (P_N ≥ 0,
// |P_T| ≤ μ P_N); the contacts the projection moves are listed, for the caller to propagate
// their change to their two bodies.
//
// Plain arrays, no allocation once warm; every sum in index order, so that the result depends
// only on the inputs (not on threads or SIMD lanes).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace nscd {

class AndersonMixer {
 public:
  static constexpr int kMaxDepth = 8;

  /// A new solve: `contacts` (2 unknowns each) then `links` (1 each) impulses, `velocities`
  /// body velocity components, a history of `depth` differences (1 … kMaxDepth). The caller
  /// then fills x() with the impulses the solve starts from and calls begin().
  void start(std::size_t contacts, std::size_t links, std::size_t velocities, int depth);
  /// The impulses at the start of the solve are in x(): remembered as the first iterate.
  void begin();
  /// Buffers the caller fills before mix() (impulses, then velocities) and reads after.
  double* x() { return xv_.data(); }
  double* v() { return xv_.data() + nx_; }
  /// x() and v() hold the results of the sweeps since the last call (or begin()). Records
  /// them; if the history allows, replaces x() and v() by the mixed iterate, projects x() on
  /// the cones of friction coefficients `mu` (one per contact) and returns true (moved() then
  /// lists the contacts the projection changed, with the change still to be propagated). A
  /// residual more than twice the last one clears the history (the contact statuses changed:
  /// the old differences no longer describe the map).
  bool mix(const double* mu);
  /// mix() in parts, for a caller that shares its vector passes among threads (each entry on its
  /// own: the same numbers as mix()): mix_begin (the residual, the history and γ; false: nothing
  /// to mix, as mix()), then mix_range over [0, velocities end) and project_range over the
  /// contacts, in any split, then mix_end (the moves listed, in contact order).
  bool mix_begin(const double* mu);
  void mix_range(std::size_t from, std::size_t to);
  void project_range(std::size_t from, std::size_t to);
  void mix_end();
  /// The entries mix_range covers: impulses then velocities.
  std::size_t mixed_size() const { return nx_ + nv_; }
  std::size_t contacts() const { return nc_; }
  /// Starts the history again, from the impulses the next mix() call finds in x() (that call
  /// only records them, as begin() does): for a solve that comes back to mixing after plain
  /// sweeps.
  void restart_at_next() { restart_at_next_ = true; }
  struct Move {
    std::uint32_t contact;
    double dpn, dpt;
  };
  const std::vector<Move>& moved() const { return moved_; }
  std::size_t mixes() const { return mixes_; }
  std::size_t restarts() const { return restarts_; }

 private:
  std::size_t nc_ = 0, nx_ = 0, nv_ = 0;
  int depth_ = 0, count_ = 0, head_ = 0;
  bool have_last_ = false, restart_at_next_ = false;
  double last_norm_ = 0.0;
  std::vector<double> xv_;       ///< the impulses (nx) then the velocities (nv)
  std::vector<double> gv_last_;  ///< … the last period's results
  std::vector<double> x0_, f_last_;
  std::vector<double> dF_;       ///< depth columns of nx (column i at i × nx)
  std::vector<double> dGV_;      ///< depth columns of nx + nv: ΔG then ΔV
  double gram_[kMaxDepth][kMaxDepth] = {};  ///< ΔFᵀΔF
  double rhs_[kMaxDepth] = {};              ///< ΔFᵀ f of the last period
  double gamma_[kMaxDepth] = {};            ///< this mixing's weights (mix_begin)
  int mix_k_ = 0, mix_h_ = 0;               ///< … their count, the history's new column
  const double* mu_ = nullptr;              ///< … the cones
  std::vector<Move> moved_;
  std::vector<std::uint64_t> moved_flag_;  ///< per contact: moved by the last projection
  std::size_t mixes_ = 0, restarts_ = 0;
};

}  // namespace nscd
