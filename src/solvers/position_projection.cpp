// nscd/solvers/position_projection.cpp — see position_projection.hpp.
#include "nscd/solvers/position_projection.hpp"

#include <algorithm>
#include <cmath>

#include "nscd/core/error.hpp"

namespace nscd {

void validate(const ProjectionOptions& o) {
  if (!(o.slop >= 0.0) || !std::isfinite(o.slop))
    throw Error("projection slop must be >= 0 and finite (a fraction of the alert distance)");
  if (!(o.share > 0.0 && o.share <= 1.0)) throw Error("projection share must lie in (0, 1]");
  if (!(o.end_slops >= 1.0) || !std::isfinite(o.end_slops)) throw Error("projection end_slops must be >= 1 and finite");
  if (o.max_sweeps < 1) throw Error("projection max_sweeps must be >= 1");
  if (!(o.tol > 0.0) || !std::isfinite(o.tol)) throw Error("projection tol must be > 0 and finite");
}

double PositionProjection::normal_shift(const ContactSystem& sys, std::size_t a) const {
  if (!moved_) return 0.0;
  const SolverContact& c = sys.contacts[a];
  double dn, dt;
  contact_velocity(c, dq_[c.cd], dq_[c.an], dn, dt);
  return dn;
}

ProjectionReport PositionProjection::project(const ContactSystem& sys, const std::vector<double>& gaps, double h,
                                             double theta, double s, const ProjectionOptions& o) {
  ProjectionReport r;
  moved_ = false;
  const std::size_t nc = sys.contacts.size();
  // 1. The slacks c_α before any correction: the next detection's gap against its target, and
  //    the end of step's against −k s; nothing to do if none is negative.
  slack_.resize(nc);
  const double end_bound = o.end_slops * s;
  for (std::size_t a = 0; a < nc; ++a) {
    const SolverContact& c = sys.contacts[a];
    double un, ut;
    contact_velocity(c, sys.bodies[c.cd], sys.bodies[c.an], un, ut);
    const double g = gaps[a] + h * un, e = gaps[a] + theta * h * un;
    if (c.W.nn <= 0.0) {
      slack_[a] = 0.0;
      continue;
    }
    const double next = g >= -s ? g + s : -o.share * (-s - g);  // g' − G
    slack_[a] = std::min(next, e + end_bound);
    if (slack_[a] < 0.0) {
      ++r.beyond;
      r.max_excess = std::max(r.max_excess, -slack_[a]);
    }
  }
  if (r.beyond == 0) return r;
  // 2. Projected Gauss–Seidel on c = slack + H*_N Δq ≥ 0 ⊥ Π ≥ 0, Δq = M⁻¹ H_N Π; a contact
  //    with room to spare whose bodies have not moved is skipped (it cannot be violated).
  dq_.resize(sys.bodies.size());
  for (std::size_t i = 0; i < dq_.size(); ++i) {
    const SolverBody& b = sys.bodies[i];
    dq_[i] = SolverBody{0.0, 0.0, 0.0, b.inv_mx, b.inv_my, b.inv_i};
  }
  pi_.assign(2 * nc, 0.0);
  touched_.assign(dq_.size(), 0);
  const double stop = o.tol * s;
  for (int sweep = 0; sweep < o.max_sweeps; ++sweep) {
    double worst = 0.0;
    for (std::size_t a = 0; a < nc; ++a) {
      const SolverContact& c = sys.contacts[a];
      double* pi = &pi_[2 * a];
      if (slack_[a] >= 0.0 && pi[0] == 0.0 && !touched_[c.cd] && !touched_[c.an]) continue;
      if (c.W.nn <= 0.0) continue;
      // the contact's relative displacement (normal: past its target G), then Coulomb's law in
      // displacements on it, exactly as an NLGS visit does in velocities
      double dn, dt;
      contact_velocity(c, dq_[c.cd], dq_[c.an], dn, dt);
      const double gap = slack_[a] + dn;
      worst = std::max(worst, -gap);
      const double bn = gap - (c.W.nn * pi[0] + c.W.nt * pi[1]), bt = dt - (c.W.nt * pi[0] + c.W.tt * pi[1]);
      const LocalImpulse p = solve_coulomb_2d(c.W, c.f, bn, bt, c.mu);
      if (p.pn == pi[0] && p.pt == pi[1]) continue;
      apply_impulse(c, dq_[c.cd], dq_[c.an], p.pn - pi[0], p.pt - pi[1]);
      pi[0] = p.pn;
      pi[1] = p.pt;
      touched_[c.cd] = c.cd_dynamic;
      touched_[c.an] = c.an_dynamic;
    }
    r.sweeps = sweep + 1;
    r.max_residual = worst;
    if (worst <= stop) break;
  }
  moved_ = true;
  for (const SolverBody& d : dq_) r.max_shift = std::max({r.max_shift, std::abs(d.vx), std::abs(d.vy)});
  return r;
}

}  // namespace nscd
