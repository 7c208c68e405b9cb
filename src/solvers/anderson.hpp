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
// Plain arrays, no allocation once warm; every sum in index order chunk by chunk, the chunks'
// in chunk order, so that the result depends only on the inputs and the chunks (not on threads
// or SIMD lanes).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "nscd/core/own_line.hpp"

namespace nscd {

/// An array on pages of its own whose entries begin `skew` cache lines into its first page. The
/// mixer's arrays and columns are read and written at the same entries in one loop; begun at
/// the same place of a page, a load there waits for the store before it to another array (the
/// core compares addresses within a page: "4K aliasing"; docs/record/benchmarks-history.md
/// §11.28). Skewed apart, they do not meet.
template <class T>
struct SkewedPages {
  PageVector<T> v;
  std::size_t skew = 0;  ///< entries before data()
  void resize(std::size_t n, std::size_t lines) {
    skew = lines * kCacheLine / sizeof(T);
    v.resize(n + skew);
  }
  T* data() { return v.data() + skew; }
  const T* data() const { return v.data() + skew; }
};

class AndersonMixer {
 public:
  static constexpr int kMaxDepth = 8;
  /// A contact the cone projection moved, and its change still to be propagated.
  struct Move {
    std::uint32_t contact;
    double dpn, dpt;
  };

  /// A new solve: `contacts` (2 unknowns each) then `links` (1 each) impulses, `velocities`
  /// body velocity components, a history of `depth` differences (1 … kMaxDepth). The caller
  /// then fills x() with the impulses the solve starts from and calls begin(). Every array
  /// starts on a cache line, x() and v() and each history column alike, a whole number of
  /// pages (and a few lines: SkewedPages) after the start of the one before it: a caller whose
  /// threads each own a region of them may leave unused contacts and velocities between the
  /// regions (zero in x() and v(), in no chunk) so that each starts a page after the last.
  void start(std::size_t contacts, std::size_t links, std::size_t velocities, int depth);
  /// The impulses at the start of the solve are in x(): remembered as the first iterate.
  void begin() {
    begin_history();
    begin_range(0, nx_);
  }
  /// begin() in parts, for threads that each own a region of x(): the history cleared (once,
  /// before the threads start), and entries from … to − 1 remembered (each region by the
  /// thread that mixes it, so that its lines are in that thread's core).
  void begin_history();
  void begin_range(std::size_t from, std::size_t to);
  /// Buffers the caller fills before mix() (impulses, then velocities) and reads after.
  double* x() { return xv_.data(); }
  double* v() { return xv_.data() + sx_; }
  /// x() and v() hold the results of the sweeps since the last call (or begin()). Records
  /// them; if the history allows, replaces x() and v() by the mixed iterate, projects x() on
  /// the cones of friction coefficients `mu` (one per contact) and returns true (moved() then
  /// lists the contacts the projection changed, with the change still to be propagated). A
  /// residual more than twice the last one clears the history (the contact statuses changed:
  /// the old differences no longer describe the map).
  bool mix(const double* mu);
  /// The sums (the residual's norm, the history's dot products) are taken chunk by chunk of the
  /// impulses, each chunk's from its first entry, and the chunks' added in chunk order: a caller
  /// whose threads each own some chunks gets the same numbers on any number of threads. Chunk i
  /// is x() entries bounds[i] … bounds[i+1] (bounds from 0 to the impulses' end, increasing);
  /// start() sets one chunk. Call after start().
  void set_chunks(const std::vector<std::size_t>& bounds);
  /// Chunks anywhere in x(), entries between them in none: chunk i is entries begins[i] …
  /// ends[i] − 1 (begins[i] ≤ ends[i] ≤ impulses(), no two overlapping; the sums are still added
  /// in chunk order). The entries in no chunk must stay zero.
  void set_chunks(const std::vector<std::size_t>& begins, const std::vector<std::size_t>& ends);
  std::size_t chunks() const { return ends_.size(); }
  /// What a mixing does, decided by decide() from the chunks' sums.
  enum class Verdict { Restart, Unmixed, Mixed };
  /// mix() in phases, for a caller whose threads each own some chunks, contacts and velocities
  /// (each entry on its own, and the sums by chunk: the same numbers as mix()):
  ///   sums(i0, i1) for chunks i0 … i1−1, in any split among threads, unless restarting();
  ///   decide() on one thread, after every sums();
  ///   apply_x over the impulses and apply_v over the velocities, in any split (apply_x over
  ///   whole contacts, its moves appended to `moves` in contact order, each move's contact its
  ///   slot less `shift`); with Verdict::Mixed the caller then propagates every move, in
  ///   contact order.
  bool restarting() const { return restart_at_next_; }
  void sums(std::size_t i0, std::size_t i1);
  Verdict decide(const double* mu);
  void apply_x(std::size_t from, std::size_t to, std::vector<Move>& moves, std::ptrdiff_t shift = 0);
  void apply_v(std::size_t from, std::size_t to);
  /// The entries of x(): 2 a contact, then the links'; of v().
  std::size_t impulses() const { return nx_; }
  std::size_t velocities() const { return nv_; }
  std::size_t contacts() const { return nc_; }
  /// Starts the history again, from the impulses the next mix() call finds in x() (that call
  /// only records them, as begin() does): for a solve that comes back to mixing after plain
  /// sweeps.
  void restart_at_next() { restart_at_next_ = true; }
  const std::vector<Move>& moved() const { return moved_; }
  std::size_t mixes() const { return mixes_; }
  std::size_t restarts() const { return restarts_; }

 private:
  // Set by start() and set_chunks(): read by every thread during a solve, written by none.
  std::size_t nc_ = 0, nx_ = 0, nv_ = 0;
  /// nx_, nv_ rounded up to whole pages, and kColumnSkew lines more: the columns' strides
  std::size_t sx_ = 0, sv_ = 0;
  int depth_ = 0;
  SkewedPages<double> xv_;       ///< the impulses (sx) then the velocities (sv)
  SkewedPages<double> gv_last_;  ///< … the last period's results
  SkewedPages<double> x0_, f_last_;
  SkewedPages<double> dF_;       ///< depth columns of sx (column i at i × sx)
  SkewedPages<double> dGV_;      ///< depth columns of sx + sv: ΔG then ΔV
  std::vector<std::size_t> bounds_, ends_;  ///< each chunk's first entry in x(), and its end
  std::vector<std::pair<std::size_t, std::size_t>> spans_;  ///< (set_chunks' check)
  SkewedPages<std::uint64_t> moved_flag_;   ///< per contact: moved by the last projection
  /// each chunk's sums (kSums of kSumStride a chunk, on lines of its own): ‖f‖², then ΔFᵀ·
  LineVector<double> partial_;
  static constexpr std::size_t kSums = kMaxDepth + 2, kSumStride = 16;
  std::vector<Move> moved_;
  // The history's state, decide()'s on one thread.
  alignas(kCacheLine) int count_ = 0, head_ = 0;
  bool have_last_ = false, restart_at_next_ = false;
  double last_norm_ = 0.0;
  double gram_[kMaxDepth][kMaxDepth] = {};  ///< ΔFᵀΔF
  double rhs_[kMaxDepth] = {};              ///< ΔFᵀ f of the last period
  std::size_t mixes_ = 0, restarts_ = 0;
  // What decide() chose, which every thread reads in apply_x and apply_v: its own lines,
  // written once a mixing.
  alignas(kCacheLine) double gamma_[kMaxDepth] = {};  ///< this mixing's weights
  int mix_k_ = 0, mix_h_ = 0;                         ///< … their count, the history's new column
  Verdict verdict_ = Verdict::Unmixed;                ///< … what apply_x and apply_v do
  const double* mu_ = nullptr;                        ///< … the cones
};

}  // namespace nscd
