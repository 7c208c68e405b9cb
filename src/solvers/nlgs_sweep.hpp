// nscd/solvers/nlgs_sweep.hpp — the NLGS iteration, generic over how contacts are coupled.
//
// A Backend provides, for contact α (all inline, no virtual call, no allocation):
//   Block2 block(α)                       its 2×2 Delassus block (symmetric part)
//   CoulombFactors factors(α)             the block's reciprocals (coulomb2d.hpp)
//   double mu(α)
//   void   velocity(α, double& un, double& ut)   current shifted relative velocity U + s
//   void   impulse(α, double& pn, double& pt)    current impulse
//   void   update(α, double pn, double pt)          set the impulse, propagate the change
//   void   set_status(α, ContactStatus)     record the law's verdict (checked sweeps: the last sweep is one)
//   std::size_t size()
//   std::size_t extra_size()               bilateral links visited after the contacts
//   void sweep_extra(bool check, CriteriaAccumulator&, double omega)
// The iteration: sweeps in the chosen order; every `check_every` sweeps (and at the end) the
// sweep accumulates LMGC90's convergence sums; stop when the policy holds and at least
// min_sweeps were done, or at max_sweeps.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "nscd/core/math.hpp"
#include "nscd/laws/coulomb2d.hpp"
#include "nscd/solvers/contact_part.hpp"
#include "nscd/solvers/convergence.hpp"
#include "nscd/solvers/nlgs.hpp"

namespace nscd {

/// Deterministic shuffle (Fisher–Yates on a 64-bit LCG), independent of the standard library.
inline void shuffle_order(std::vector<std::uint32_t>& order, std::uint64_t& state) {
  for (std::size_t i = order.size(); i > 1; --i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const std::size_t j = static_cast<std::size_t>((state >> 33) % i);
    std::swap(order[i - 1], order[j]);
  }
}

/// Reusable buffers of a sequential NLGS solve (no allocation once warmed up); the colored
/// sweep's own are in NlgsColoredWorkspace (nlgs_colored.hpp).
struct NlgsWorkspace {
  std::vector<std::uint32_t> order;   ///< the contacts in visiting order
  std::vector<std::uint32_t> vanish;  ///< sweeps in a row with a zero impulse (skip rule)
  std::vector<std::uint32_t> level;   ///< skip level k: visited when vanish reaches k(k+1)/2
};

/// One contact visit of NLGS (steps 0–4), shared by every sweep order; `sums` receives the
/// convergence terms on checked sweeps.
template <class Backend, class Sums>
NSCD_HOT_INLINE inline void nlgs_visit(Backend& be, std::uint32_t a, const NlgsOptions& opt, NlgsWorkspace& ws,
                                       bool check, double omega, Sums& sums) {
  // 0. LMGC90's skip rule: a contact whose impulse stays zero is visited less and less
  //    often between checks (after 1, 3, 6, 10, ... such sweeps); checked sweeps visit all.
  double un, ut, pn, pt;
  be.impulse(a, pn, pt);
  if (opt.skip_zero) {
    if (!check && pn == 0.0 && pt == 0.0) {
      const std::uint32_t k = ws.level[a];
      if (++ws.vanish[a] < k * (k + 1) / 2) return;
      ++ws.level[a];
    } else {
      ws.vanish[a] = 0;
      ws.level[a] = 1;
    }
  }
  // 1. The contact's velocity without its own impulse: b = U − W P.
  const Block2 W = be.block(a);
  be.velocity(a, un, ut);
  const double bn = un - (W.nn * pn + W.nt * pt);
  const double bt = ut - (W.nt * pn + W.tt * pt);
  // 2. Exact single-contact Signorini–Coulomb solve, relaxed between checks; a checked sweep
  //    is plain Gauss–Seidel (ω = 1), so that a solve ends on a state where each contact met
  //    its own law at its last visit (theory §9.5: it also keeps SOR converging up to ω ≈ 1.5).
  const LocalImpulse loc = solve_coulomb_2d(W, be.factors(a), bn, bt, be.mu(a));
  const double w = check ? 1.0 : omega;
  const double new_pn = w * loc.pn + (1.0 - w) * pn;
  const double new_pt = w * loc.pt + (1.0 - w) * pt;
  // 3. Convergence sums compare the impulse before the visit with the fresh one.
  if (check) sums.add(a, W, pn, pt, loc.pn, loc.pt);
  // 4. Apply the change to the coupled unknowns; the status is cold data, recorded on checked
  //    sweeps only (the last sweep of a solve is always checked).
  be.update(a, new_pn, new_pt);
  if (check) be.set_status(a, loc.status);
}

/// The sums of a sequential sweep, accumulated in visiting order.
struct SequentialSums {
  CriteriaAccumulator& acc;
  void add(std::uint32_t, const Block2& W, double pn, double pt, double lpn, double lpt) {
    acc.add(W, pn, pt, lpn, lpt);
  }
};

/// The sequential sweeps of nlgs_iterate and nlgs_iterate_mixed (nlgs_mixing.cpp): the order
/// (fixed, reversed, shuffled with opt.seed, alternating), the visits, the extra unknowns, the
/// convergence check every check_every sweeps and at the last. `omega()` gives each sweep's
/// relaxation; `after(sweep, check, res)` runs after every sweep that did not converge. Returns
/// the sweeps done, the last criteria and whether they converged.
template <class Backend, class Omega, class After>
NlgsResult sequential_sweeps(Backend& be, const NlgsOptions& opt, NlgsWorkspace& ws, Omega&& omega, After&& after) {
  NlgsResult res;
  std::vector<std::uint32_t>& order = ws.order;
  order.resize(be.size());
  std::iota(order.begin(), order.end(), 0u);
  if (opt.order == SweepOrder::Reversed) std::reverse(order.begin(), order.end());
  std::uint64_t rng = opt.seed;
  for (int sweep = 1; sweep <= opt.max_sweeps; ++sweep) {
    if (opt.order == SweepOrder::Shuffled) shuffle_order(order, rng);
    if (opt.order == SweepOrder::Alternating && sweep > 1) std::reverse(order.begin(), order.end());
    const bool check = sweep % opt.check_every == 0 || sweep == opt.max_sweeps;
    const double w = omega();
    CriteriaAccumulator acc;
    SequentialSums sums{acc};
    for (const std::uint32_t a : order) nlgs_visit(be, a, opt, ws, check, w, sums);
    be.sweep_extra(check, acc, check ? 1.0 : w);
    res.sweeps = sweep;
    if (check) {
      res.criteria = acc.finish(opt.tol);
      if (sweep >= opt.min_sweeps && converged(res.criteria, opt.policy)) {
        res.converged = true;
        break;
      }
    }
    after(sweep, check, res);
  }
  return res;
}

template <class Backend>
NlgsResult nlgs_iterate(Backend& be, const NlgsOptions& opt, NlgsWorkspace& ws) {
  NlgsResult res;
  const std::size_t n = be.size();
  if (n == 0 && be.extra_size() == 0) {
    res.converged = true;
    return res;
  }
  if (opt.skip_zero) {
    ws.vanish.assign(n, 0u);
    ws.level.assign(n, 1u);
  }
  const double omega = opt.relaxation;
  return sequential_sweeps(be, opt, ws, [omega] { return omega; }, [](int, bool, NlgsResult&) {});
}

}  // namespace nscd
