// nscd/solvers/contact_system.cpp — see contact_system.hpp.
#include "nscd/solvers/contact_system.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "nscd/core/error.hpp"

namespace nscd {
namespace {

/// One 2-row block of the system (a contact, or a link with an unused tangential row).
struct Block {
  std::uint32_t cd, an;
  JacobianRows J;
};

std::vector<Block> blocks_of(const ContactSystem& s, bool with_links) {
  std::vector<Block> blocks;
  blocks.reserve(s.contacts.size() + (with_links ? s.links.size() : 0));
  for (const SolverContact& c : s.contacts) blocks.push_back({c.cd, c.an, jacobian_rows(c)});
  if (with_links)
    for (const SolverLink& l : s.links) blocks.push_back({l.cd, l.an, jacobian_rows(l)});
  return blocks;
}

const double* row(const JacobianRows& J, bool candidate, int r) {
  return candidate ? (r == 0 ? J.cd_n : J.cd_t) : (r == 0 ? J.an_n : J.an_t);
}

/// W = H* M⁻¹ H, block row by block row: row a couples with every block that shares a dynamic
/// body with it (each shared body adds its term, the lower body index first). Built directly
/// in block-sparse rows, columns in order (no sort of triplets: this runs every NEWTON_AC step).
FrictionProblem2D assemble_w(const std::vector<SolverBody>& m, const std::vector<Block>& blocks,
                             std::vector<double> q, std::vector<double> mu) {
  struct Entry { std::uint32_t block; bool candidate; };
  const std::size_t nb = blocks.size();
  // 1. Each body's blocks, in block order (compressed by body).
  std::vector<std::uint32_t> first(m.size() + 1, 0);
  for (const Block& b : blocks) {
    ++first[b.cd + 1];
    ++first[b.an + 1];
  }
  for (std::size_t b = 0; b < m.size(); ++b) first[b + 1] += first[b];
  std::vector<Entry> by_body(2 * nb);
  {
    std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
    for (std::uint32_t a = 0; a < nb; ++a) {
      by_body[next[blocks[a].cd]++] = {a, true};
      by_body[next[blocks[a].an]++] = {a, false};
    }
  }
  FrictionProblem2D p;
  p.nc = nb;
  if (q.size() != 2 * nb || mu.size() != nb) throw Error("assemble_w: q must have 2·nc values and mu nc");
  p.q = std::move(q);
  p.mu = std::move(mu);
  p.row_start.assign(nb + 1, 0);
  p.diag.assign(nb, 0);
  std::vector<std::int64_t> slot(nb, -1);  // column → its block in the row being built
  std::vector<std::uint32_t> order;
  std::vector<std::array<double, 4>> row_blocks;
  std::vector<std::uint32_t> row_cols;
  for (std::uint32_t a = 0; a < nb; ++a) {
    row_blocks.clear();
    row_cols.clear();
    // 2. Through each dynamic body of a (a kinematic body couples nothing, M⁻¹ = 0: the
    //    floor's contacts do not form a dense clique in W nor fill in NEWTON_AC's factors).
    const std::uint32_t lo = std::min(blocks[a].cd, blocks[a].an), hi = std::max(blocks[a].cd, blocks[a].an);
    const std::uint32_t bodies[2] = {lo, hi};
    for (int side = 0; side < (lo == hi ? 1 : 2); ++side) {
      const std::uint32_t bi = bodies[side];
      if (!is_dynamic(m[bi])) continue;
      const double inv[3] = {m[bi].inv_mx, m[bi].inv_my, m[bi].inv_i};
      for (std::uint32_t ka = first[bi]; ka < first[bi + 1]; ++ka) {
        if (by_body[ka].block != a) continue;
        const Entry ea = by_body[ka];
        for (std::uint32_t kb = first[bi]; kb < first[bi + 1]; ++kb) {
          const Entry eb = by_body[kb];
          if (slot[eb.block] < 0) {
            slot[eb.block] = static_cast<std::int64_t>(row_blocks.size());
            row_blocks.push_back({0.0, 0.0, 0.0, 0.0});
            row_cols.push_back(eb.block);
          }
          std::array<double, 4>& w = row_blocks[static_cast<std::size_t>(slot[eb.block])];
          for (int e = 0; e < 4; ++e) {
            const double* ra = row(blocks[a].J, ea.candidate, e / 2);
            const double* rb = row(blocks[eb.block].J, eb.candidate, e % 2);
            double v = 0.0;
            for (int d = 0; d < 3; ++d) v += ra[d] * inv[d] * rb[d];
            w[e] += v;
          }
        }
      }
    }
    // 3. The row's blocks in column order.
    order.resize(row_cols.size());
    for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) { return row_cols[x] < row_cols[y]; });
    bool has_diag = false;
    for (const std::uint32_t k : order) {
      if (row_cols[k] == a) {
        p.diag[a] = static_cast<std::uint32_t>(p.block.size());
        has_diag = true;
      }
      p.col.push_back(row_cols[k]);
      p.block.push_back(row_blocks[k]);
      slot[row_cols[k]] = -1;
    }
    if (!has_diag) throw Error("W: contact " + std::to_string(a) + " has no diagonal block (both bodies kinematic)");
    p.row_start[a + 1] = static_cast<std::uint32_t>(p.block.size());
  }
  return p;
}

/// q and μ of the contacts (the first 2·nc and nc entries) at the free velocities u0.
void contact_rhs(const std::vector<SolverContact>& contacts, const std::vector<SolverBody>& u0, std::vector<double>& q,
                 std::vector<double>& mu) {
  for (std::size_t a = 0; a < contacts.size(); ++a) {
    const SolverContact& s = contacts[a];
    double un, ut;
    contact_velocity(s, u0[s.cd], u0[s.an], un, ut);
    q[2 * a] = un + s.sn;
    q[2 * a + 1] = ut + s.st;
    mu[a] = s.mu;
  }
}

}  // namespace

FrictionProblem2D ContactSystem::local_problem() const {
  // free velocities with the iterated links' current impulses folded in
  std::vector<SolverBody> u0 = free;
  for (const SolverLink& l : links) apply_link_impulse(l, u0[l.cd], u0[l.an], l.p);
  const std::size_t nc = contacts.size();
  std::vector<double> q(2 * nc), mu(nc);
  contact_rhs(contacts, u0, q, mu);
  return assemble_w(free, blocks_of(*this, false), std::move(q), std::move(mu));
}

FrictionProblem2D ContactSystem::local_problem_with_links(BilateralRows& rows) const {
  const std::size_t nc = contacts.size(), nl = links.size();
  std::vector<double> q(2 * (nc + nl), 0.0), mu(nc + nl, 0.0);
  contact_rhs(contacts, free, q, mu);
  rows = {};
  for (std::size_t k = 0; k < nl; ++k) {
    const SolverLink& l = links[k];
    q[2 * (nc + k)] = link_velocity(l, free[l.cd], free[l.an]);
    rows.index.push_back(static_cast<std::uint32_t>(nc + k));
    rows.ha.push_back(l.law.ha);
    rows.hb.push_back(l.law.hb);
  }
  return assemble_w(free, blocks_of(*this, true), std::move(q), std::move(mu));
}

GlobalProblem ContactSystem::global_problem() const {
  GlobalProblem g;
  // 1. Free dofs: those with a non-zero inverse mass.
  std::vector<std::int64_t> dof_of(3 * free.size(), -1);
  for (std::uint32_t b = 0; b < free.size(); ++b) {
    const double inv[3] = {free[b].inv_mx, free[b].inv_my, free[b].inv_i};
    for (std::uint8_t d = 0; d < 3; ++d)
      if (inv[d] != 0.0) {
        dof_of[3 * b + d] = static_cast<std::int64_t>(g.dof_body.size());
        g.dof_body.push_back(b);
        g.dof_kind.push_back(d);
      }
  }
  const auto n = static_cast<Eigen::Index>(g.dof_body.size());
  // 2. M and f = M v_free, diagonal.
  g.M.resize(n, n);
  g.M.reserve(Eigen::VectorXi::Constant(n, 1));
  g.f.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const SolverBody& s = free[g.dof_body[static_cast<std::size_t>(i)]];
    const double inv[3] = {s.inv_mx, s.inv_my, s.inv_i}, v[3] = {s.vx, s.vy, s.w};
    const int d = g.dof_kind[static_cast<std::size_t>(i)];
    g.M.insert(i, i) = 1.0 / inv[d];
    g.f[i] = v[d] / inv[d];
  }
  g.M.makeCompressed();
  // 3. H column by column (at most 6 entries each), b from the kinematic dofs and the shifts.
  const std::vector<Block> blocks = blocks_of(*this, true);
  const auto ncol = static_cast<Eigen::Index>(2 * blocks.size());
  g.H.resize(n, ncol);
  g.H.reserve(Eigen::VectorXi::Constant(ncol, 6));
  g.b = Eigen::VectorXd::Zero(ncol);
  g.mu.assign(blocks.size(), 0.0);
  for (std::size_t a = 0; a < blocks.size(); ++a) {
    const Block& blk = blocks[a];
    for (int r = 0; r < 2; ++r) {
      const auto col = static_cast<Eigen::Index>(2 * a + r);
      for (const bool candidate : {true, false}) {
        const std::uint32_t body = candidate ? blk.cd : blk.an;
        const double* h = row(blk.J, candidate, r);
        const double v[3] = {free[body].vx, free[body].vy, free[body].w};
        for (int d = 0; d < 3; ++d) {
          if (h[d] == 0.0) continue;
          const std::int64_t dof = dof_of[3 * body + d];
          if (dof >= 0) g.H.insert(dof, col) = h[d];
          else g.b[col] += h[d] * v[d];
        }
      }
    }
    if (a < contacts.size()) {
      g.b[static_cast<Eigen::Index>(2 * a)] += contacts[a].sn;
      g.b[static_cast<Eigen::Index>(2 * a + 1)] += contacts[a].st;
      g.mu[a] = contacts[a].mu;
    }
  }
  g.H.makeCompressed();
  return g;
}

std::vector<double> ContactSystem::impulses(bool with_links) const {
  std::vector<double> r(2 * (contacts.size() + (with_links ? links.size() : 0)), 0.0);
  for (std::size_t a = 0; a < contacts.size(); ++a) {
    r[2 * a] = contacts[a].pn;
    r[2 * a + 1] = contacts[a].pt;
  }
  if (with_links)
    for (std::size_t k = 0; k < links.size(); ++k) r[2 * (contacts.size() + k)] = links[k].p;
  return r;
}

void ContactSystem::set_impulses(const std::vector<double>& r, bool with_links) {
  bodies = free;
  for (std::size_t a = 0; a < contacts.size(); ++a) {
    SolverContact& c = contacts[a];
    // a global solver's answer is admissible up to its tolerance: put it exactly in the cone
    c.pn = std::max(0.0, r[2 * a]);
    c.pt = std::clamp(r[2 * a + 1], -c.mu * c.pn, c.mu * c.pn);
    apply_impulse(c, bodies[c.cd], bodies[c.an], c.pn, c.pt);
  }
  if (with_links)
    for (std::size_t k = 0; k < links.size(); ++k) {
      SolverLink& l = links[k];
      l.p = r[2 * (contacts.size() + k)];
      apply_link_impulse(l, bodies[l.cd], bodies[l.an], l.p);
    }
  else
    for (const SolverLink& l : links) apply_link_impulse(l, bodies[l.cd], bodies[l.an], l.p);
  // statuses from the final impulses and velocities
  status.resize(contacts.size());
  for (std::size_t a = 0; a < contacts.size(); ++a) {
    const SolverContact& c = contacts[a];
    double un, ut;
    contact_velocity(c, bodies[c.cd], bodies[c.an], un, ut);
    ut += c.st;
    if (c.pn <= 0.0) status[a] = ContactStatus::Open;
    else if (std::abs(c.pt) < c.mu * c.pn || ut == 0.0) status[a] = ContactStatus::Stick;
    else status[a] = ut > 0.0 ? ContactStatus::SlipForward : ContactStatus::SlipBackward;
  }
}

}  // namespace nscd
