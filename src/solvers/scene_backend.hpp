// nscd/solvers/scene_backend.hpp — the NLGS backend of a running scene: contacts couple
// through the velocities of the two bodies they touch (W is never assembled).
//
// Hot data are gathered once per step into two flat arrays (Box2D-style solver bodies and
// solver contacts, contact_part.hpp), cold data (registry row, status) beside them: one contact
// visit reads one SolverContact and two SolverBody records, about 50 flops, no allocation, no
// virtual call. The ≤ 2 points of a PLPLx pair are consecutive (detection emits them so), so a
// sweep visits them one after the other, the second finding the pair's bodies in L1. Bodies are
// not loaded once per pair into locals (Box2D's contact_solver.c), nor are the impulses kept in
// an array of their own: at 1.2–1.5 points per pair the first adds work, and the second's extra
// stream costs more than the write-back it saves (docs/benchmarks.md §8).
#pragma once

#include <cstdint>
#include <vector>

#include "nscd/solvers/contact_part.hpp"
#include "nscd/solvers/contact_system.hpp"
#include "nscd/solvers/convergence.hpp"

namespace nscd {

struct SceneBackend {
  std::vector<SolverContact>& contacts;
  std::vector<SolverBody>& bodies;
  std::vector<SolverLink>& links;
  std::vector<ContactStatus>& status;  ///< cold: written on checked sweeps, read after the solve

  explicit SceneBackend(ContactSystem& s) : contacts(s.contacts), bodies(s.bodies), links(s.links), status(s.status) {}

  std::size_t size() const { return contacts.size(); }
  std::size_t extra_size() const { return links.size(); }
  /// One visit of every spring link (after the contacts, in the same sweep): exact implicit
  /// VOIGT_ROD solve, relaxed, with its contribution to the convergence sums.
  void sweep_extra(bool check, CriteriaAccumulator& acc, double omega) {
    for (SolverLink& l : links) {
      SolverBody& cd = bodies[l.cd];
      SolverBody& an = bodies[l.an];
      const double c = link_velocity(l, cd, an) - l.w * l.p;
      const double p_loc = voigt_impulse(l.law, l.w, c);
      const double p_new = omega * p_loc + (1.0 - omega) * l.p;
      if (check) acc.add(Block2{l.w, 0.0, 0.0}, l.p, 0.0, p_loc, 0.0);
      apply_link_impulse(l, cd, an, p_new - l.p);
      l.p = p_new;
    }
  }
  Block2 block(std::uint32_t a) const { return contacts[a].W; }
  const CoulombFactors& factors(std::uint32_t a) const { return contacts[a].f; }
  double mu(std::uint32_t a) const { return contacts[a].mu; }
  void velocity(std::uint32_t a, double& un, double& ut) const {
    const SolverContact& c = contacts[a];
    contact_velocity(c, bodies[c.cd], bodies[c.an], un, ut);
    un += c.sn;
    ut += c.st;
  }
  void impulse(std::uint32_t a, double& pn, double& pt) const {
    pn = contacts[a].pn;
    pt = contacts[a].pt;
  }
  void update(std::uint32_t a, double pn, double pt) {
    SolverContact& c = contacts[a];
    apply_impulse(c, bodies[c.cd], bodies[c.an], pn - c.pn, pt - c.pt);
    c.pn = pn;
    c.pt = pt;
  }
  void set_status(std::uint32_t a, ContactStatus s) { status[a] = s; }
};

}  // namespace nscd
