// nscd/solvers/nlgs_mixing.cpp — see nlgs_mixing.hpp.
#include "nscd/solvers/nlgs_mixing.hpp"

#include <algorithm>
#include <numeric>

#include "nscd/solvers/nlgs_sweep.hpp"
#include "nscd/solvers/scene_backend.hpp"

namespace nscd {
namespace {

// the slot of entry i of a run shifted by `shift` (never negative)
std::size_t slot(std::size_t i, std::ptrdiff_t shift) {
  return static_cast<std::size_t>(static_cast<std::ptrdiff_t>(i) + shift);
}

}  // namespace

// the bodies a contact or a link touches, in body order
void NlgsMixing::list_bodies(const ContactSystem& sys) {
  std::vector<std::uint8_t>& touched = buf_.touched;
  touched.assign(sys.bodies.size(), 0);
  for (const SolverContact& c : sys.contacts) touched[c.cd] = touched[c.an] = 1;
  for (const SolverLink& l : sys.links) touched[l.cd] = touched[l.an] = 1;
  buf_.bodies.clear();
  for (std::size_t i = 0; i < touched.size(); ++i)
    if (touched[i]) buf_.bodies.push_back(static_cast<std::uint32_t>(i));
  buf_.runs.clear();
  list_runs(buf_.bodies.data(), 0, buf_.bodies.size(), buf_.runs);
}

void NlgsMixing::list_runs(const std::uint32_t* ids, std::size_t s0, std::size_t s1, std::vector<BodyRun>& runs) {
  for (std::size_t s = s0; s < s1; ++s) {
    BodyRun* last = runs.empty() ? nullptr : &runs.back();
    if (last && s > s0 && ids[s] == last->first + last->count)
      ++last->count;
    else
      runs.push_back({ids[s], static_cast<std::uint32_t>(s), 1});
  }
}

void NlgsMixing::start(const ContactSystem& sys, const MixSlots* slots) {
  const std::size_t n = sys.contacts.size();
  if (!slots) list_bodies(sys);
  const std::size_t nc = slots ? slots->contacts : n, nb = slots ? slots->bodies : buf_.bodies.size();
  AndersonMixer& mixer = buf_.mixer;
  mixer.start(nc, sys.links.size(), 3 * nb, opt_.anderson);
  buf_.mu.resize(nc);
  if (slots) return mixer.begin_history();
  start_run(sys, 0, n, 0);
  gather_links(sys);
  mixer.begin();
}

// contacts a0 … a1−1 of a run: their impulses and μ into their slots
void NlgsMixing::start_run(const ContactSystem& sys, std::size_t a0, std::size_t a1, std::ptrdiff_t shift) {
  gather_contacts(sys, a0, a1, shift);
  double* mu = buf_.mu.data() + slot(a0, shift);
  for (std::size_t a = a0; a < a1; ++a) mu[a - a0] = sys.contacts[a].mu;
}

// Share u's part of start(): its runs' impulses and μ, zeros in the slots after them (impulses
// and velocities, to the next region), its impulses remembered as the first iterate; share 0
// the links' too. Written by the thread that mixes them, their lines are in its core's cache
// from the start (written on thread 0 for every share, each solve's first mixing on the other
// threads took them from thread 0's core).
void NlgsMixing::start_share(const ContactSystem& sys, const MixSlots& s, std::size_t u) {
  AndersonMixer& mixer = buf_.mixer;
  const std::size_t shares = s.region.size() - 1, runs = s.shift.size();
  std::size_t end = s.region[u];
  for (std::size_t r = 0; r < runs; ++r)
    if (MixSlots::share_of(r, runs, shares) == u) {
      start_run(sys, s.first[r], s.first[r + 1], s.shift[r]);
      end = slot(s.first[r + 1], s.shift[r]);
    }
  double* x = mixer.x();
  std::fill(x + 2 * end, x + 2 * s.region[u + 1], 0.0);
  const std::size_t v_end = 3 * (s.body_region[u] + buf_.body_split[u + 1] - buf_.body_split[u]);
  std::fill(mixer.v() + v_end, mixer.v() + 3 * s.body_region[u + 1], 0.0);
  mixer.begin_range(2 * s.region[u], 2 * s.region[u + 1]);
  if (u != 0) return;
  gather_links(sys);
  mixer.begin_range(2 * mixer.contacts(), mixer.impulses());
}

// the mixing stalls where the statuses keep changing, relaxed sweeps can settle into a cycle
// that repeats the same changes: each phase gives way to the other where it stalls
void NlgsMixing::follow(NlgsResult& res) {
  const double ratio = policy_ratio(res.criteria, opt_.policy);
  if (ratio < 0.9 * best_ratio_) {
    best_ratio_ = ratio;
    stalled_ = 0;
  } else if (++stalled_ >= kStallChecks) {
    mixing_ = !mixing_;
    omega_ = mixing_ ? 1.0 : opt_.relaxation;
    if (mixing_) {
      buf_.mixer.restart_at_next();
      ++res.mix_returns;
    }
    best_ratio_ = HUGE_VAL;
    stalled_ = 0;
  }
}

void NlgsMixing::gather_contacts(const ContactSystem& sys, std::size_t a0, std::size_t a1, std::ptrdiff_t shift) {
  double* x = buf_.mixer.x() + 2 * slot(a0, shift);
  for (std::size_t a = a0; a < a1; ++a, x += 2) {
    x[0] = sys.contacts[a].pn;
    x[1] = sys.contacts[a].pt;
  }
}

void NlgsMixing::scatter_contacts(ContactSystem& sys, std::size_t a0, std::size_t a1, std::ptrdiff_t shift) {
  const double* x = buf_.mixer.x() + 2 * slot(a0, shift);
  for (std::size_t a = a0; a < a1; ++a, x += 2) {
    sys.contacts[a].pn = x[0];
    sys.contacts[a].pt = x[1];
  }
}

void NlgsMixing::gather_links(const ContactSystem& sys) {
  double* x = buf_.mixer.x() + 2 * buf_.mixer.contacts();
  for (std::size_t l = 0; l < sys.links.size(); ++l) x[l] = sys.links[l].p;
}

void NlgsMixing::scatter_links(ContactSystem& sys) {
  const double* x = buf_.mixer.x() + 2 * buf_.mixer.contacts();
  for (std::size_t l = 0; l < sys.links.size(); ++l) sys.links[l].p = x[l];
}

void NlgsMixing::gather_bodies(const ContactSystem& sys, std::size_t r0, std::size_t r1, std::ptrdiff_t shift) {
  for (std::size_t r = r0; r < r1; ++r) {
    const BodyRun& run = buf_.runs[r];
    double* v = buf_.mixer.v() + 3 * slot(run.slot, shift);
    const SolverBody* b = sys.bodies.data() + run.first;
    for (std::uint32_t i = 0; i < run.count; ++i, v += 3) {
      v[0] = b[i].vx;
      v[1] = b[i].vy;
      v[2] = b[i].w;
    }
  }
}

void NlgsMixing::scatter_bodies(ContactSystem& sys, std::size_t r0, std::size_t r1, std::ptrdiff_t shift) {
  for (std::size_t r = r0; r < r1; ++r) {
    const BodyRun& run = buf_.runs[r];
    const double* v = buf_.mixer.v() + 3 * slot(run.slot, shift);
    SolverBody* b = sys.bodies.data() + run.first;
    for (std::uint32_t i = 0; i < run.count; ++i, v += 3) {
      b[i].vx = v[0];
      b[i].vy = v[1];
      b[i].w = v[2];
    }
  }
}

void NlgsMixing::propagate(ContactSystem& sys, const std::vector<AndersonMixer::Move>& moves) {
  for (const AndersonMixer::Move& m : moves) {
    const SolverContact& c = sys.contacts[m.contact];
    apply_impulse(c, sys.bodies[c.cd], sys.bodies[c.an], m.dpn, m.dpt);
  }
}

void NlgsMixing::gather(const ContactSystem& sys, std::size_t from) {
  gather_contacts(sys, from, sys.contacts.size());
  gather_links(sys);
  gather_bodies(sys, 0, buf_.runs.size());
}

void NlgsMixing::scatter(ContactSystem& sys, std::size_t from) {
  scatter_contacts(sys, from, sys.contacts.size());
  scatter_links(sys);
  scatter_bodies(sys, 0, buf_.runs.size());
  propagate(sys, buf_.mixer.moved());
}

// nlgs_iterate's sweeps (sequential_sweeps, nlgs_sweep.hpp) with the mixing's ω between checks,
// its phases after each unconverged check and a mixing every kMixPeriod sweeps
NlgsResult nlgs_iterate_mixed(ContactSystem& sys, const NlgsOptions& opt, NlgsWorkspace& ws, NlgsMixingBuffers& buf) {
  NlgsResult res;
  const std::size_t n = sys.contacts.size();
  if (n == 0 && sys.links.empty()) {
    res.converged = true;
    return res;
  }
  SceneBackend be(sys);
  NlgsMixing mixing(opt, buf);
  mixing.start(sys);
  const auto omega = [&mixing] { return mixing.omega(); };
  res = sequential_sweeps(be, opt, ws, omega, [&](int sweep, bool check, NlgsResult& r) {
    if (check) mixing.follow(r);
    if (mixing.due(sweep)) {
      mixing.gather(sys, 0);
      if (mixing.mix()) mixing.scatter(sys, 0);
    }
  });
  res.mixes = mixing.mixes();
  return res;
}

}  // namespace nscd
