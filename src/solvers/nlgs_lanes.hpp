// nscd/solvers/nlgs_lanes.hpp — the colored order's sweeps, several contacts at a time in the
// lanes of SIMD registers.
//
// The blocks of one colour share no dynamic body, so visiting them one after the other, or
// interleaved contact by contact, gives the same numbers. Before a solve, each thread's blocks
// of each colour are dealt to the 8 lanes of bundles (longest first to the least loaded lane,
// then blocks moved or swapped off the longest lane while that shortens it; lane j visits its
// blocks' contacts in order), and the contacts are copied lane by lane:
// a bundle holds the same field of 8 contacts side by side (Box2D v3's wide contact constraints
// are the model), so that one vector load reads a field of 4 contacts. A sweep then visits a
// bundle at a time, in halves of 4 lanes (AVX2) or pairs (SSE2): the contacts' bodies gathered
// (a 4 × 4 transpose; where the bundles are streamed from memory, their inverse masses too, from
// the same cache lines, so that the bundles carry only the contacts' own data), each lane
// computing exactly the scalar visit of nlgs_sweep.hpp — the same operations in the same order,
// the cases of the local solve all evaluated and then selected in the scalar order of precedence
// — and the dynamic bodies scattered back. A checked sweep also
// adds up each lane's convergence sums, in its block's contact order, into the block's sums, and
// records the statuses. The result is bit for bit that of the scalar colored sweep
// (tests/unit/test_nlgs_lanes.cpp).
//
// Kernels: AVX2 (compiled for AVX2 without FMA, since a fused multiply-add rounds once where the
// scalar visit rounds twice; the file is built with -ffp-contract=off; chosen at run time) or
// SSE2, x86-64 only; elsewhere `lanes_available()` is false and the scalar sweep runs. There is
// no AVX-512 kernel: 8 lanes at once ran slower than AVX2 (docs/benchmarks.md §8). The skip
// rule stays scalar.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "nscd/interactions/contact_table.hpp"
#include "nscd/solvers/contact_part.hpp"
#include "nscd/solvers/convergence.hpp"

namespace nscd {

/// kLanes contacts, field by field (lane j = contact id[j]). An idle lane (id kIdleLane) reads
/// a live lane's bodies, writes nothing, and has zero impulses and W_NN = 1 (so it has no share
/// in the sums). A contact's two bodies differ (detection never pairs a body with itself): a
/// lane stores the candidate's row, then the antagonist's. This is the layout of streamed
/// bundles (larger than the last-level cache: stream_bytes()), whose sweeps read the inverse
/// masses 1/m_y, 1/I from the bodies' cache lines, which they load anyway; MassBundle adds them.
struct alignas(64) ContactBundle {
  /// Not zeroed: append_bundles writes every field of every lane (zeroing 1.4 kB a bundle first
  /// was a fifth of its time).
  ContactBundle() {}
  static constexpr int kLanes = 8;
  static constexpr std::uint32_t kIdleLane = 0xffffffffu;
  double nx[kLanes], ny[kLanes], cd_rn[kLanes], cd_rt[kLanes], an_rn[kLanes], an_rt[kLanes];
  double wnn[kLanes], wnt[kLanes], wtt[kLanes], inv_det[kLanes], inv_fwd[kLanes], inv_bwd[kLanes];
  double sn[kLanes], st[kLanes], mu[kLanes], pn[kLanes], pt[kLanes];
  /// bodies, each as its place in the bodies' array in 8-byte words (its index × kBodyWords):
  /// a load's address scales that by 8, where an index would need a shift of its own first
  std::uint32_t cd_word[kLanes], an_word[kLanes];
  std::uint32_t id[kLanes];                                    ///< contacts (ContactSystem order)
  std::uint32_t block[kLanes];                                 ///< each lane's block (its convergence sums)
  std::uint8_t write_cd[kLanes], write_an[kLanes];             ///< live lane and dynamic body
  std::uint8_t block_ends[kLanes];                             ///< the lane's block ends with this contact
  std::uint8_t ends;                                           ///< … the same as a mask (bit j: lane j)
  std::uint8_t idle_high;                                      ///< lanes 4 … 7 all idle: the AVX2 sweep skips them
  /// lanes 4h … 4h+3 all live, between dynamic bodies: the AVX2 sweep stores their rows untested
  std::uint8_t writes_all[kLanes / 4];
  /// checked sweeps: each lane's ContactStatus at its last visit (bytes: the bundle keeps its 20 cache lines)
  std::uint8_t status[kLanes];
};

static_assert(sizeof(ContactBundle) == 20 * 64, "a streamed bundle is 20 cache lines: a sweep streams them all");

/// A body's words (ContactBundle::cd_word), and the bodies a bundle can number: a system with
/// more is swept without lanes.
constexpr std::size_t kWordBytes = 8;
constexpr std::uint32_t kBodyWords = sizeof(SolverBody) / kWordBytes;
constexpr std::size_t kMaxLaneBodies = (std::size_t{1} << 32) / kBodyWords;
static_assert(sizeof(SolverBody) == kBodyWords * kWordBytes);
/// The body whose place is `word` (ContactBundle::cd_word); Body: SolverBody or const SolverBody.
template <class Body>
inline Body& body_at(Body* bodies, std::uint32_t word) {
  static_assert(std::is_same_v<std::remove_const_t<Body>, SolverBody>);
  using Byte = std::conditional_t<std::is_const_v<Body>, const char, char>;
  return *reinterpret_cast<Body*>(reinterpret_cast<Byte*>(bodies) + std::size_t{word} * kWordBytes);
}

/// The bundles of a system that fits the cache: the inverse masses come with the contacts (one
/// stream of loads; 1/m_x comes with the velocity row), 3–4 % faster there than from the bodies.
/// Streamed, these four more cache lines per bundle made a sweep about a third slower than
/// reading the masses from the bodies, even unread (docs/benchmarks.md §2.2).
struct alignas(64) MassBundle : ContactBundle {
  /// Not zeroed either: without a constructor of its own, `emplace_back()` value-initialises,
  /// which zeroes the whole bundle first (a third of append_bundles' time on the LMGC90 case).
  MassBundle() {}
  double cd_imy[kLanes], cd_ii[kLanes], an_imy[kLanes], an_ii[kLanes];
};

/// True where a lane kernel exists (x86-64).
bool lanes_available();
/// Lanes of the widest kernel this CPU runs: 4 (AVX2) or 2 (SSE2); 0 where none.
int lane_width();

/// Deals blocks b0 … b1−1 (block b: contacts block_start[b] … block_start[b+1]−1, no two
/// blocks sharing a dynamic body) to the lanes, so that they end together, and appends their bundles to
/// `out`; `order` is scratch. MassBundle: with the inverse masses of `bodies`.
template <class Bundle>
void append_bundles(const std::vector<SolverContact>& contacts, const SolverBody* bodies,
                    const std::uint32_t* block_start, std::uint32_t b0, std::uint32_t b1, std::vector<Bundle>& out,
                    std::vector<std::uint32_t>& order);

/// The lane kernel's passes over the bundles append_bundles would make of blocks b0 … b1−1:
/// their bundles, and with `halves` (the AVX2 kernel, which skips a bundle's lanes 4 … 7 where
/// they are all idle) their busy upper halves too. `order` is scratch.
std::uint32_t dealt_passes(const std::uint32_t* block_start, std::uint32_t b0, std::uint32_t b1, bool halves,
                           std::vector<std::uint32_t>& order);

/// A block's contacts in one lane of a run of bundles: from the bundle at `start` to the one
/// before `end` (nlgs_plan.hpp).
struct LaneRun {
  std::uint32_t block, start, end;
};

/// The lanes' running convergence sums of a checked sweep between two calls of sweep_bundles
/// that split it inside a block (zero at the sweep's start; opaque).
struct LaneCarry {
  alignas(32) double v[8 * ContactBundle::kLanes] = {};
};

/// One sweep of bundles [first, last): nlgs_visit for every live lane, impulses relaxed by ω
/// between checks. A checked sweep (ω = 1) also writes each block's convergence sums into
/// block_sums[block] and each lane's status into the bundle (bundle_results_to_contacts reads them out);
/// with `carry`, its lanes' sums start from it and are left in it.
/// `width`: the widest kernel to use, 4 or 2 (this CPU's widest if wider). Nothing happens where
/// !lanes_available().
void sweep_bundles(MassBundle* first, MassBundle* last, SolverBody* bodies, double omega, bool check,
                   CriteriaAccumulator* block_sums, int width = 4, LaneCarry* carry = nullptr);
/// … streamed bundles: the same numbers, each bundle prefetched two bundles ahead and the inverse
/// masses read from the bodies.
void sweep_bundles(ContactBundle* first, ContactBundle* last, SolverBody* bodies, double omega, bool check,
                   CriteriaAccumulator* block_sums, int width = 4, LaneCarry* carry = nullptr);

/// After the solve: the bundles' impulses into the contacts, and the statuses of their last
/// checked sweep into status[id]; ContactBundle or MassBundle.
template <class Bundle>
void bundle_results_to_contacts(const Bundle* first, const Bundle* last, SolverContact* contacts,
                                ContactStatus* status);

/// The bundles' impulses into x (contact id of block b at slot s = id + block_shift[b], or id
/// where block_shift is null: x[2 s] = P_N, x[2 s + 1] = P_T) and back, for Anderson mixing
/// (anderson.hpp); idle lanes are left alone.
template <class Bundle>
void bundle_impulses_to(const Bundle* first, const Bundle* last, double* x, const std::int64_t* block_shift = nullptr);
template <class Bundle>
void bundle_impulses_from(Bundle* first, Bundle* last, const double* x, const std::int64_t* block_shift = nullptr);

/// Bundles (all threads' together) above which a sweep streams them from memory rather than
/// finding them in the last-level cache, and ContactBundle replaces MassBundle: half the L3 that
/// Linux reports for the first CPU (the bodies and the contacts need room too), 16 MiB where it
/// says nothing (docs/benchmarks.md §2.2 has the measurements on both sides).
std::size_t stream_bytes();

}  // namespace nscd
