// nscd/solvers/position_projection.cpp — see position_projection.hpp.
#include "nscd/solvers/position_projection.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "nscd/core/error.hpp"
#include "nscd/solvers/spin_barrier.hpp"
#include "nscd/solvers/thread_range.hpp"

namespace nscd {
namespace {

/// A block's work in a sweep: a unit for each contact (the skip test: four loads and compares)
/// and this many more for each contact visited (the local solve and the impulse applied): a
/// visit costs 3–4 skip tests more in time, 4–8 in instructions (benchmarks-history.md §11.40).
constexpr std::uint32_t kVisitWork = 4;

/// Thread t's blocks [b0, b1) of a colour of n blocks whose works are w[0 … n−1]: from the first
/// block whose work before it reaches t/team of the colour's to the first that reaches
/// (t+1)/team. Every thread finds the same boundaries, so the ranges tile the colour.
std::pair<std::size_t, std::size_t> work_range(const std::uint32_t* w, std::size_t n, std::size_t t, std::size_t team) {
  std::uint64_t total = 0;
  for (std::size_t b = 0; b < n; ++b) total += w[b];
  // the first b with (w[0] + … + w[b−1]) × team ≥ total × t, then from there × (t + 1)
  std::uint64_t before = 0;
  std::size_t b = 0;
  for (; b < n && before * team < total * t; ++b) before += w[b];
  const std::size_t b0 = b;
  if (t + 1 >= team) return {b0, n};
  for (; b < n && before * team < total * (t + 1); ++b) before += w[b];
  return {b0, b};
}

}  // namespace

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

// 1. The slacks c_α before any correction: the next detection's gap against its target, and the
//    end of step's against −k s; with each contact's ends for the sweeps' skip test. Contacts
//    a0 … a1−1; counts and largest excess added to `out` (a count and a maximum: the same in any split).
void PositionProjection::slacks(const ContactSystem& sys, const std::vector<double>& gaps, const SlackParams& q,
                                std::size_t a0, std::size_t a1, ProjectionReport& out) {
  ProjectionReport r = out;  // (in registers: `out` may share a cache line with another thread's)
  for (std::size_t a = a0; a < a1; ++a) {
    const SolverContact& c = sys.contacts[a];
    ends_[a] = {c.cd, c.an};
    double un, ut;
    contact_velocity(c, sys.bodies[c.cd], sys.bodies[c.an], un, ut);
    const double g = gaps[a] + q.h * un, e = gaps[a] + q.theta * q.h * un;
    if (c.W.nn <= 0.0) {
      slack_[a] = 0.0;
      continue;
    }
    const double next = g >= -q.s ? g + q.s : -q.share * (-q.s - g);  // g' − G
    slack_[a] = std::min(next, e + q.end_bound);
    if (slack_[a] < 0.0) {
      ++r.beyond;
      r.max_excess = std::max(r.max_excess, -slack_[a]);
    }
  }
  out = r;
}

ProjectionReport PositionProjection::project(const ContactSystem& sys, const std::vector<double>& gaps, double h,
                                             double theta, double s, const ProjectionOptions& o, int threads,
                                             ContactColors colors) {
  ProjectionReport r;
  moved_ = false;
  const std::size_t nc = sys.contacts.size(), nb = sys.bodies.size();
  slack_.resize(nc);
  ends_.resize(nc);
  const SlackParams q{h, theta, s, o.share, o.end_slops * s};
  if (const int t = light_threads(nc, threads); t > 1) {
    each_range_into(nc, t, part_,
                    [&](std::size_t a0, std::size_t a1, ProjectionReport& p) { slacks(sys, gaps, q, a0, a1, p); });
    for (const ProjectionReport& p : part_) {
      r.beyond += p.beyond;
      r.max_excess = std::max(r.max_excess, p.max_excess);
    }
  } else {
    slacks(sys, gaps, q, 0, nc, r);
  }
  if (r.beyond == 0) return r;
  // 2. Projected Gauss–Seidel on c = slack + H*_N Δq ≥ 0 ⊥ Π ≥ 0, Δq = M⁻¹ H_N Π; a contact
  //    with room to spare whose bodies have not moved is skipped (it cannot be violated).
  dq_.resize(nb);
  touched_.resize(nb);
  pi_.resize(2 * nc);
  each_index(nb, light_threads(nb, threads), [&](std::size_t i) {
    const SolverBody& b = sys.bodies[i];
    dq_[i] = SolverBody{0.0, 0.0, 0.0, b.inv_mx, b.inv_my, b.inv_i};
  });
  if (const int t = light_threads(nc, threads); t > 1) {
#pragma omp parallel num_threads(t)
    {
      const auto [a0, a1] = thread_range(nc);
      std::fill(pi_.data() + 2 * a0, pi_.data() + 2 * a1, 0.0);
      const auto [i0, i1] = thread_range(nb);
      std::fill(touched_.data() + i0, touched_.data() + i1, 0);
    }
  } else {
    std::fill(pi_.begin(), pi_.end(), 0.0);
    std::fill(touched_.begin(), touched_.end(), 0);
  }
  const double stop = o.tol * s;
  if (colors.block_start && threads > 1 && nc >= kProjectionParallelMin) {
    colored_sweeps(sys, colors, threads, o.max_sweeps, stop, r);
  } else {
    std::uint32_t visits = 0;  // (the serial sweeps share no blocks)
    for (int sweep = 0; sweep < o.max_sweeps; ++sweep) {
      const double worst = gauss_seidel_sweep(sys, 0, nc, visits);
      r.sweeps = sweep + 1;
      r.max_residual = worst;
      if (worst <= stop) break;
    }
  }
  moved_ = true;
  r.max_shift = largest_shift(light_threads(nb, threads));
  return r;
}

// The largest |Δx|, |Δy| of a body (a maximum: the same on any threads).
double PositionProjection::largest_shift(int threads) const {
  double shift = 0.0;
  auto of = [this](std::size_t i, double s) { return std::max({s, std::abs(dq_[i].vx), std::abs(dq_[i].vy)}); };
  if (threads <= 1) {
    for (std::size_t i = 0; i < dq_.size(); ++i) shift = of(i, shift);
    return shift;
  }
  const auto m = static_cast<std::ptrdiff_t>(dq_.size());
#pragma omp parallel for num_threads(threads) schedule(static) reduction(max : shift)
  for (std::ptrdiff_t i = 0; i < m; ++i) shift = of(static_cast<std::size_t>(i), shift);
  return shift;
}

// One sweep of 2. over contacts a0 … a1−1; returns the largest −c_α met. The skip test reads the
// slacks, Π and the contacts' ends (8 bytes a contact), not the records: in a large system
// nearly every contact is skipped, and the sweep is then a pass over these arrays.
double PositionProjection::gauss_seidel_sweep(const ContactSystem& sys, std::size_t a0, std::size_t a1,
                                              std::uint32_t& visits) {
  double worst = 0.0;
  std::uint32_t n = 0;
  for (std::size_t a = a0; a < a1; ++a) {
    double* pi = &pi_[2 * a];
    if (slack_[a] >= 0.0 && pi[0] == 0.0 && !touched_[ends_[a].cd] && !touched_[ends_[a].an]) continue;
    const SolverContact& c = sys.contacts[a];
    if (c.W.nn <= 0.0) continue;
    ++n;
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
    // only a dynamic body is marked (a kinematic one, shared by a colour's blocks, is never written)
    if (c.cd_dynamic) touched_[c.cd] = 1;
    if (c.an_dynamic) touched_[c.an] = 1;
  }
  visits = n;
  return worst;
}

// The same sweeps on the threads, in one parallel region, colour by colour: each thread a range
// of a colour's blocks, which share no dynamic body with the others' (their Δq and marks), a
// barrier between colours; at the last, thread 0 sweeps the overflow colour, takes the largest
// of the threads' and decides whether to stop. Every contact sees what it sees in the sweep in
// order; the largest is the same. The overlaps to remove gather where the pile moves, so the
// ranges share out the blocks' work in the sweep before (a block's contacts, and kVisitWork for
// each it visited), not their count: any ranges give the same numbers
// (docs/record/benchmarks-history.md §11.39).
void PositionProjection::colored_sweeps(const ContactSystem& sys, const ContactColors& colors, int threads,
                                        int max_sweeps, double stop, ProjectionReport& r) {
  const std::vector<std::uint32_t>& block = *colors.block_start;
  const std::vector<std::uint32_t>& color = *colors.color_start;
  const std::size_t last = color.size() - 2;  // the overflow
  const std::size_t blocks = block.size() - 1;
  worst_.resize(static_cast<std::size_t>(threads));
  for (std::vector<std::uint32_t>& w : block_work_) w.resize(blocks);
  for (std::size_t b = 0; b < blocks; ++b) block_work_[0][b] = block[b + 1] - block[b];
  SpinBarrier barrier;
#pragma omp parallel num_threads(threads)
  {
    const std::size_t t = thread_index(), team = thread_count();
#pragma omp single
    barrier.reset(static_cast<unsigned>(team));  // (the single's own barrier follows)
    unsigned sense = 0;
    for (int sweep = 0; sweep < max_sweeps; ++sweep) {
      const std::uint32_t* before = block_work_[sweep & 1].data();
      std::uint32_t* now = block_work_[(sweep & 1) ^ 1].data();
      double worst = 0.0;
      for (std::size_t k = 0; k < last; ++k) {
        if (color[k + 1] == color[k]) continue;  // (every thread skips it alike)
        const auto [b0, b1] = work_range(before + color[k], color[k + 1] - color[k], t, team);
        for (std::size_t b = color[k] + b0; b < color[k] + b1; ++b) {
          std::uint32_t visits;
          worst = std::max(worst, gauss_seidel_sweep(sys, block[b], block[b + 1], visits));
          now[b] = block[b + 1] - block[b] + kVisitWork * visits;
        }
        if (k + 1 < last) barrier.wait(sense, t);
      }
      worst_[t].v = worst;
      const bool done = barrier.wait_then(sense, t, [&] {
        std::uint32_t visits;
        double w = gauss_seidel_sweep(sys, block[color[last]], block[color[last + 1]], visits);
        for (std::size_t u = 0; u < team; ++u) w = std::max(w, worst_[u].v);
        r.sweeps = sweep + 1;
        r.max_residual = w;
        return w <= stop;
      });
      if (done) break;
    }
  }
}

}  // namespace nscd
