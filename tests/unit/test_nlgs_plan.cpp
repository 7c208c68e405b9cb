// tests/unit/test_nlgs_plan.cpp — a small system's colored sweep planned lane by lane
// (src/solvers/nlgs_plan.hpp):
//   - one share: one run of bundles visits each dynamic body's contacts in the colour-by-colour
//     order, never two live lanes of a bundle on one dynamic body, in fewer bundles;
//   - 2, 3 and 5 shares: the shares' bundles and stops, run in random interleavings of the threads
//     (a simulation: each share a bundle or a stop at a time), visit each dynamic body in the
//     colour-by-colour order sweep after sweep and never deadlock, the sleeper of a ballast layer
//     in share 0's tail; without their waits they do not; the solve gives one thread's numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "nscd/core/thread_share.hpp"
#include "nscd/shared/ballast.hpp"
#include "nscd/shared/samples.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "nscd/solvers/nlgs_blocks.hpp"
#include "nscd/solvers/nlgs_colored.hpp"
#include "nscd/solvers/nlgs_plan.hpp"
#include "squeezed_system.hpp"
#include "threads.hpp"

namespace {

using namespace nscd;
using Visits = std::vector<std::vector<std::uint32_t>>;  // each body's contacts (links: n + l), in visit order

using testing_support::squeezed_system;

/// A ballast layer with its sleeper (its contacts span strips: the overflow), `steps` steps on.
ContactSystem sleeper_system(int steps) {
  scenes::BallastOptions ballast;
  ballast.grading_fraction = 0.4;
  scenes::BallastScene layer = scenes::ballast_sample(ballast);
  scenes::place_sleeper(layer, ballast);
  StepperOptions o;
  MoreauJean mj(layer.scene.reg, o);
  for (int k = 0; k < steps; ++k) mj.step();
  mj.begin_step();
  mj.detect();
  mj.prepare();
  return mj.system();
}

void visit(const ContactSystem& sys, std::uint32_t a, Visits& v) {
  const SolverContact& c = sys.contacts[a];
  if (c.cd_dynamic) v[c.cd].push_back(a);
  if (c.an_dynamic) v[c.an].push_back(a);
}

void visit_links(const ContactSystem& sys, Visits& v) {
  const auto n = static_cast<std::uint32_t>(sys.contacts.size());
  for (std::uint32_t l = 0; l < sys.links.size(); ++l)
    for (std::uint32_t b : {sys.links[l].cd, sys.links[l].an})
      if (is_dynamic(sys.bodies[b])) v[b].push_back(n + l);
}

/// Colour by colour (the layout's order: blocks colour by colour, the overflow last), then the links.
Visits colour_by_colour(const ContactSystem& sys, int sweeps) {
  Visits v(sys.bodies.size());
  for (int s = 0; s < sweeps; ++s) {
    for (std::uint32_t a = 0; a < sys.contacts.size(); ++a) visit(sys, a, v);
    visit_links(sys, v);
  }
  return v;
}

/// The solve's planned shares run `sweeps` sweeps, one share taking one step at a time, chosen at
/// random among those not waiting: a stop (publish, or wait if the other share has not published
/// enough), a bundle, or the tail (share 0: the overflow and the links) and the sweep's end.
/// `waits`: false drops the waits, and a share chosen runs alone to its last sweep's end (the
/// threads as far apart as they can be). False where every share left waits (a deadlock).
bool interleave(const ContactSystem& sys, const NlgsColoredWorkspace& ws, int sweeps, std::mt19937& rng, bool waits,
                Visits& v) {
  const std::size_t T = ws.plan.shares.size();
  const std::uint32_t overflow = ws.block_start[ws.color_start[colored::kOverflow]];
  struct At {
    unsigned sweep = 1;
    std::size_t stop = 0;
    std::uint32_t at = 0;
  };
  std::vector<At> st(T);
  std::vector<std::uint64_t> pub(T, 0);
  auto step = [&](std::size_t u) {
    const SharePlan& p = ws.plan.shares[u];
    At& s = st[u];
    if (s.stop < p.stops.size() && p.stops[s.stop].at == s.at) {
      const ShareStop& stop = p.stops[s.stop];
      if (stop.share == ShareStop::kPublish) {
        pub[u] = std::max<std::uint64_t>(pub[u], std::uint64_t{s.sweep - 1} * p.steps() + s.at);
      } else if (waits) {
        const std::int64_t target = std::int64_t{s.sweep - 1} * ws.plan.shares[stop.share].steps() + stop.need;
        if (std::int64_t(pub[stop.share]) < target) return false;
      }
      ++s.stop;
      return true;
    }
    if (s.at < p.bundles) {
      const MassBundle& b = ws.share_bundles[u][s.at++];
      for (int j = 0; j < ContactBundle::kLanes; ++j)
        if (b.id[j] != ContactBundle::kIdleLane) visit(sys, b.id[j], v);
      return true;
    }
    if (u == 0) {
      for (std::uint32_t a = overflow; a < sys.contacts.size(); ++a) visit(sys, a, v);
      visit_links(sys, v);
    }
    pub[u] = std::uint64_t{s.sweep} * p.steps();
    s = At{s.sweep + 1, 0, 0};
    return true;
  };
  std::vector<std::size_t> order(T);
  for (;;) {
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::shuffle(order.begin(), order.end(), rng);
    bool moved = false, left = false;
    for (std::size_t u : order) {
      if (st[u].sweep > static_cast<unsigned>(sweeps)) continue;
      left = true;
      if ((moved = step(u))) {
        while (!waits && st[u].sweep <= static_cast<unsigned>(sweeps)) step(u);
        break;
      }
    }
    if (!left) return true;
    if (!moved) return false;
  }
}

// what plan_lanes reads to plan the colours of `sys`, laid out in `ws`, as one share
PlanInput one_share(const ContactSystem& sys, const NlgsColoredWorkspace& ws, std::size_t colours) {
  PlanInput in;
  in.contacts = &sys.contacts;
  in.n_bodies = sys.bodies.size();
  in.block_start = ws.block_start.data();
  in.colour_start = ws.color_start.data();
  in.colours = static_cast<unsigned>(colours);
  return in;
}

TEST(NlgsPlan, OneShareKeepsEveryBodysOrderInFewerBundles) {
  ContactSystem sys = squeezed_system(300, SweepOrder::ColoredRows);
  NlgsColoredWorkspace ws;
  const std::size_t colours = color_contacts(sys, ws, SweepOrder::ColoredRows);
  ASSERT_TRUE(ws.cells);
  ASSERT_GE(colours, 4u);
  const std::uint32_t* bs = ws.block_start.data();
  std::vector<MassBundle> by_colour, run;
  std::vector<std::uint32_t> order;
  for (std::size_t k = 0; k < colours; ++k)
    append_bundles(sys.contacts, sys.bodies.data(), bs, ws.color_start[k], ws.color_start[k + 1], by_colour, order);
  LanePlan plan;
  plan_lanes(one_share(sys, ws, colours), plan);
  ASSERT_EQ(plan.shares.size(), 1u);
  EXPECT_TRUE(plan.shares[0].stops.empty());  // one share waits for none
  append_planned(sys.contacts, sys.bodies.data(), bs, plan.shares[0], run);
  EXPECT_EQ(run.size(), plan.shares[0].bundles);
  auto visits = [&](const std::vector<MassBundle>& bundles) {
    Visits seen(sys.bodies.size());
    for (const MassBundle& b : bundles) {
      std::set<std::uint32_t> written;
      for (int j = 0; j < ContactBundle::kLanes; ++j) {
        if (b.id[j] == ContactBundle::kIdleLane) continue;
        const SolverContact& c = sys.contacts[b.id[j]];
        for (auto [body, dynamic] : {std::pair{c.cd, c.cd_dynamic}, std::pair{c.an, c.an_dynamic}})
          if (dynamic) {
            EXPECT_TRUE(written.insert(body).second) << "two lanes of a bundle write body " << body;
          }
        visit(sys, b.id[j], seen);
      }
    }
    return seen;
  };
  const Visits expected = visits(by_colour), got = visits(run);
  std::size_t bodies_seen = 0, live = 0;
  for (std::size_t i = 0; i < sys.bodies.size(); ++i) {
    EXPECT_EQ(got[i], expected[i]) << "body " << i;
    bodies_seen += !expected[i].empty();
  }
  EXPECT_GT(bodies_seen, 200u);
  for (const MassBundle& b : run)
    for (int j = 0; j < ContactBundle::kLanes; ++j) live += b.id[j] != ContactBundle::kIdleLane;
  EXPECT_EQ(live, ws.block_start[ws.color_start[colours]]);  // every contact once
  EXPECT_LT(run.size(), by_colour.size());  // idle lanes filled across colours
}

// One thread sweeps the plan or the colours dealt one after the other, whichever needs fewer
// passes of the lane kernel: the passes each way counted without the bundles are those of the
// bundles, a pass a bundle, or a pass a half that holds a live lane (the AVX2 kernel).
TEST(NlgsPlan, PassesAreCountedAsTheBundlesHoldThem) {
  for (const SweepOrder order : {SweepOrder::ColoredRows, SweepOrder::Colored}) {
    ContactSystem sys = squeezed_system(300, order);
    NlgsColoredWorkspace ws;
    const std::size_t colours = color_contacts(sys, ws, order);
    const std::uint32_t* bs = ws.block_start.data();
    std::vector<MassBundle> by_colour, run;
    std::vector<std::uint32_t> scratch;
    std::uint32_t dealt = 0, dealt_halves = 0;
    for (std::size_t k = 0; k < colours; ++k) {
      append_bundles(sys.contacts, sys.bodies.data(), bs, ws.color_start[k], ws.color_start[k + 1], by_colour, scratch);
      dealt += dealt_passes(bs, ws.color_start[k], ws.color_start[k + 1], false, scratch);
      dealt_halves += dealt_passes(bs, ws.color_start[k], ws.color_start[k + 1], true, scratch);
    }
    LanePlan plan;
    plan_lanes(one_share(sys, ws, colours), plan);
    append_planned(sys.contacts, sys.bodies.data(), bs, plan.shares[0], run);
    auto halves = [](const std::vector<MassBundle>& bundles) {
      std::uint32_t h = 0;
      for (const MassBundle& b : bundles) {
        bool high = false;
        for (int j = ContactBundle::kLanes / 2; j < ContactBundle::kLanes; ++j)
          high |= b.id[j] != ContactBundle::kIdleLane;
        h += high ? 2 : 1;
      }
      return h;
    };
    std::vector<std::pair<std::uint32_t, std::uint32_t>> spans;
    EXPECT_EQ(dealt, by_colour.size());
    EXPECT_EQ(dealt_halves, halves(by_colour));
    EXPECT_EQ(planned_passes(plan.shares[0], false, spans), run.size());
    EXPECT_EQ(planned_passes(plan.shares[0], true, spans), halves(run));
  }
  // by hand: blocks of 1 … 9 contacts dealt to 8 lanes end at 9, 8, 7, 6, 5, 4, 3 and 3 (the
  // 1 after the 2): 9 bundles, the upper halves busy in the first 5
  std::vector<std::uint32_t> block_start{0}, scratch;
  for (std::uint32_t len = 1; len <= 9; ++len) block_start.push_back(block_start.back() + len);
  EXPECT_EQ(dealt_passes(block_start.data(), 0, 9, false, scratch), 9u);
  EXPECT_EQ(dealt_passes(block_start.data(), 0, 9, true, scratch), 14u);
  // a plan whose lanes 4 … 7 are busy at times 0 … 8 and 20, 21 (overlapping runs counted once)
  SharePlan plan;
  plan.bundles = 30;
  plan.runs[0] = {{0, 0, 30}};
  plan.runs[4] = {{1, 0, 5}, {2, 7, 9}};
  plan.runs[5] = {{3, 3, 8}};
  plan.runs[7] = {{4, 20, 22}};
  std::vector<std::pair<std::uint32_t, std::uint32_t>> spans;
  EXPECT_EQ(planned_passes(plan, false, spans), 30u);
  EXPECT_EQ(planned_passes(plan, true, spans), 41u);
}

TEST(NlgsPlan, SharesVisitEveryBodyInOrderInAnyInterleavingOfTheirThreads) {
  NSCD_SKIP_WITHOUT_THREADS();
  if (!lanes_available()) GTEST_SKIP() << "no SIMD lanes here: the sweeps are not planned";
  const std::pair<ContactSystem, SweepOrder> systems[] = {
      {squeezed_system(300, SweepOrder::Colored), SweepOrder::Colored},
      {squeezed_system(300, SweepOrder::ColoredRows), SweepOrder::ColoredRows},
      {squeezed_system(300, SweepOrder::ColoredCells), SweepOrder::ColoredCells},
      {sleeper_system(700), SweepOrder::Colored}};
  std::size_t tails = 0, stops = 0;
  for (const auto& [base, order] : systems) {
    NlgsOptions o;
    o.order = order;
    o.min_sweeps = o.max_sweeps = 12;
    o.anderson = 3;  // (mixed on the threads: from the planned bundles)
    ContactSystem one = base;
    NlgsColoredWorkspace ws1;
    nlgs_iterate_colored(one, o, ws1);
    for (int T : {2, 3, 5}) {
      SCOPED_TRACE(testing::Message() << T << " shares, " << base.contacts.size() << " contacts, " << name_of(order));
      ContactSystem sys = base;
      NlgsColoredWorkspace ws;
      o.threads = T;
      nlgs_iterate_colored(sys, o, ws);
      for (std::size_t i = 0; i < sys.contacts.size(); ++i) {
        ASSERT_EQ(sys.contacts[i].pn, one.contacts[i].pn) << "contact " << i;
        ASSERT_EQ(sys.contacts[i].pt, one.contacts[i].pt) << "contact " << i;
      }
      ASSERT_EQ(ws.plan.shares.size(), static_cast<std::size_t>(T));
      ASSERT_EQ(ws.share_bundles.size(), static_cast<std::size_t>(T));
      for (const SharePlan& p : ws.plan.shares) stops += p.stops.size();
      tails += sys.contacts.size() - ws.block_start[ws.color_start[colored::kOverflow]] + sys.links.size();
      const Visits expected = colour_by_colour(sys, 3);
      std::mt19937 rng(7);
      for (int round = 0; round < 20; ++round) {
        Visits got(sys.bodies.size());
        ASSERT_TRUE(interleave(sys, ws, 3, rng, true, got)) << "deadlock, round " << round;
        ASSERT_EQ(got, expected) << "round " << round;
      }
      bool out_of_order = false;  // the waits are what keeps the order
      for (int round = 0; round < 20 && !out_of_order; ++round) {
        Visits got(sys.bodies.size());
        interleave(sys, ws, 3, rng, false, got);
        out_of_order = got != expected;
      }
      EXPECT_TRUE(out_of_order);
    }
  }
  EXPECT_GT(tails, 0u);  // the sleeper's contacts were among them
  EXPECT_GT(stops, 0u);
}

// The plan in parts on a team of threads, share u on thread u (what a solve on threads does:
// plan_start, the colours with the team meeting between them, plan_share, plan_end), against
// plan_lanes on one thread: the same runs, bundles, stops and fetches, share by share.
TEST(NlgsPlan, ThreadsPlanTheirSharesAsOneThreadPlansThemAll) {
  NSCD_SKIP_WITHOUT_THREADS();
  const std::pair<ContactSystem, SweepOrder> systems[] = {
      {squeezed_system(300, SweepOrder::Colored), SweepOrder::Colored},
      {squeezed_system(300, SweepOrder::ColoredRows), SweepOrder::ColoredRows},
      {squeezed_system(300, SweepOrder::ColoredCells), SweepOrder::ColoredCells},
      {sleeper_system(700), SweepOrder::Colored}};
  std::size_t stops = 0;
  for (const auto& [base, order] : systems) {
    ContactSystem sys = base;
    NlgsColoredWorkspace ws;
    const auto colours = static_cast<unsigned>(color_contacts(sys, ws, order));
    const unsigned parallel = colours - (ws.color_start[colored::kOverflow + 1] > ws.color_start[colored::kOverflow]);
    std::vector<std::uint32_t> tail;
    for (std::uint32_t a = ws.block_start[ws.color_start[colored::kOverflow]]; a < sys.contacts.size(); ++a)
      for (const std::uint32_t i : {sys.contacts[a].cd, sys.contacts[a].an})
        if (is_dynamic(sys.bodies[i])) tail.push_back(i);
    for (const std::size_t T : {2u, 3u}) {
      SCOPED_TRACE(testing::Message() << T << " shares, " << sys.contacts.size() << " contacts, " << name_of(order));
      std::vector<std::uint32_t> split;  // each colour's blocks cut in T ranges
      for (unsigned k = 0; k < parallel; ++k)
        for (std::size_t u = 0; u <= T; ++u) {
          const std::uint32_t b0 = ws.color_start[k], b1 = ws.color_start[k + 1];
          split.push_back(static_cast<std::uint32_t>(b0 + (b1 - b0) * u / T));
        }
      PlanInput in;
      in.contacts = &sys.contacts;
      in.n_bodies = sys.bodies.size();
      in.block_start = ws.block_start.data();
      in.colour_start = ws.color_start.data();
      in.colours = parallel;
      in.shares = T;
      in.split = split.data();
      in.tail = &tail;
      LanePlan one, team;
      plan_lanes(in, one);
      plan_start(in, team);
      std::size_t got = 0;
#pragma omp parallel num_threads(static_cast<int>(T)) reduction(+ : got)
      {
        const std::size_t t = thread_index();
        got = 1;
        if (thread_count() == T) {
          for (unsigned k = 0; k < in.colours; ++k) {
            if (k > 0) {
#pragma omp barrier
            }
            plan_colour(in, team, k, t);
          }
          plan_share(team, t);
        }
      }
      if (got != T) GTEST_SKIP() << "OpenMP gave " << got << " threads of " << T;
      plan_end(in, team);
      for (std::size_t u = 0; u < T; ++u) {
        const SharePlan &a = one.shares[u], &b = team.shares[u];
        EXPECT_EQ(a.span, b.span);
        EXPECT_EQ(a.bundles, b.bundles);
        EXPECT_EQ(a.bundle_at, b.bundle_at);
        EXPECT_EQ(a.fetch, b.fetch);
        ASSERT_EQ(a.stops.size(), b.stops.size()) << "share " << u;
        for (std::size_t i = 0; i < a.stops.size(); ++i)
          EXPECT_TRUE(a.stops[i].at == b.stops[i].at && a.stops[i].share == b.stops[i].share &&
                      a.stops[i].need == b.stops[i].need)
              << "share " << u << ", stop " << i;
        for (int j = 0; j < ContactBundle::kLanes; ++j) {
          ASSERT_EQ(a.runs[j].size(), b.runs[j].size()) << "share " << u << ", lane " << j;
          for (std::size_t r = 0; r < a.runs[j].size(); ++r)
            EXPECT_TRUE(a.runs[j][r].block == b.runs[j][r].block && a.runs[j][r].start == b.runs[j][r].start &&
                        a.runs[j][r].end == b.runs[j][r].end);
        }
        stops += a.stops.size();
      }
    }
  }
  EXPECT_GT(stops, 0u);  // the shares did meet
}

}  // namespace
