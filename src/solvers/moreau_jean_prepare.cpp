// nscd/solvers/moreau_jean_prepare.cpp — MoreauJean::prepare's steps (moreau_jean.hpp): the
// spring links, the contact records, the contacts' warm start.
#include <cstddef>
#include <cstring>
#include <utility>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/interactions/ptpt2.hpp"
#include "nscd/laws/contact_laws.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "nscd/solvers/contact_part.hpp"
#include "nscd/solvers/thread_range.hpp"

namespace nscd {

void MoreauJean::prepare_links() {
  // 1. Spring links: frame at q_m and implicit law coefficients. A link from a kinematic body
  //    (the ground) acting on a single free dof of its candidate (a pad guided vertically) is
  //    condensed: its affine force enters that dof as an effective mass m + h b c² and a shifted
  //    free velocity, exactly, so no sweep is spent on it. Other links are iterated.
  const double h = reg_.params.dt, theta = reg_.params.theta;
  std::vector<SolverBody>& bodies_ = sys_.bodies;
  sys_.links.clear();
  sys_.condensed.clear();
  const Ptpt2Table& links = reg_.links;
  for (std::uint32_t k = 0; k < links.size(); ++k) {
    const LinkFrame f = link_frame(reg_, LinkId(k), qm_x_, qm_y_, qm_a_);
    SolverLink l;
    l.row = k;
    l.cd = reg_.points.body[links.candidate[k].index()].index();
    l.an = reg_.points.body[links.antagonist[k].index()].index();
    l.nx = f.n.x;
    l.ny = f.n.y;
    l.cd_rn = f.cd_rn;
    l.an_rn = f.an_rn;
    const VoigtRod& law = links.law[k];
    l.law = voigt_affine(law.k, law.nu, law.L0 * (1.0 + law.eps0), f.length, h, theta);
    l.cd_dynamic = is_dynamic(bodies_[l.cd]);
    l.an_dynamic = is_dynamic(bodies_[l.an]);
    if (condense_link(l, bodies_[l.cd], bodies_[l.an])) sys_.condensed.push_back(l);
    else sys_.links.push_back(l);
  }
}

void MoreauJean::build_contacts() {
  // 2. Contacts: frame, own Delassus block (effective masses), law shift.
  const double h = reg_.params.dt, theta = reg_.params.theta;
  const ContactTable& c = reg_.contacts;
  const BodyTable& b = reg_.bodies;
  std::vector<SolverContact>& contacts_ = sys_.contacts;
  const std::vector<SolverBody>& eff_free_ = sys_.free;
  // the records of the last step are written over, every field (constructing them anew would
  // zero each one first, for nothing)
  sys_.rows.clear();
  for (std::uint32_t k = 0; k < c.size(); ++k)
    if (c.law[k] >= 0) sys_.rows.push_back(k);  // no law for this pair of materials: no interaction
  contacts_.resize(sys_.rows.size());
  const std::vector<LawSpec>& laws = reg_.contact_laws.laws;
  auto build = [&](std::size_t a) __attribute__((always_inline)) {
    const std::uint32_t k = sys_.rows[a];
    // built in place: a local copied in stalls the stores that load it (docs/benchmarks.md §8)
    SolverContact& s = contacts_[a];
    s.pn = s.pt = 0.0;
    s.cd = c.cd_body[k].index();
    s.an = c.an_body[k].index();
    s.nx = c.normal[k].x;
    s.ny = c.normal[k].y;
    s.cd_rn = c.cd_rn[k];
    s.cd_rt = c.cd_rt[k];
    s.an_rn = c.an_rn[k];
    s.an_rt = c.an_rt[k];
    s.mu = c.mu[k];
    s.cd_dynamic = is_dynamic(eff_free_[s.cd]);
    s.an_dynamic = is_dynamic(eff_free_[s.an]);
    s.W = delassus_block(s, eff_free_[s.cd], eff_free_[s.an]);
    s.f = coulomb_factors(s.W, s.mu);
    // law shift from the gap at q_m and the relative velocity at the start of the step
    SolverBody cd0{b.vx[s.cd], b.vy[s.cd], b.spin[s.cd]}, an0{b.vx[s.an], b.vy[s.an], b.spin[s.an]};
    double un0, ut0;
    contact_velocity(s, cd0, an0, un0, ut0);
    const LawShift sh = law_shift(laws[static_cast<std::size_t>(c.law[k])], c.gap[k], un0, ut0, h, theta);
    std::memcpy(&s.sn, &sh, sizeof sh);  // (sn, st) in one store: field by field, GCC spills the pair to the stack
    static_assert(offsetof(SolverContact, st) == offsetof(SolverContact, sn) + sizeof(double) &&
                  sizeof(LawShift) == 2 * sizeof(double));
  };
  // each record from its own row only: on the threads for a large system, the same records
  const std::size_t nc = contacts_.size();
  if (const int threads = loop_threads(nc, loops_); threads > 1) {
#pragma omp parallel num_threads(threads)
    {
      const auto [a0, a1] = thread_range(nc);
      for (std::size_t a = a0; a < a1; ++a) build(a);
    }
  } else {
    for (std::size_t a = 0; a < nc; ++a) build(a);
  }
  sys_.status.assign(contacts_.size(), ContactStatus::Open);
}

void MoreauJean::warm_start_contacts() {
  // 4. Warm start: contacts matched with the last step by polygon pair and touching features.
  //    The impulses go into the bodies in the contacts' order, so that each body's sums are
  //    made in a fixed order, whatever the threads. One thread: each contact's lookup, then its
  //    impulses applied, contact after contact. On the threads: warm_start_on_threads.
  const double h = reg_.params.dt;
  const ContactTable& c = reg_.contacts;
  std::vector<SolverBody>& bodies_ = sys_.bodies;
  std::vector<SolverContact>& contacts_ = sys_.contacts;
  const std::size_t n = contacts_.size();
  const std::uint32_t* rows = sys_.rows.data();
  auto key = [&c, rows](std::size_t a) {
    const std::uint32_t row = rows[a];
    return std::pair<std::uint64_t, std::uint32_t>{contact_pair_key(c.candidate[row], c.antagonist[row]),
                                                   c.feature[row]};
  };
  auto take = [&](std::size_t a, std::uint32_t k) {
    contacts_[a].pn = previous_[k].rn * h;
    contacts_[a].pt = previous_[k].rt * h;
  };
  if (const int threads = loop_threads(n, loops_); threads > 1) return warm_start_on_threads(threads, key, take);
  // the bodies of the contact kAhead further on are prefetched, where they are out of a
  // core's L2 cache
  constexpr std::size_t kAhead = 8;
  const bool prefetch = bodies_.size() * sizeof(SolverBody) >= ContactHistoryIndex::kCachedBytes;
  previous_index_.find_range(previous_, 0, n, key, [&](std::size_t a, std::uint32_t k) {
    if (prefetch && a + kAhead < n) {
      __builtin_prefetch(&bodies_[contacts_[a + kAhead].cd]);
      __builtin_prefetch(&bodies_[contacts_[a + kAhead].an]);
    }
    if (k == ContactHistoryIndex::kNone) return;
    take(a, k);
    SolverContact& s = contacts_[a];
    apply_impulse(s, bodies_[s.cd], bodies_[s.an], s.pn, s.pt);
    ++report_.warm_started;
  });
}

// The warm start on the threads. (a) Each thread looks up its range of contacts (its misses
// overlapped: ContactHistoryIndex::find_range) and writes the impulses found into their
// records; it lists each found contact's dynamic ends by the thread that owns their body (the
// bodies in as many ranges as threads). (b) Each thread applies the impulses to its own bodies,
// from the lists of thread 0, 1, … in turn: every body gets its contacts' impulses in contact
// order, the sums of one thread.
template <class Key, class Take>
void MoreauJean::warm_start_on_threads(int threads, const Key& key, const Take& take) {
  std::vector<SolverBody>& bodies_ = sys_.bodies;
  const std::vector<SolverContact>& contacts_ = sys_.contacts;
  const std::size_t nb = bodies_.size(), T = static_cast<std::size_t>(threads);
  warm_ends_.resize(T * T);  // list [s T + u]: the ends thread s found on thread u's bodies
  std::size_t found = 0;
#pragma omp parallel num_threads(threads) reduction(+ : found)
  {
    const std::size_t s = thread_index(), team = thread_count();
    auto owner = [nb, team](std::uint32_t body) { return std::size_t{body} * team / nb; };
    for (std::size_t u = 0; u < team; ++u) warm_ends_[s * T + u].v.clear();
    const auto [a0, a1] = thread_range(contacts_.size());
    previous_index_.find_range(previous_, a0, a1, key, [&](std::size_t a, std::uint32_t k) {
      if (k == ContactHistoryIndex::kNone) return;
      take(a, k);
      ++found;
      const SolverContact& c = contacts_[a];
      const auto end = static_cast<std::uint32_t>(2 * a);  // 2a: the candidate's, 2a + 1: the antagonist's
      if (c.cd_dynamic) warm_ends_[s * T + owner(c.cd)].v.push_back(end);
      if (c.an_dynamic) warm_ends_[s * T + owner(c.an)].v.push_back(end + 1);
    });
#pragma omp barrier
    for (std::size_t from = 0; from < team; ++from)
      for (const std::uint32_t end : warm_ends_[from * T + s].v) {
        const SolverContact& c = contacts_[end / 2];
        const bool on_cd = end % 2 == 0;
        apply_impulse_to(c, bodies_[on_cd ? c.cd : c.an], on_cd, c.pn, c.pt);
      }
  }
  report_.warm_started += found;
}

}  // namespace nscd
