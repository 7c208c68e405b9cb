// nscd/solvers/nlgs_plan.hpp — a small system's sweep planned lane by lane: every colour in one
// run of bundles per thread share, and the stops where the shares wait for each other.
//
// Colour by colour, swept one after the other, a colour's last bundles run with idle lanes (a
// share of a small system has a few blocks of each colour, of unequal lengths), and on threads
// the shares meet at every colour: a share's run of a colour waits for the other share's border
// block of the colour before. Planned instead, each block goes to the lane where it can start
// first with each of its contacts after every contact of an earlier colour on one of its dynamic
// bodies — in any share: the shares are planned together, on one clock, each on its own lanes.
// Each body then sees the same updates in the same order as colour after colour (the same
// numbers), a colour's idle lanes take the next colours' blocks, and a share waits only where
// one of its contacts follows another share's contact on a body (ShareStop), until that contact
// is swept: in the same sweep, or, for a body's first contact of a sweep, in the last one.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "nscd/core/own_line.hpp"
#include "nscd/interactions/contact_table.hpp"
#include "nscd/solvers/contact_part.hpp"
#include "nscd/solvers/nlgs_lanes.hpp"

namespace nscd {

/// A stop in a share's sweep of planned bundles, once its bundles 0 … at−1 are swept: the share
/// publishes `at` (share == kPublish), or waits until share `share` has published `need` in this
/// sweep (need > 0), or need + its steps in the last sweep (need ≤ 0). A share's steps: its
/// bundles, then share 0's tail (the overflow colour and the links; an empty step elsewhere).
struct ShareStop {
  static constexpr std::uint32_t kPublish = 0xffffffffu;
  std::uint32_t at, share;
  std::int32_t need;
};

/// One share's planned sweep.
struct SharePlan {
  std::vector<LaneRun> runs[ContactBundle::kLanes];  ///< each lane's blocks, in time order
  std::uint32_t span = 0;  ///< when its last block ends
  std::uint32_t bundles = 0;  ///< the times some lane is busy: its bundles
  std::vector<std::uint32_t> bundle_at;  ///< time t → its bundles before t (t ≤ span)
  std::vector<ShareStop> stops;  ///< in order of `at`; at one bundle, publishes first
  /// the bodies another share wrote last, to fetch at once past the waits at a step: (step, body), by step
  std::vector<std::pair<std::uint32_t, std::uint32_t>> fetch;
  std::uint32_t steps() const { return bundles + 1; }
};

/// What plan_lanes reads: the layout (nlgs_colored.hpp) and the threads' shares.
struct PlanInput {
  const std::vector<SolverContact>* contacts;
  std::size_t n_bodies = 0;
  const std::uint32_t* block_start = nullptr;
  const std::uint32_t* colour_start = nullptr;  ///< colour k: blocks colour_start[k] … colour_start[k+1]−1
  unsigned colours = 0;
  std::size_t shares = 1;
  /// colour k of share u: blocks split[k (shares+1) + u] … split[k (shares+1) + u + 1]−1 (null: one share)
  const std::uint32_t* split = nullptr;
  /// the dynamic bodies of share 0's tail (the overflow's and the links'; null: none)
  const std::vector<std::uint32_t>* tail = nullptr;
};

/// The plan and its scratch (kept from solve to solve: no allocation once warm).
struct LanePlan {
  std::vector<SharePlan> shares;
  /// each body: when the last block planned to touch it ends, that block's share, and when and
  /// where the sweep first touches it
  std::vector<std::uint32_t> ready, last, first_time, first_share;
  struct Wait {
    std::uint32_t share, at, of, need,
        body;  ///< share waits at time `at` until share `of` reaches time `need`, for `body`
  };
  /// Each share's scratch, on lines of its own (the shares may be planned on threads).
  struct Scratch {
    std::vector<std::uint32_t> order;  ///< its blocks of a colour, longest first
    std::uint32_t free_at[ContactBundle::kLanes], load[ContactBundle::kLanes];  ///< its lanes: when free, contacts
    std::vector<Wait> waits;  ///< its contacts' waits for other shares
    std::vector<LaneRun> renumbered[ContactBundle::kLanes];  ///< (swapped with its runs)
  };
  std::vector<OwnLine<Scratch>> scratch;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> spans;  ///< (planned_passes' scratch)
};

/// Plans the shares' sweeps (LanePlan::shares): colour after colour, each share's blocks longest
/// first (a colour's blocks share no dynamic body: their order is free), each to the lane of its
/// share where it can start first with each of its contacts after every contact planned before
/// it on one of its dynamic bodies (one share: once the blocks of those contacts end); then each
/// share's lanes renumbered busiest first (lanes 4 … 7 all idle: the AVX2 sweep skips them) and
/// its stops. The plan depends on the shares, never the numbers.
void plan_lanes(const PlanInput& in, LanePlan& plan);

/// plan_lanes in parts, for a team of threads, share u on thread u: plan_start (one thread),
/// then colour after colour plan_colour for each share, the team meeting after each colour but
/// the last (a colour's blocks touch no body another block of the colour touches, whatever
/// their shares: a colour's shares are planned at once); plan_share for each share once its
/// colours are planned; then, the team met, plan_end (one thread). The same plan as plan_lanes.
void plan_start(const PlanInput& in, LanePlan& plan);
void plan_colour(const PlanInput& in, LanePlan& plan, unsigned k, std::size_t u);
void plan_share(LanePlan& plan, std::size_t u);
void plan_end(const PlanInput& in, LanePlan& plan);

/// The lane kernel's passes over share `plan`'s bundles, as dealt_passes (nlgs_lanes.hpp);
/// `spans` is scratch.
std::uint32_t planned_passes(const SharePlan& plan, bool halves,
                             std::vector<std::pair<std::uint32_t, std::uint32_t>>& spans);

/// Share `plan`'s bundles appended to `out`: bundle i holds each lane's contact at the i-th time
/// some lane is busy (an idle lane: ContactBundle's). MassBundle: with the inverse masses of `bodies`.
template <class Bundle>
void append_planned(const std::vector<SolverContact>& contacts, const SolverBody* bodies,
                    const std::uint32_t* block_start, const SharePlan& plan, std::vector<Bundle>& out);

}  // namespace nscd
