// nscd/solvers/nlgs_mixing.hpp — Anderson mixing of a scene's NLGS sweeps with its phases
// (anderson.hpp, docs/theory.md §9.5b), for the colored sweep and the sequential one alike.
//
// The sweeps it mixes are plain Gauss–Seidel (ω = 1), mixed every kMixPeriod sweeps. After
// kStallChecks checks in a row that do not bring the policy's ratio 10 % below its best since
// the phase began, the solve goes over from mixed sweeps to relaxed ones (ω = relaxation), and
// from relaxed ones back to mixed ones from a fresh history.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "nscd/core/own_line.hpp"
#include "nscd/solvers/anderson.hpp"
#include "nscd/solvers/contact_system.hpp"
#include "nscd/solvers/nlgs.hpp"

namespace nscd {

struct NlgsWorkspace;  // nlgs_sweep.hpp

/// Where a colored solve on threads puts its contacts and bodies in the mixer's arrays: each
/// thread's in a region of pages of its own, so that two cores never write one line, and one
/// core's prefetchers never fetch the other's lines (docs/record/benchmarks-history.md §11.9). Run r: contacts
/// first[r] … first[r+1] − 1 in the mixer's contacts (slots) from first[r] + shift[r]; share
/// u's body slots (NlgsMixingBuffers::body_split) from body_split[u] + body_shift[u].
/// `contacts` and `bodies`: the slots in all; block_shift[b]: the shift of block b's run.
/// Share u's region: contact slots region[u] … region[u+1] − 1 (its runs, then zeros to the
/// next page), body slots body_region[u] … body_region[u+1] − 1; the last run (the overflow)
/// is share 0's, every other run r share r mod (shares).
struct MixSlots {
  std::vector<std::uint32_t> first;
  std::vector<std::int64_t> shift, body_shift, block_shift;
  std::vector<std::size_t> region, body_region;
  std::size_t contacts = 0, bodies = 0;
  /// The share whose region holds run r of `runs` (the last, the overflow, is share 0's).
  static std::size_t share_of(std::size_t r, std::size_t runs, std::size_t shares) {
    return r + 1 == runs ? 0 : r % shares;
  }
};

/// Bodies first … first + count − 1 in the mixer's body slots slot … slot + count − 1: a list of
/// bodies as runs of consecutive numbers, copied in and out without a look-up a body.
struct BodyRun {
  std::uint32_t first, slot, count;
};

/// The mixing's buffers, kept from solve to solve (no allocation once warm).
struct NlgsMixingBuffers {
  AndersonMixer mixer;     ///< the history
  std::vector<double> mu;  ///< each contact's μ (its cone)
  /// The bodies the solve moves (a contact or a link touches them) in the order of v()'s
  /// slots (`touched`: a flag a body, to list them on one thread).
  std::vector<std::uint32_t> bodies;
  std::vector<std::uint8_t> touched;
  /// `bodies` as runs (NlgsMixing::list_runs); on threads, share u's runs are run_split[u] …
  /// run_split[u + 1] − 1.
  std::vector<BodyRun> runs;
  std::vector<std::uint32_t> run_split;
  /// A colored solve on threads: the sums' chunks (AndersonMixer::set_chunks), each share's
  /// first body slot, each thread's moves (one list a thread). (chunk_ends: the chunks' ends
  /// where slots lie between them.)
  std::vector<std::size_t> chunks, chunk_ends;
  std::vector<std::uint32_t> body_split;
  std::vector<OwnLine<std::vector<AndersonMixer::Move>>> moves;
  std::vector<AndersonMixer::Move> merged;  ///< … in contact order
  MixSlots slots;                           ///< … and where the threads' ranges lie
};

class NlgsMixing {
 public:
  static constexpr int kMixPeriod = 4, kStallChecks = 5;

  /// A solve with `opt` (mixing where opt.anderson > 0) on `buf`.
  NlgsMixing(const NlgsOptions& opt, NlgsMixingBuffers& buf)
      : opt_(opt), buf_(buf), mixing_(opt.anderson > 0), omega_(mixing_ ? 1.0 : opt.relaxation) {}
  /// ω of the sweeps between checks: 1 while mixing, else the relaxation.
  double omega() const { return omega_; }
  /// Starts the history from the impulses of `sys` (call once, where opt.anderson > 0), each
  /// contact in the slot `slots` gives it (null: slot = contact, and the bodies the solve moves
  /// listed in body order). A body no contact or link touches keeps its velocity through the
  /// solve, a fixed point of the mixing: it is left out.
  /// With `slots`, only the history is cleared: each share's part is start_share's, on the
  /// thread that mixes the share.
  void start(const ContactSystem& sys, const MixSlots* slots = nullptr);
  void start_share(const ContactSystem& sys, const MixSlots& slots, std::size_t u);
  /// After a checked sweep that did not converge (res.criteria): a stalled phase gives way to
  /// the other one (res.mix_returns counts the returns to mixing).
  void follow(NlgsResult& res);
  /// Whether sweep `sweep` is followed by a mixing.
  bool due(int sweep) const { return mixing_ && sweep % kMixPeriod == 0; }
  /// The mixer's impulses, for a caller that keeps those of contacts before `from` elsewhere.
  double* x() { return buf_.mixer.x(); }
  /// The sweeps' impulses of the contacts from `from` on, the links' and the listed bodies'
  /// velocities into the mixer.
  void gather(const ContactSystem& sys, std::size_t from);
  /// gather and scatter in parts, for threads that each own some contacts and bodies: the
  /// impulses of contacts a0 … a1−1, in the mixer's contacts a0 + shift …; the links'; the
  /// velocities of the bodies of runs r0 … r1−1 (NlgsMixingBuffers::runs), each in its slot +
  /// shift of the mixer's v().
  void gather_contacts(const ContactSystem& sys, std::size_t a0, std::size_t a1, std::ptrdiff_t shift = 0);
  void scatter_contacts(ContactSystem& sys, std::size_t a0, std::size_t a1, std::ptrdiff_t shift = 0);
  void gather_links(const ContactSystem& sys);
  void scatter_links(ContactSystem& sys);
  void gather_bodies(const ContactSystem& sys, std::size_t r0, std::size_t r1, std::ptrdiff_t shift = 0);
  void scatter_bodies(ContactSystem& sys, std::size_t r0, std::size_t r1, std::ptrdiff_t shift = 0);
  /// Bodies ids[s0] … ids[s1 − 1], in slots s0 … s1 − 1, appended to `runs` as runs of
  /// consecutive numbers.
  static void list_runs(const std::uint32_t* ids, std::size_t s0, std::size_t s1, std::vector<BodyRun>& runs);
  /// The cone projection's changes `moves` propagated to the contacts' bodies, in their order.
  static void propagate(ContactSystem& sys, const std::vector<AndersonMixer::Move>& moves);
  /// Mixes; false if the history does not allow it yet (nothing to scatter).
  bool mix() { return buf_.mixer.mix(buf_.mu.data()); }
  /// The mixed impulses of the contacts from `from` on, the links' and the velocities back into
  /// `sys`, the cone projection's changes propagated to the bodies.
  void scatter(ContactSystem& sys, std::size_t from);
  /// Mixings done in this solve (0 without mixing).
  int mixes() const { return opt_.anderson > 0 ? static_cast<int>(buf_.mixer.mixes()) : 0; }

 private:
  const NlgsOptions& opt_;
  void list_bodies(const ContactSystem& sys);
  void start_run(const ContactSystem& sys, std::size_t a0, std::size_t a1, std::ptrdiff_t shift);

  NlgsMixingBuffers& buf_;
  bool mixing_;
  double omega_;
  /// follow()'s state, written at every check on thread 0, apart from ω and the phase that
  /// every thread reads at every sweep
  alignas(64) double best_ratio_ = HUGE_VAL;
  int stalled_ = 0;
};

/// NLGS in a sequential order (fixed, reversed, shuffled, alternating) on a scene, with
/// Anderson mixing (opt.anderson > 0); nlgs_iterate without it.
NlgsResult nlgs_iterate_mixed(ContactSystem& sys, const NlgsOptions& opt, NlgsWorkspace& ws, NlgsMixingBuffers& buf);

}  // namespace nscd
