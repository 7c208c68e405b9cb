// nscd/solvers/nlgs_colored_bodies.cpp — a colored solve on threads with its bodies numbered
// share by share (ColoredSolve, nlgs_colored_solve.hpp): each body's share, the bodies grouped
// by share, and the renumbering of the bodies, the contacts and the links, and back.
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "nscd/solvers/nlgs_colored_solve.hpp"
#include "nscd/solvers/thread_range.hpp"

namespace nscd::colored {

// Each body's share: the last share whose contacts touch it (a body at a border: one of two),
// T where none does.
void ColoredSolve::contact_owners(std::vector<std::uint32_t>& owner) const {
  owner.assign(sys.bodies.size(), static_cast<std::uint32_t>(T));
  for (unsigned k = 0; k < colours; ++k)
    for (std::size_t u = 0; u < T; ++u) {
      const std::uint32_t* s = ws.split.data() + k * (T + 1);
      for (std::uint32_t a = block_start[s[u]]; a < block_start[s[u + 1]]; ++a)
        owner[sys.contacts[a].cd] = owner[sys.contacts[a].an] = static_cast<std::uint32_t>(u);
    }
}

// The owners of contact_owners finished. A body of no contact: with `fill`, the share of the
// body before it (where it lies in memory); without, share 0 if a link moves it, else none (T:
// the mixing leaves it out). Without `fill`, the overflow's and the links' bodies are share 0's
// (thread 0 writes them last: its tail).
void ColoredSolve::finish_owners(std::vector<std::uint32_t>& owner, bool fill) const {
  if (!fill) {
    for (std::uint32_t a = block_start[start[kOverflow]]; a < n; ++a)  // (the overflow: share 0's)
      for (std::uint32_t i : {sys.contacts[a].cd, sys.contacts[a].an}) owner[i] = 0;
    for (const SolverLink& l : sys.links)
      for (std::uint32_t i : {l.cd, l.an}) owner[i] = 0;
    return;
  }
  for (std::size_t i = 0; i < owner.size(); ++i)
    if (owner[i] == T) owner[i] = i > 0 ? owner[i - 1] : 0;
}

// The bodies share by share (`owner`: each body's share, T for none), each share's in their
// order: order[j] is the j-th body, split[u] the first of share u.
void ColoredSolve::group_bodies(const std::vector<std::uint32_t>& owner, std::vector<std::uint32_t>& order,
                                std::vector<std::uint32_t>& split) {
  std::vector<std::uint32_t>& next = ws.scratch.next;
  split.assign(T + 2, 0);
  for (const std::uint32_t u : owner) ++split[u + 1];
  for (std::size_t u = 0; u < T; ++u) split[u + 1] += split[u];
  next.assign(split.begin(), split.end() - 2);
  order.resize(split[T]);
  for (std::size_t i = 0; i < owner.size(); ++i)
    if (owner[i] < T) order[next[owner[i]]++] = static_cast<std::uint32_t>(i);
  split.pop_back();
}

// A system on threads is solved with its bodies numbered share by share (contact_owners),
// each share's in their own order: a core's hardware prefetcher fetches the lines next to those
// it is asked for, and where those are another thread's bodies (the bodies are numbered
// as the scene lists them, row after row across the threads' strips) the two cores take the
// lines from each other at every sweep (docs/record/benchmarks-history.md §11.6). The numbers do not depend
// on where a body lies in memory; restore_bodies() puts them back.
// The owners found here serve the mixing's slots too (set_body_slots), renumbered.
void ColoredSolve::renumber_bodies() {
  std::vector<std::uint32_t>&to_new = ws.body_new, &to_old = ws.body_old, &owner = ws.scratch.placed;
  contact_owners(ws.body_share);
  owner = ws.body_share;
  finish_owners(owner, true);
  group_bodies(owner, to_old, ws.scratch.first);
  to_new.resize(to_old.size());
  for (std::size_t j = 0; j < to_old.size(); ++j) to_new[to_old[j]] = static_cast<std::uint32_t>(j);
  renumber(to_new);
}

void ColoredSolve::restore_bodies() { renumber(ws.body_old); }

// body i becomes body to[i], in the bodies, the contacts and the links: on the threads from
// kLoopParallelMin contacts on, each moving its range of bodies into the scratch, which then
// becomes the bodies (the old order stays there, for the next renumbering), and renaming its
// range of contacts
void ColoredSolve::renumber(const std::vector<std::uint32_t>& to) {
  const int team = loop_threads(n, threads);
  ws.body_copy.resize(sys.bodies.size());
#pragma omp parallel num_threads(team) if (team > 1)
  {
    const auto [i0, i1] = thread_range(sys.bodies.size());
    for (std::size_t i = i0; i < i1; ++i) ws.body_copy[to[i]] = sys.bodies[i];
    const auto [a0, a1] = thread_range(n);
    for (SolverContact* c = sys.contacts.data() + a0; c != sys.contacts.data() + a1; ++c)
      c->cd = to[c->cd], c->an = to[c->an];
  }
  sys.bodies.swap(ws.body_copy);
  for (SolverLink& l : sys.links) l.cd = to[l.cd], l.an = to[l.an];
}

}  // namespace nscd::colored
