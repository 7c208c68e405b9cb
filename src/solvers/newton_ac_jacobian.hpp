// nscd/solvers/newton_ac_jacobian.hpp — NEWTON_AC's Alart–Curnier function and its generalized
// Jacobian (see newton_ac.hpp), and the rows of that Jacobian the sparse LU factorises. Private
// to newton_ac.cpp (which alone includes SuiteSparse); not part of the library's interface.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "nscd/solvers/newton_ac.hpp"

namespace nscd::newton_ac_detail {

/// Which piece of the Alart–Curnier function a contact is on, as the coefficients of its two
/// Jacobian rows: row N = dr_n e_N + cn (W row N); row T = tn e_N + tt e_T + ctn (W row N) +
/// ctt (W row T).
struct Branch {
  double dr_n = 1.0, cn = 0.0;
  double tn = 0.0, tt = 1.0, ctn = 0.0, ctt = 0.0;
};

struct Evaluation {
  double merit = 0.0;  ///< ½‖Φ‖² of the proximal subproblem
  double sub_residual = 0.0;  ///< natural map / ‖q‖ of the subproblem
  double residual = 0.0;  ///< natural map / ‖q‖ of the problem itself (the stop test)
  bool finite = true;
};

/// The Alart–Curnier function of the proximal subproblem centred at c:
///     u = W r + q + η_α (r − c)    (η_α = η W_NN,α on both rows of contact α)
/// With η = 0 it is the problem itself. Every evaluation also gives the problem's own
/// natural-map residual (u − η(r − c) is the true velocity).
class AlartCurnier {
 public:
  AlartCurnier(const FrictionProblem2D& p, const BilateralRows& bil, const NewtonOptions& o);

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
  Evaluation evaluate_with(const std::vector<double>& r, const std::vector<double>& u);

  /// Fills the values of J + ε I (J of the subproblem) in the layout built by pattern(), on
  /// the rows of the contacts listed (the others' values are left as they were).
  void jacobian(double eps, const std::vector<int>& ap, const std::vector<std::uint32_t>& contacts,
                std::vector<double>& ax) const;

  /// The compressed-row pattern of J: W's block pattern, scalar.
  void pattern(std::vector<int>& ap, std::vector<int>& ai) const;

  /// ‖r − P_K(r − (u + μ|u_T| e_N))‖² of one contact (natural_map_error's formula).
  static double natural_map2(double rn, double rt, double un, double ut, double mu);

 private:
  /// Φ of frictional contact i at (r, u) of the subproblem (un, ut: its velocity with the
  /// proximal term), and the Jacobian's piece there, in branch_[i].
  void friction_rows(std::size_t i, double rn, double rt, double un, double ut, double& fn, double& ft);

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
  bool grow(const AlartCurnier& ac, bool all);

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
  void rhs(const std::vector<double>& ax_full, double eps, std::vector<double>& d, std::vector<double>& x) const;

  /// Puts J_SS's solution x back into d.
  void scatter(const std::vector<double>& x, std::vector<double>& d) const {
    for (std::size_t m = 0; m < members_.size(); ++m) {
      d[2 * members_[m]] = x[2 * m];
      d[2 * members_[m] + 1] = x[2 * m + 1];
    }
  }

 private:
  void build_pattern();

  const FrictionProblem2D& p_;
  const std::vector<int>& ap_full_;
  std::vector<int> local_;  ///< contact → its place in S, −1 outside
  std::vector<std::uint32_t> members_;  ///< S, in the problem's order
  std::vector<int> ap_, ai_;  ///< J_SS's pattern (compressed rows)
  std::vector<std::size_t> pick_;  ///< each J_SS entry's place in the full J
};

}  // namespace nscd::newton_ac_detail
