// nscd/solvers/nlgs.cpp — NLGS on a stand-alone FrictionProblem2D (the W-row backend), and
// the option parsing shared with the scene solver.
#include "nscd/solvers/nlgs.hpp"

#include <array>
#include <string>
#include <utility>

#include "nscd/core/error.hpp"
#include "nscd/solvers/anderson.hpp"
#include "nscd/solvers/nlgs_sweep.hpp"

namespace nscd {
namespace {

constexpr std::array<std::pair<std::string_view, ConvergencePolicy>, 6> kPolicies{{
    {"Quad", ConvergencePolicy::Quad},
    {"Maxm", ConvergencePolicy::Maxm},
    {"QM/16", ConvergencePolicy::QM16},
    {"Strict", ConvergencePolicy::Strict},
    {"NonStrict", ConvergencePolicy::NonStrict},
    {"Energy", ConvergencePolicy::Energy},
}};
constexpr std::array<std::pair<std::string_view, SweepOrder>, 7> kOrders{{{"fixed", SweepOrder::Fixed},
                                                                          {"reversed", SweepOrder::Reversed},
                                                                          {"shuffled", SweepOrder::Shuffled},
                                                                          {"alternating", SweepOrder::Alternating},
                                                                          {"colored", SweepOrder::Colored},
                                                                          {"colored-rows", SweepOrder::ColoredRows},
                                                                          {"colored-cells", SweepOrder::ColoredCells}}};

// Coupling through the rows of W: U_α = q_α + Σ_β W_αβ P_β, recomputed from the row at each visit.
struct ProblemBackend {
  const FrictionProblem2D& p;
  std::vector<double>& r;
  std::vector<CoulombFactors> f;  ///< per contact, computed once

  ProblemBackend(const FrictionProblem2D& problem, std::vector<double>& impulses) : p(problem), r(impulses) {
    f.reserve(p.nc);
    for (std::uint32_t a = 0; a < p.nc; ++a) f.push_back(coulomb_factors(block(a), p.mu[a]));
  }
  const CoulombFactors& factors(std::uint32_t a) const { return f[a]; }

  std::size_t size() const { return p.nc; }
  std::size_t extra_size() const { return 0; }
  void sweep_extra(bool, CriteriaAccumulator&, double) {}
  Block2 block(std::uint32_t a) const {
    const auto& b = p.block[p.diag[a]];
    return {b[0], 0.5 * (b[1] + b[2]), b[3]};
  }
  double mu(std::uint32_t a) const { return p.mu[a]; }
  void velocity(std::uint32_t a, double& un, double& ut) const {
    un = p.q[2 * a];
    ut = p.q[2 * a + 1];
    for (std::uint32_t k = p.row_start[a]; k < p.row_start[a + 1]; ++k) {
      const auto& b = p.block[k];
      const double xn = r[2 * p.col[k]], xt = r[2 * p.col[k] + 1];
      un += b[0] * xn + b[1] * xt;
      ut += b[2] * xn + b[3] * xt;
    }
  }
  void impulse(std::uint32_t a, double& pn, double& pt) const {
    pn = r[2 * a];
    pt = r[2 * a + 1];
  }
  void update(std::uint32_t a, double pn, double pt) {
    r[2 * a] = pn;
    r[2 * a + 1] = pt;
  }
  void set_status(std::uint32_t, ContactStatus) {}
};

}  // namespace

ConvergencePolicy parse_convergence_policy(std::string_view name) {
  for (const auto& [n, p] : kPolicies)
    if (n == name) return p;
  std::string msg = "unknown convergence policy '" + std::string(name) + "'; valid:";
  for (const auto& e : kPolicies) msg += " " + std::string(e.first);
  throw Error(msg);
}

std::string_view name_of(ConvergencePolicy p) {
  for (const auto& [n, v] : kPolicies)
    if (v == p) return n;
  return "?";
}

SweepOrder parse_sweep_order(std::string_view name) {
  for (const auto& [n, o] : kOrders)
    if (n == name) return o;
  std::string valid;  // (from the table: a new order is listed where it is added)
  for (const auto& [n, o] : kOrders) valid += " " + std::string(n);
  throw Error("unknown sweep order '" + std::string(name) + "'; valid:" + valid);
}

std::string_view name_of(SweepOrder o) {
  for (const auto& [n, v] : kOrders)
    if (v == o) return n;
  return "?";
}

void validate(const NlgsOptions& o) {
  if (!(o.tol > 0.0)) throw Error("NLGS: tolerance must be > 0, got " + std::to_string(o.tol));
  if (o.check_every < 1) throw Error("NLGS: sweeps between checks must be >= 1, got " + std::to_string(o.check_every));
  if (o.min_sweeps < 0 || o.max_sweeps < 1 || o.max_sweeps < o.min_sweeps)
    throw Error("NLGS: need 0 <= min_sweeps <= max_sweeps and max_sweeps >= 1 (got " + std::to_string(o.min_sweeps) +
                ", " + std::to_string(o.max_sweeps) + ")");
  if (!(o.relaxation > 0.0 && o.relaxation < 2.0))
    throw Error("NLGS: relaxation must lie in (0, 2), got " + std::to_string(o.relaxation));
  if (o.relaxation != 1.0 && o.check_every < 2)
    throw Error("NLGS: relaxation " + std::to_string(o.relaxation) +
                " needs at least 2 sweeps between checks (check_every = 1): "
                "a checked sweep is plain Gauss-Seidel, so the relaxation would never be used");
  if (o.lanes != 0 && o.lanes != 2 && o.lanes != 4)
    throw Error("NLGS: lanes must be 0 (scalar), 2 (SSE2) or 4 (AVX2 where the CPU has it, else SSE2), got " +
                std::to_string(o.lanes));
  if (o.anderson < 0 || o.anderson > AndersonMixer::kMaxDepth)
    throw Error("NLGS: Anderson depth must lie in [0, " + std::to_string(AndersonMixer::kMaxDepth) +
                "] (0: off), got " + std::to_string(o.anderson));
  if (o.anderson > 0 && o.skip_zero)
    throw Error(
        "NLGS: Anderson mixing and the skip rule do not go together "
        "(a skipped contact's impulse would be mixed as if swept)");
  if (o.threads < 1 || o.threads > 256)
    throw Error("NLGS: threads must lie in [1, 256], got " + std::to_string(o.threads));
  if (o.threads > 1 && !is_colored(o.order))
    throw Error("NLGS: " + std::to_string(o.threads) +
                " threads need the colored sweep order (order = colored): the other orders are sequential");
}

NlgsResult nlgs_solve(const FrictionProblem2D& problem, std::vector<double>& r, const NlgsOptions& options) {
  validate(options);
  if (is_colored(options.order))
    throw Error("NLGS: the colored orders colour contacts by the bodies they share; a stand-alone problem has no "
                "bodies (use fixed, reversed, shuffled or alternating)");
  if (options.anderson > 0)
    throw Error("NLGS: Anderson mixing mixes a scene's impulses and body velocities; a stand-alone problem has no "
                "bodies (use anderson = 0)");
  if (r.size() != 2 * problem.nc) r.assign(2 * problem.nc, 0.0);
  ProblemBackend be{problem, r};
  NlgsWorkspace ws;
  return nlgs_iterate(be, options, ws);
}

}  // namespace nscd
