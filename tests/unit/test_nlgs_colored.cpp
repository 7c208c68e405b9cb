// tests/unit/test_nlgs_colored.cpp — the colored NLGS order's layout (src/solvers/nlgs_colored.hpp)
// on the system of a running scene: a compressed field of pentagons (bench_nlgs's scene, no
// gravity, every grain moving toward the centre), prepared for a step.
//   - the colouring: no two blocks of a colour (overflow apart) share a dynamic body, and every
//     contact is in exactly one block; bodies with positions give strips or cells of two
//     colours (a row) at any size and in any contact order, the same layout on 1, 2 and 3 threads;
//   - the cells: the colored sweep gives, bit for bit, the numbers of the cells swept one after
//     the other; their median and 95th percentile (two_ranks) are those of a sort.
// The steps in the colored order (threads, answer, relaxation): test_nlgs_colored_steps.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <climits>
#include <cstdint>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "nscd/solvers/moreau_jean.hpp"
#include "nscd/solvers/nlgs_blocks.hpp"
#include "nscd/solvers/nlgs_colored.hpp"
#include "nscd/solvers/scene_backend.hpp"
#include "compressed_field.hpp"
#include "nlgs_colored_fixtures.hpp"
#include "threads.hpp"

namespace {

using namespace nscd;

using nlgs_colored_fixtures::colored;
using testing_support::compressed_field;

/// `sys` is `before` laid out by color_contacts: the same contacts (by registry row), each in
/// exactly one block (blocks are consecutive ranges covering all contacts), and no two blocks
/// of a colour (overflow apart) share a dynamic body.
void expect_a_valid_colouring(const ContactSystem& before, const ContactSystem& sys, const NlgsColoredWorkspace& ws) {
  const std::size_t n = sys.contacts.size();
  ASSERT_EQ(n, before.contacts.size());
  ASSERT_EQ(sys.rows.size(), n);
  std::vector<std::uint32_t> where(n, UINT32_MAX);  // registry row -> index before (rows are distinct)
  std::vector<std::uint32_t> sorted_rows = before.rows;
  std::sort(sorted_rows.begin(), sorted_rows.end());
  for (std::size_t a = 0; a < n; ++a) {
    const auto r = static_cast<std::size_t>(std::lower_bound(sorted_rows.begin(), sorted_rows.end(), before.rows[a]) - sorted_rows.begin());
    where[r] = static_cast<std::uint32_t>(a);
  }
  for (std::size_t a = 0; a < n; ++a) {
    const auto it = std::lower_bound(sorted_rows.begin(), sorted_rows.end(), sys.rows[a]);
    ASSERT_TRUE(it != sorted_rows.end() && *it == sys.rows[a]) << "contact " << a;
    const SolverContact& was = before.contacts[where[static_cast<std::size_t>(it - sorted_rows.begin())]];
    ASSERT_EQ(sys.contacts[a].cd, was.cd);
    ASSERT_EQ(sys.contacts[a].an, was.an);
    ASSERT_EQ(sys.contacts[a].sn, was.sn);
    ASSERT_EQ(sys.contacts[a].pn, was.pn);
  }
  ASSERT_EQ(ws.block_start.size(), ws.color_start.back() + 1u);
  ASSERT_EQ(ws.block_start.front(), 0u);
  ASSERT_EQ(ws.block_start.back(), n);
  for (std::size_t b = 0; b + 1 < ws.block_start.size(); ++b) ASSERT_LE(ws.block_start[b], ws.block_start[b + 1]);
  for (std::size_t k = 0; k + 2 < ws.color_start.size(); ++k) {  // colours 0 … 62 (the last is the overflow)
    std::set<std::uint32_t> bodies;
    for (std::uint32_t b = ws.color_start[k]; b < ws.color_start[k + 1]; ++b) {
      std::set<std::uint32_t> mine;
      for (std::uint32_t a = ws.block_start[b]; a < ws.block_start[b + 1]; ++a) {
        if (sys.contacts[a].cd_dynamic) mine.insert(sys.contacts[a].cd);
        if (sys.contacts[a].an_dynamic) mine.insert(sys.contacts[a].an);
      }
      for (std::uint32_t body : mine) EXPECT_TRUE(bodies.insert(body).second) << "colour " << k << " body " << body;
    }
  }
}

/// The system of a scene's first step, prepared (fixed order: not yet laid out).
ContactSystem prepared_system(Registry reg, int steps_before = 0) {
  StepperOptions o;
  MoreauJean mj(reg, o);
  for (int k = 0; k < steps_before; ++k) mj.step();
  mj.begin_step();
  mj.detect();
  mj.prepare();
  return mj.system();
}

/// Colouring `sys` again (it was laid out with `ws`) moves nothing: same order, same blocks.
/// colored-cells: the cells, in the order they are swept one after the other (`laid`, positions
/// in the layout), go from the top down, and each cell's contacts upward.
void expect_cells_from_the_top_each_upward(const ContactSystem& sys, const NlgsColoredWorkspace& ws,
                                           const std::vector<std::uint32_t>& laid) {
  auto height = [&](std::uint32_t a) {
    const SolverContact& c = sys.contacts[a];
    if (c.cd_dynamic && c.an_dynamic) return 0.5 * (sys.body_y[c.cd] + sys.body_y[c.an]);
    return c.cd_dynamic ? sys.body_y[c.cd] : sys.body_y[c.an];
  };
  const std::uint32_t overflow = ws.color_start[ws.color_start.size() - 2];
  std::vector<double> mean;  // each cell's mean height, in sweep order
  for (const std::uint32_t b : laid) {
    if (b >= overflow || ws.block_start[b + 1] == ws.block_start[b]) continue;
    double sum = 0.0;
    for (std::uint32_t a = ws.block_start[b]; a < ws.block_start[b + 1]; ++a) {
      sum += height(a);
      if (a > ws.block_start[b]) {
        ASSERT_LE(height(a - 1), height(a)) << "cell " << b << ", contact " << a;
      }
    }
    mean.push_back(sum / (ws.block_start[b + 1] - ws.block_start[b]));
  }
  ASSERT_GE(mean.size(), 8u);
  const std::size_t q = mean.size() / 4;  // the first quarter of the cells lies above the last
  EXPECT_GT(*std::min_element(mean.begin(), mean.begin() + q), *std::max_element(mean.end() - q, mean.end()));
}

void expect_recolouring_moves_nothing(const ContactSystem& sys, const NlgsColoredWorkspace& ws,
                                      SweepOrder order = SweepOrder::Colored) {
  ContactSystem again = sys;
  NlgsColoredWorkspace fresh;
  color_contacts(again, fresh, order);
  EXPECT_EQ(again.rows, sys.rows);
  EXPECT_EQ(fresh.block_start, ws.block_start);
}

TEST(NlgsColored, BlocksOfAColourShareNoDynamicBody) {
  // a large system without positions (a dumped problem): blocks of consecutive contacts
  ContactSystem before = prepared_system(compressed_field(4000).reg);
  before.body_x.clear();
  before.body_y.clear();
  ContactSystem sys = before;
  NlgsColoredWorkspace ws;
  const std::size_t colours = color_contacts(sys, ws);
  ASSERT_GT(sys.contacts.size(), 8192u);
  EXPECT_EQ(ws.arranged, &sys);
  EXPECT_GE(colours, 2u);
  EXPECT_LE(colours, 8u);  // in detection order, a block meets only its neighbours
  EXPECT_FALSE(ws.cells || ws.strips);
  expect_a_valid_colouring(before, sys, ws);
  expect_recolouring_moves_nothing(sys, ws);  // blocks by rank of registry row
}

/// `sys`'s contacts (with their statuses) in a shuffled order, their registry rows in order: a
/// registry whose rows follow no layer of the field.
ContactSystem shuffled(ContactSystem sys) {
  std::vector<std::uint32_t> p(sys.contacts.size());
  std::iota(p.begin(), p.end(), 0u);
  std::shuffle(p.begin(), p.end(), std::mt19937(2006));
  ContactSystem out = sys;
  for (std::size_t a = 0; a < p.size(); ++a) {
    out.contacts[a] = sys.contacts[p[a]];
    if (sys.status.size() == p.size()) out.status[a] = sys.status[p[a]];
  }
  return out;
}

TEST(NlgsColored, ALargeFieldInAnyOrderIsCutIntoTwoColoursAStepAndSolvedAlikeOnTwoThreads) {
  // From 8192 contacts on too, bodies with positions: strips (or cells), whatever the contacts'
  // order. Blocks of consecutive contacts in a scattered order each touch bodies all over the
  // field and need many colours, few blocks each: a barrier per colour, and a colour of one
  // block leaves the other thread idle (a 7,000-grain deposit got 9–10 colours of 1–11 blocks).
  const ContactSystem before = shuffled(prepared_system(compressed_field(4000).reg));
  ASSERT_GT(before.contacts.size(), 8192u);
  NlgsColoredWorkspace ws;
  ContactSystem sys = before;
  const std::size_t colours = color_contacts(sys, ws);
  EXPECT_TRUE(ws.strips);
  EXPECT_GE(colours, 2u);
  EXPECT_LE(colours, 3u);
  EXPECT_GE(ws.color_start[1] - ws.color_start[0], 8u);  // many strips per colour
  const std::size_t overflow = ws.block_start.back() - ws.block_start[ws.color_start[ws.color_start.size() - 2]];
  EXPECT_LT(overflow, sys.contacts.size() / 20);
  expect_a_valid_colouring(before, sys, ws);
  expect_recolouring_moves_nothing(sys, ws);
  ContactSystem rows = before;
  const std::size_t row_colours = color_contacts(rows, ws, SweepOrder::ColoredRows);
  EXPECT_TRUE(ws.cells);
  EXPECT_LE(row_colours, 63u);
  EXPECT_GE(ws.color_start[1] - ws.color_start[0], 4u);  // several cells per colour
  expect_a_valid_colouring(before, rows, ws);
  // the same contacts without positions: blocks of consecutive contacts, many colours
  ContactSystem bare = before;
  bare.body_x.clear();
  bare.body_y.clear();
  const std::size_t bare_colours = color_contacts(bare, ws);
  EXPECT_FALSE(ws.strips || ws.cells);
  EXPECT_GT(bare_colours, 8u);
  expect_a_valid_colouring(before, bare, ws);
  // … which still give the same numbers on one and two threads
  NSCD_SKIP_WITHOUT_THREADS();
  for (const SweepOrder order :
       {SweepOrder::Colored, SweepOrder::ColoredRows, SweepOrder::ColoredCells})  // the same layout on threads
    for (int threads : {2, 3}) {
      ContactSystem one_thread = before, many = before;
      NlgsColoredWorkspace w1, w2;
      EXPECT_EQ(color_contacts(one_thread, w1, order, 1), color_contacts(many, w2, order, threads));
      EXPECT_EQ(one_thread.rows, many.rows);
      EXPECT_EQ(w1.block_start, w2.block_start);
      EXPECT_EQ(w1.color_start, w2.color_start);
      EXPECT_EQ(w1.block_id, w2.block_id);
    }
  NlgsOptions o = colored(1);
  ContactSystem one = bare, two = bare;
  NlgsColoredWorkspace w1, w2;
  const NlgsResult r1 = nlgs_iterate_colored(one, o, w1);
  o.threads = 2;
  const NlgsResult r2 = nlgs_iterate_colored(two, o, w2);
  EXPECT_EQ(r1.sweeps, r2.sweeps);
  ASSERT_EQ(one.contacts.size(), two.contacts.size());
  std::size_t pushing = 0;
  for (std::size_t a = 0; a < one.contacts.size(); ++a) {
    ASSERT_EQ(one.contacts[a].pn, two.contacts[a].pn) << "contact " << a;
    ASSERT_EQ(one.contacts[a].pt, two.contacts[a].pt) << "contact " << a;
    pushing += one.contacts[a].pn > 0.0;
  }
  EXPECT_GT(pushing, one.contacts.size() / 4);
  for (std::size_t i = 0; i < one.bodies.size(); ++i) ASSERT_EQ(one.bodies[i].vx, two.bodies[i].vx) << "body " << i;
}

TEST(NlgsColored, StripsColouredOnThreadsAreTheGreedyColours) {
  // A large system's strips are coloured on threads from which neighbours share a body
  // (strip_colours); the colours are those of the greedy colouring on one thread, also where
  // neighbouring strips share no body (the contacts of a band of the field taken out: two
  // strips of colour 0 side by side).
  const ContactSystem field = prepared_system(compressed_field(6000).reg);
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const SolverContact& c : field.contacts) lo = std::min(lo, field.body_x[c.cd]), hi = std::max(hi, field.body_x[c.cd]);
  ContactSystem gapped = field;  // without the contacts of bodies in two bands across x
  gapped.contacts.clear();
  gapped.status.clear();
  for (std::size_t a = 0; a < field.contacts.size(); ++a) {
    const SolverContact& c = field.contacts[a];
    auto in_band = [&](std::uint32_t i) {
      const double u = (field.body_x[i] - lo) / (hi - lo);
      return (u > 0.30 && u < 0.36) || (u > 0.62 && u < 0.66);
    };
    if (in_band(c.cd) || in_band(c.an)) continue;
    gapped.contacts.push_back(c);
    if (!field.status.empty()) gapped.status.push_back(field.status[a]);
  }
  gapped.rows.clear();
  ASSERT_GT(gapped.contacts.size(), 8192u);
  NSCD_SKIP_WITHOUT_THREADS();
  for (const ContactSystem* sys : {&field, static_cast<const ContactSystem*>(&gapped)}) {
    ContactSystem one = *sys;
    NlgsColoredWorkspace w1;
    color_contacts(one, w1, SweepOrder::Colored, 1);
    ASSERT_TRUE(w1.strips);
    bool side_by_side = false;  // two strips next to each other in colour 0
    for (std::uint32_t b = w1.color_start[0]; b + 1 < w1.color_start[1]; ++b)
      side_by_side = side_by_side || w1.block_key[b + 1] == w1.block_key[b] + 1;
    EXPECT_EQ(side_by_side, sys == &gapped);
    for (int threads : {2, 3}) {
      ContactSystem many = *sys;
      NlgsColoredWorkspace w2;
      color_contacts(many, w2, SweepOrder::Colored, threads);
      EXPECT_EQ(w1.color_start, w2.color_start) << threads << " threads";
      EXPECT_EQ(w1.block_id, w2.block_id) << threads << " threads";
      EXPECT_EQ(w1.block_start, w2.block_start) << threads << " threads";
    }
  }
}

TEST(NlgsColored, ASmallFieldIsCutIntoStripsOfTwoColours) {
  // below 8192 contacts, bodies with positions: strips across the longer side, two apart
  // sharing no body, so two colours (and an overflow for the rare contact spanning more)
  const ContactSystem before = prepared_system(compressed_field(300).reg);
  ContactSystem sys = before;
  ASSERT_GT(sys.contacts.size(), 256u);
  NlgsColoredWorkspace ws;
  const std::size_t colours = color_contacts(sys, ws);
  EXPECT_TRUE(ws.strips);
  EXPECT_FALSE(ws.cells);
  EXPECT_GE(colours, 2u);
  EXPECT_LE(colours, 3u);
  const std::size_t overflow = ws.block_start.back() - ws.block_start[ws.color_start[ws.color_start.size() - 2]];
  EXPECT_GE(ws.color_start[1] - ws.color_start[0], 2u);  // several strips per colour
  EXPECT_LT(overflow, sys.contacts.size() / 20);
  expect_a_valid_colouring(before, sys, ws);
  expect_recolouring_moves_nothing(sys, ws);
  // without positions (a dumped problem): blocks of consecutive contacts
  ContactSystem bare = before;
  bare.body_x.clear();
  bare.body_y.clear();
  color_contacts(bare, ws);
  EXPECT_FALSE(ws.strips || ws.cells);
  expect_a_valid_colouring(before, bare, ws);
  // a body without a finite position: no strips either (nothing undefined)
  ContactSystem lost = before;
  lost.body_x[lost.contacts[0].cd_dynamic ? lost.contacts[0].cd : lost.contacts[0].an] = std::nan("");
  color_contacts(lost, ws);
  EXPECT_FALSE(ws.strips || ws.cells);
  expect_a_valid_colouring(before, lost, ws);
}

TEST(NlgsColored, ASmallFieldIsCutIntoCellsSweptRowByRow) {
  // below 8192 contacts, bodies with positions: a grid of cells, two colours a row (even
  // columns, odd columns), blocks sharing a body swept in row order; an overflow for the rare
  // contact spanning more than a cell
  const ContactSystem before = prepared_system(compressed_field(300).reg);
  ContactSystem sys = before;
  ASSERT_GT(sys.contacts.size(), 256u);
  NlgsColoredWorkspace ws;
  const std::size_t colours = color_contacts(sys, ws, SweepOrder::ColoredRows);
  EXPECT_TRUE(ws.cells);
  EXPECT_FALSE(ws.strips);
  EXPECT_GE(colours, 4u);   // more than one row
  EXPECT_LE(colours, 63u);  // the rows' colours fit the parallel ones (and the overflow)
  EXPECT_GE(ws.keys, 4u);   // several columns
  const std::size_t overflow = ws.block_start.back() - ws.block_start[ws.color_start[ws.color_start.size() - 2]];
  EXPECT_GE(ws.color_start[1] - ws.color_start[0], 2u);  // several cells per colour
  EXPECT_LT(overflow, sys.contacts.size() / 20);
  expect_a_valid_colouring(before, sys, ws);
  expect_recolouring_moves_nothing(sys, ws, SweepOrder::ColoredRows);
  // inside a colour, the blocks by column (the threads' shares are ranges of columns)
  for (std::size_t k = 0; k + 2 < ws.color_start.size(); ++k)
    for (std::uint32_t b = ws.color_start[k]; b + 1 < ws.color_start[k + 1]; ++b) EXPECT_LE(ws.block_key[b], ws.block_key[b + 1]);
  // without positions (a dumped problem): blocks of consecutive contacts
  ContactSystem bare = before;
  bare.body_x.clear();
  bare.body_y.clear();
  color_contacts(bare, ws, SweepOrder::ColoredRows);
  EXPECT_FALSE(ws.cells || ws.strips);
  expect_a_valid_colouring(before, bare, ws);
  // a body without a finite position: no cells either (nothing undefined)
  ContactSystem lost = before;
  lost.body_x[lost.contacts[0].cd_dynamic ? lost.contacts[0].cd : lost.contacts[0].an] = std::nan("");
  color_contacts(lost, ws, SweepOrder::ColoredRows);
  EXPECT_FALSE(ws.cells || ws.strips);
  expect_a_valid_colouring(before, lost, ws);
}

TEST(NlgsColored, CellsGiveTheNumbersOfTheCellsSweptOneAfterTheOther) {
  // The colours are levels: two cells sharing a dynamic body are swept in cell order. So the
  // colored sweep is, bit for bit, the fixed sweep of the same contacts put cell after cell
  // (row by row from the bottom; colored-cells: from the top, each cell's contacts upward), the
  // overflow last — with lanes or without.
  const ContactSystem before = prepared_system(compressed_field(300).reg);
  const std::pair<SweepOrder, int> cases[] = {{SweepOrder::ColoredRows, 0},
                                              {SweepOrder::ColoredRows, 4},
                                              {SweepOrder::ColoredCells, 0},
                                              {SweepOrder::ColoredCells, 4}};
  for (const auto& [order, lanes] : cases) {
    SCOPED_TRACE(std::string(name_of(order)));
    ContactSystem sys = before;
    NlgsColoredWorkspace ws;
    color_contacts(sys, ws, order);
    ASSERT_TRUE(ws.cells);
    ContactSystem seq = sys;  // laid out colour by colour; now cell by cell
    std::vector<std::uint32_t> laid(ws.block_id.size());
    std::iota(laid.begin(), laid.end(), 0u);
    std::sort(laid.begin(), laid.end(), [&](std::uint32_t p, std::uint32_t q) { return ws.block_id[p] < ws.block_id[q]; });
    std::vector<std::uint32_t> from;  // seq's contact i is sys's contact from[i]
    for (std::uint32_t b : laid)
      for (std::uint32_t a = ws.block_start[b]; a < ws.block_start[b + 1]; ++a) from.push_back(a);
    ASSERT_EQ(from.size(), sys.contacts.size());
    for (std::size_t i = 0; i < from.size(); ++i) seq.contacts[i] = sys.contacts[from[i]];
    if (order == SweepOrder::ColoredCells) expect_cells_from_the_top_each_upward(sys, ws, laid);
    NlgsOptions o;
    o.min_sweeps = o.max_sweeps = 30;  // the same work, whatever the convergence sums' order
    o.relaxation = 1.3;
    o.lanes = lanes;
    NlgsWorkspace seq_ws;
    SceneBackend be(seq);
    nlgs_iterate(be, o, seq_ws);
    o.order = order;
    nlgs_iterate_colored(sys, o, ws);  // ws arranged sys for this order: its layout is kept
    std::size_t pressed = 0;
    for (std::size_t i = 0; i < from.size(); ++i) {
      ASSERT_EQ(seq.contacts[i].pn, sys.contacts[from[i]].pn) << "lanes " << lanes << ", contact " << i;
      ASSERT_EQ(seq.contacts[i].pt, sys.contacts[from[i]].pt) << "lanes " << lanes << ", contact " << i;
      pressed += seq.contacts[i].pn > 0.0;
    }
    EXPECT_GT(pressed, from.size() / 4);
    for (std::size_t b = 0; b < sys.bodies.size(); ++b) {
      ASSERT_EQ(seq.bodies[b].vx, sys.bodies[b].vx) << "body " << b;
      ASSERT_EQ(seq.bodies[b].vy, sys.bodies[b].vy) << "body " << b;
      ASSERT_EQ(seq.bodies[b].w, sys.bodies[b].w) << "body " << b;
    }
  }
}

TEST(NlgsColored, TwoRanksAreThoseOfASort) {
  // the cells' median and 95th percentile: values of every spread, ties, a single value, two
  std::mt19937 rng(17);
  std::vector<double> scratch;
  for (const std::size_t n : {1u, 2u, 3u, 10u, 255u, 256u, 1300u, 20000u})
    for (int kind = 0; kind < 4; ++kind) {
      std::vector<double> v(n);
      for (double& x : v) {
        const double u = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        x = kind == 0 ? u : kind == 1 ? std::floor(8.0 * u) : kind == 2 ? 0.25 : std::exp(30.0 * u) * 1e-9;  // ties, one value, 13 decades
      }
      if (kind == 3 && n > 2) v[1] = 0.0;
      std::vector<double> sorted = v;
      std::sort(sorted.begin(), sorted.end());
      const std::size_t k1 = n / 2, k2 = std::max(n / 2, (n - 1) * 95 / 100);
      double r1 = -1.0, r2 = -1.0;
      two_ranks(v, k1, k2, r1, r2, scratch);
      EXPECT_EQ(r1, sorted[k1]) << "n " << n << " kind " << kind;
      EXPECT_EQ(r2, sorted[k2]) << "n " << n << " kind " << kind;
      two_ranks(v, 0, n - 1, r1, r2, scratch);
      EXPECT_EQ(r1, sorted.front());
      EXPECT_EQ(r2, sorted.back());
    }
}

}  // namespace
