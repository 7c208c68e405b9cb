// tests/unit/test_broad_phase.cpp — the PLPLx broad phase (grid of tiles, broad_phase.hpp)
// against the O(N²) reference (and the same pairs in the same order on 2, 3 and 7 threads),
// and detect_plplx (plplx.hpp) on a small scene: pentagons of
// 1 cm resting on a fixed 1.5 m floor, with hand-computed gaps, frames, lever arms and laws.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/core/error.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/interactions/broad_phase.hpp"
#include "nscd/interactions/plplx.hpp"
#include "nscd/interactions/shadow_overlap.hpp"

namespace {

using namespace nscd;

// ---- broad phase ---------------------------------------------------------------------------------

struct BroadScene {
  std::vector<Aabb> boxes;
  std::vector<std::uint8_t> big;
};

// n boxes in the unit square: mostly grains of 5–20 mm, one in twenty of 5–10 cm, some
// zero-size boxes (points and segments), a few far-away outliers, and `n_big` big boxes
// (walls and a floor around the square, flagged is_big).
BroadScene random_scene(std::size_t n, std::uint64_t seed, std::size_t n_big, std::size_t n_outliers) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  BroadScene s;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = u(rng), y = u(rng);
    double w = 0.005 + 0.015 * u(rng), h = 0.005 + 0.015 * u(rng);
    if (i % 20 == 7) { w *= 5.0; h *= 5.0; }
    if (i % 50 == 3) w = h = 0.0;  // degenerate: a point
    if (i % 50 == 4) h = 0.0;      // degenerate: a segment
    s.boxes.push_back({x, y, x + w, y + h});
    s.big.push_back(0);
  }
  for (std::size_t k = 0; k < n_outliers && k < n; ++k) {  // far away, some of them touching each other
    const double x = (k % 2 ? -1.0 : 1.0) * 1e3, y = 5e2 + 0.01 * static_cast<double>(k / 2);
    s.boxes[(k * 7919) % n] = {x, y, x + 0.02, y + 0.015};
  }
  const Aabb walls[4] = {{-0.05, -0.05, 1.05, 0.0}, {-0.05, -0.05, 0.0, 1.2}, {1.0, -0.05, 1.05, 1.2}, {0.4, 0.3, 0.6, 0.5}};
  for (std::size_t k = 0; k < n_big; ++k) {
    const std::size_t i = (k * 104729 + 11) % std::max<std::size_t>(n, 1);
    if (i < n) {
      s.boxes[i] = walls[k % 4];
      s.big[i] = 1;
    }
  }
  return s;
}

std::vector<IndexPair> grid_pairs(const BroadScene& s) {
  BroadPhase ws;
  find_pairs(s.boxes, s.big, ws);
  return ws.pairs;
}

void expect_same_as_brute_force(const BroadScene& s) {
  std::vector<IndexPair> grid = grid_pairs(s);
  for (const auto& [i, j] : grid) ASSERT_LT(i, j);
  std::sort(grid.begin(), grid.end());
  EXPECT_TRUE(std::adjacent_find(grid.begin(), grid.end()) == grid.end()) << "duplicate pair";
  std::vector<IndexPair> brute = find_pairs_brute_force(s.boxes);
  std::sort(brute.begin(), brute.end());
  EXPECT_EQ(grid.size(), brute.size());
  EXPECT_TRUE(grid == brute);
}

TEST(BroadPhase, EqualsBruteForceOnRandomScenes) {
  for (std::size_t n : {100u, 1000u, 5000u})
    for (std::uint64_t seed : {1u, 2u}) {
      SCOPED_TRACE(testing::Message() << n << " boxes, seed " << seed);
      const BroadScene plain = random_scene(n, seed, 0, 0);
      expect_same_as_brute_force(plain);
      // the brute force finds pairs: the comparison is not vacuous
      EXPECT_GT(find_pairs_brute_force(plain.boxes).size(), n / 20);
      expect_same_as_brute_force(random_scene(n, seed, 4, 0));   // walls, floor and a big block
      expect_same_as_brute_force(random_scene(n, seed, 0, 6));   // outliers 1 km away
      expect_same_as_brute_force(random_scene(n, seed, 8, 10));  // both, walls twice (big–big pairs)
    }
}

TEST(BroadPhase, EmptySingleAndAllBig) {
  BroadScene s;
  EXPECT_TRUE(grid_pairs(s).empty());
  s.boxes = {{0, 0, 1, 1}};
  s.big = {0};
  EXPECT_TRUE(grid_pairs(s).empty());
  // only big boxes: big–big pairs once each. (0,1) overlap, (1,2) touch at x = 2, 0 and 2 apart
  s.boxes = {{0, 0, 1, 1}, {0.5, 0.5, 2, 2}, {2, 0, 3, 1}};
  s.big = {1, 1, 1};
  EXPECT_EQ(grid_pairs(s), (std::vector<IndexPair>{{0, 1}, {1, 2}}));
}

TEST(BroadPhase, AllBoxesInOneTile) {
  // 200 boxes of 1 cm, all centres within 2 mm of each other: one tile, every pair overlaps
  // (200·199/2 = 19900 pairs)
  BroadScene s;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 0.002);
  for (int i = 0; i < 200; ++i) {
    const double x = u(rng), y = u(rng);
    s.boxes.push_back({x, y, x + 0.01, y + 0.01});
    s.big.push_back(0);
  }
  EXPECT_EQ(grid_pairs(s).size(), 19900u);
  expect_same_as_brute_force(s);
}

TEST(BroadPhase, DegenerateZeroSizeBoxes) {
  // all boxes are points: the tile size falls to its floor; coincident points overlap.
  // Points on a 3×3 lattice of pitch 1, each point doubled: the pairs are the 9 doubles.
  BroadScene s;
  for (int k = 0; k < 18; ++k) {
    const double x = (k / 2) % 3, y = (k / 2) / 3;
    s.boxes.push_back({x, y, x, y});
    s.big.push_back(0);
  }
  const auto p = grid_pairs(s);
  EXPECT_EQ(p.size(), 9u);
  expect_same_as_brute_force(s);
  // a single point repeated 50 times: 1225 pairs
  BroadScene one;
  one.boxes.assign(50, Aabb{0.3, 0.3, 0.3, 0.3});
  one.big.assign(50, 0);
  EXPECT_EQ(grid_pairs(one).size(), 1225u);
}

TEST(BroadPhase, ExactlyTouchingLatticeBoxes) {
  // boxes of side p on a lattice of pitch p: every box touches its 8 neighbours exactly
  // (overlap is inclusive); an m×m lattice has 2m(m−1) edge pairs + 2(m−1)² corner pairs.
  for (double p : {0.1, 0.01 * 1.1, 1.0 / 3.0, 0.7, 0.0123456789}) {
    for (double x0 : {0.0, 0.3, -17.1}) {
      SCOPED_TRACE(testing::Message() << "pitch " << p << " origin " << x0);
      BroadScene s;
      const int m = 30;
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
          const double x = x0 + i * p, y = x0 + j * p;
          s.boxes.push_back({x, y, x + p, y + p});
          s.big.push_back(0);
        }
      expect_same_as_brute_force(s);
    }
  }
}

// Two boxes of the largest size touching exactly have centres exactly one tile size apart;
// when those centres sit on tile boundaries (to the last bit), rounding in (centre − x0)/size
// could put them two tiles apart and lose the pair. The first case was found by the sweep
// below: box 1 = [−0.36244, −0.28772], box 2 = [−0.28772, −0.21299] (width 0.0747244, the
// largest), anchor box at x0 = −0.77343: they touch at x = −0.28772, one pair (1, 2).
TEST(BroadPhase, TouchingBoxesOnTileBoundaries) {
  {
    const double w = 0.074724408195435063, x0 = -0.77342783053389041;
    const double a = -0.36244358545899785, b = -0.28771917726356283, c = -0.21299476906812781;
    BroadScene s;
    s.boxes = {{x0, 0, x0 + 0.1 * w, 0.1 * w}, {a, 0, b, 0.5 * w}, {b, 0, c, 0.5 * w}};
    s.big = {0, 0, 0};
    EXPECT_EQ(grid_pairs(s), (std::vector<IndexPair>{{1, 2}}));
  }
  // sweep: an anchor box fixing the grid origin x0, then two touching boxes of width w whose
  // first centre is within 6 ulp of the tile boundary x0 + k w
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int failures = 0;
  for (int wi = 0; wi < 300; ++wi) {
    const double w = 0.001 + 0.1 * u(rng), x0 = 10.0 * (u(rng) - 0.5);
    for (int k = 1; k < 60; ++k)
      for (int j = -6; j <= 6; ++j) {
        double c1 = x0 + k * w;
        for (int t = 0; t < std::abs(j) + 1; ++t) c1 = std::nextafter(c1, j < 0 ? -1e300 : 1e300);
        const double a = c1 - 0.5 * w, b = c1 + 0.5 * w, c = b + (b - a);
        BroadScene s;
        s.boxes = {{x0, 0, x0 + 0.1 * w, 0.1 * w}, {a, 0, b, 0.5 * w}, {b, 0, c, 0.5 * w}};
        s.big = {0, 0, 0};
        std::vector<IndexPair> g = grid_pairs(s);
        std::sort(g.begin(), g.end());
        if (g != find_pairs_brute_force(s.boxes) && ++failures <= 3)
          ADD_FAILURE() << std::setprecision(17) << "w " << w << " x0 " << x0 << " boxes [" << a << ", " << b << "], [" << b << ", " << c << "]";
      }
  }
  EXPECT_EQ(failures, 0);
}

TEST(BroadPhase, DeterministicOrder) {
  const BroadScene s = random_scene(1000, 9, 4, 3);
  BroadPhase ws;
  find_pairs(s.boxes, s.big, ws);
  const std::vector<IndexPair> first = ws.pairs;
  find_pairs(s.boxes, s.big, ws);  // same workspace, warmed up
  EXPECT_EQ(ws.pairs, first);
  EXPECT_EQ(grid_pairs(s), first);  // fresh workspace
  for (int threads : {2, 3, 7}) {  // each thread's boxes' partners, joined in order
    find_pairs(s.boxes, s.big, ws, threads);
    EXPECT_EQ(ws.pairs, first) << threads << " threads";
  }
  // documented order: grid pairs by i ascending then j ascending, then the big boxes' pairs
  std::size_t k = 0;
  while (k + 1 < first.size() && !s.big[first[k + 1].first] && !s.big[first[k + 1].second]) {
    EXPECT_LT(first[k], first[k + 1]);
    ++k;
  }
}

TEST(BroadPhase, ThreadsShareEveryPassAndGiveTheOneThreadGrid) {
  // find_pairs on threads scans, lists, tiles and tests against the big boxes in shares: the
  // same pairs in the same order, and the same grid (tiles, their boxes in order), whether the
  // boxes' numbers follow the rows of tiles or not, with more threads than boxes, with no
  // ordinary box, with none at all.
  BroadScene mixed = random_scene(3000, 5, 4, 6), rows = mixed, tiny = random_scene(3, 2, 0, 0);
  std::vector<std::size_t> order(rows.boxes.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return mixed.boxes[a].ymin < mixed.boxes[b].ymin; });
  for (std::size_t i = 0; i < order.size(); ++i) rows.boxes[i] = mixed.boxes[order[i]], rows.big[i] = mixed.big[order[i]];
  BroadScene walls = random_scene(4, 1, 4, 0), none;
  for (const BroadScene* s : {&mixed, &rows, &tiny, &walls, &none}) {
    BroadPhase one, many;
    find_pairs(s->boxes, s->big, one);
    std::vector<IndexPair> sorted = one.pairs;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, find_pairs_brute_force(s->boxes));
    if (s == &mixed) {
      EXPECT_GT(one.pairs.size(), 3000u);
    }
    for (int threads : {2, 3, 4, 7}) {
      SCOPED_TRACE(testing::Message() << s->boxes.size() << " boxes, " << threads << " threads");
      find_pairs(s->boxes, s->big, many, threads);
      EXPECT_EQ(many.pairs, one.pairs);
      EXPECT_EQ(many.small, one.small);
      EXPECT_EQ(many.big, one.big);
      if (one.small.empty()) continue;
      EXPECT_EQ(many.cell_start, one.cell_start);
      EXPECT_EQ(many.cell_items, one.cell_items);
      for (std::size_t k = 0; k < one.tile_boxes.size(); ++k)
        ASSERT_EQ(many.tile_boxes[k].xmin, one.tile_boxes[k].xmin) << k;
    }
  }
  // a bad box is named on threads as on one: the first in index order
  BroadScene bad = random_scene(3000, 5, 4, 0);
  bad.boxes[2500].ymax = std::nan("");
  bad.boxes[9].xmin = -std::numeric_limits<double>::infinity();
  for (int threads : {1, 2, 3}) {
    BroadPhase ws;
    try {
      find_pairs(bad.boxes, bad.big, ws, threads);
      ADD_FAILURE() << "a non-finite box was accepted on " << threads << " threads";
    } catch (const nscd::Error& e) {
      EXPECT_NE(std::string(e.what()).find("bounding box 9 "), std::string::npos) << e.what();
    }
  }
}

TEST(BroadPhaseReusing, GivesFindPairsExactlyWhileTheBoxesMove) {
  // Boxes that drift a little every call (as grains do from one step to the next), and now and
  // then jump (past the quarter margin), change count or big flag: every call gives the pairs of
  // find_pairs, in its order, and the kept list is reused most of the time; on one thread and on
  // two (the boxes' test and the kept pairs' filter shared).
  for (int run = 0; run < 4; ++run) {
    const int threads = 1 + run / 2;
    const std::size_t n_big = run % 2 == 0 ? 0 : 4;
    SCOPED_TRACE(testing::Message() << n_big << " big boxes, " << threads << " thread(s)");
    BroadScene s = random_scene(1000, 7, n_big, 4);
    std::mt19937_64 rng(11);
    std::normal_distribution<double> drift(0.0, 2e-4);  // 0.2 mm a call; the margin is 10 mm here
    BroadPhase ws;
    std::size_t calls = 0, pairs = 0;
    for (int call = 0; call < 300; ++call) {
      for (std::size_t i = 0; i < s.boxes.size(); ++i) {
        if (s.big[i]) continue;
        const double dx = drift(rng), dy = drift(rng), grow = call % 97 == 50 ? 0.004 : 0.0;  // a box that grows
        s.boxes[i] = {s.boxes[i].xmin + dx, s.boxes[i].ymin + dy, s.boxes[i].xmax + dx + grow * (i == 3), s.boxes[i].ymax + dy};
      }
      if (call == 120) s.boxes[500].xmin -= 0.05;                  // one box jumps
      if (call == 200) s.big[17] = s.big[17] ? 0 : 1;              // a big flag changes
      if (call == 250) { s.boxes.push_back({0.5, 0.5, 0.51, 0.51}); s.big.push_back(0); }  // a box is added
      find_pairs_reusing(s.boxes, s.big, ws, threads);
      ASSERT_EQ(ws.pairs, grid_pairs(s)) << "call " << call;
      ASSERT_EQ(ws.pairs.size(), ws.pair_near.size());
      for (std::size_t k = 0; k < ws.pairs.size(); ++k) ASSERT_EQ(ws.near[ws.pair_near[k]], ws.pairs[k]) << "call " << call;
      ++calls;
      pairs += ws.pairs.size();
    }
    EXPECT_GT(pairs, calls * 200);  // the scenes have pairs
    EXPECT_EQ(ws.rebuilds + ws.reuses, calls);
    EXPECT_GT(ws.reuses, calls / 2) << ws.rebuilds << " rebuilds";
    EXPECT_GE(ws.rebuilds, 4u);  // the first call, the jump, the flag, the added box (and the drift)
  }
}

TEST(BroadPhaseReusing, BadBoxesAreNamedAndPointsAreNotKept) {
  BroadScene s = random_scene(200, 3, 0, 0);
  BroadPhase ws;
  find_pairs_reusing(s.boxes, s.big, ws);
  ASSERT_EQ(ws.rebuilds, 1u);
  s.boxes[9].xmax = std::nan("");
  try {
    find_pairs_reusing(s.boxes, s.big, ws);
    FAIL() << "a NaN box was accepted";
  } catch (const nscd::Error& e) {
    EXPECT_NE(std::string(e.what()).find("bounding box 9"), std::string::npos) << e.what();
  }
  // boxes of no extent (points): no margin, find_pairs every call, still its pairs
  BroadScene points;
  for (int k = 0; k < 50; ++k) {
    points.boxes.push_back({0.01 * (k % 7), 0.0, 0.01 * (k % 7), 0.0});
    points.big.push_back(0);
  }
  BroadPhase pw;
  for (int call = 0; call < 3; ++call) {
    find_pairs_reusing(points.boxes, points.big, pw);
    EXPECT_EQ(pw.pairs, grid_pairs(points));
  }
  EXPECT_EQ(pw.rebuilds, 3u);
  EXPECT_FALSE(pw.pairs.empty());
}

// ---- detect_plplx on a small scene ----------------------------------------------------------------

const double kR = 0.005;  // 1 cm pentagons: circumscribed radius 5 mm
const double kS36 = std::sin(kPi / 5.0), kC36 = std::cos(kPi / 5.0);

// Pentagons first (lower polygon indices), the floor last, so that "antagonist = big polygon"
// differs from "antagonist = lower index". Floor: 1.5 m × 5 cm, fixed, top face y = 0 over
// x in [0, 1.5] (its top edge is edge 2). A regular pentagon's centroid is its centre, so each
// body's centre of mass is the position given.
//   P0 flat bottom (vertex 0 up) at (0.30, r cos36 − 2e-4): bottom edge 2 at y = −2e-4, edge–edge
//   P1 vertex 0 down at (0.50, r − 1e-4): corner at y = −1e-4, vertex–edge
//   P2 flat bottom at (0.70, r cos36 + 5e-4): 5e-4 above the floor, within the alert 1.25e-3
//   P3 flat bottom at (0.90, r cos36 + 3e-3): 3 mm above, beyond the alert (no broad-phase pair:
//      boxes grow by alert/2 = 0.625 mm each)
//   T  one body made of two touching squares (same body: skipped)
//   P5 flat top (vertex 0 down) at (1.2, 0.1), P6 vertex 0 down just above it, 1e-4 into P5's
//      top edge 2: vertex–edge between two grains, antagonist the lower index P5
//   W  a fixed wall overlapping the floor (two fixed bodies: skipped)
struct PlplxScene {
  Registry reg;
  MaterialId ballast, concrete;
  std::vector<std::uint32_t> polyg;  // first POLYG of each body, in creation order
  std::vector<BodyId> body;
};

void add(PlplxScene& s, const Polygon& shape, MaterialId m, Vec2 at) {
  s.polyg.push_back(static_cast<std::uint32_t>(s.reg.polyg.size()));
  s.body.push_back(add_polygon_body(s.reg, shape, m, at));
}

void build(PlplxScene& s) {
  Registry& reg = s.reg;
  s.ballast = add_material(reg, "ballast", 2367.0);
  s.concrete = add_material(reg, "concrete", 2400.0);
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.5});                 // law 0
  set_contact_law(reg, s.ballast, s.concrete, LawSpec{LawKind::IQS_CLB, 0.8});  // law 1
  add(s, regular_polygon(5, 2 * kR, kPi / 2), s.ballast, {0.30, kR * kC36 - 2e-4});   // 0: P0
  add(s, regular_polygon(5, 2 * kR, -kPi / 2), s.ballast, {0.50, kR - 1e-4});         // 1: P1
  add(s, regular_polygon(5, 2 * kR, kPi / 2), s.ballast, {0.70, kR * kC36 + 5e-4});   // 2: P2
  add(s, regular_polygon(5, 2 * kR, kPi / 2), s.ballast, {0.90, kR * kC36 + 3e-3});   // 3: P3
  const std::vector<Polygon> two = {{{-0.005, 0}, {0, 0}, {0, 0.005}, {-0.005, 0.005}}, {{0, 0}, {0.005, 0}, {0.005, 0.005}, {0, 0.005}}};
  s.polyg.push_back(static_cast<std::uint32_t>(reg.polyg.size()));
  s.body.push_back(add_polygon_body(reg, two, s.ballast, {0.1, 0.5}));                // 4: T (2 POLYGs)
  add(s, regular_polygon(5, 2 * kR, -kPi / 2), s.ballast, {1.2, 0.1});                // 5: P5
  add(s, regular_polygon(5, 2 * kR, -kPi / 2), s.ballast, {1.2, 0.1 + kR * kC36 + kR - 1e-4});  // 6: P6
  add(s, rectangle(1.5, 0.05), s.concrete, {0.75, -0.025});                           // 7: floor
  add(s, rectangle(0.05, 0.2), s.concrete, {1.45, 0.05});                             // 8: wall
  fix_body(reg, s.body[7]);
  fix_body(reg, s.body[8]);
  classify_big_polygons(reg, 8.0);
}

// Row of reg.contacts for candidate polygon cd, extremity k (rows of a pair are consecutive).
std::size_t row_of(const ContactTable& c, std::uint32_t cd, std::size_t k = 0) {
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c.candidate[i].index() == cd) return i + k;
  return c.size();
}

TEST(Plplx, PentagonsOnAFloor) {
  PlplxScene s;
  build(s);
  Registry& reg = s.reg;
  const std::uint32_t floor = s.polyg[7];
  // the floor (radius 0.75) and the wall (0.103) exceed 8 × the median radius (5 mm)
  EXPECT_EQ(reg.polyg.is_big[floor], 1);
  EXPECT_EQ(reg.polyg.is_big[s.polyg[8]], 1);
  EXPECT_EQ(reg.polyg.is_big[s.polyg[0]], 0);

  PlplxDetector det;
  const DetectionStats st = detect_plplx(reg, det);
  // broad phase: P0, P1, P2 with the floor, T's two squares, P5–P6, wall–floor = 6 pairs;
  // contacts: P0 (2), P1 (1), P2 (2), P5–P6 (1)
  EXPECT_EQ(st.candidate_pairs, 6u);
  EXPECT_EQ(st.contact_pairs, 4u);
  EXPECT_EQ(st.contact_points, 6u);
  EXPECT_EQ(st.double_contacts, 2u);
  const ContactTable& c = reg.contacts;
  ASSERT_EQ(c.size(), 6u);

  for (std::size_t i = 0; i < c.size(); ++i) {
    SCOPED_TRACE(i);
    // never the same body, never two fixed bodies
    EXPECT_NE(c.cd_body[i], c.an_body[i]);
    EXPECT_NE(c.cd_body[i], s.body[8]);
    EXPECT_NE(c.an_body[i], s.body[8]);
    EXPECT_NE(c.cd_body[i], s.body[4]);
    // lever arms: cross(point − G, n) and cross(point − G, t), t = perp(n), G = centre of mass
    const std::size_t bc = c.cd_body[i].index(), ba = c.an_body[i].index();
    const Vec2 n = c.normal[i], t{-n.y, n.x};
    const Vec2 rc = c.point[i] - Vec2{reg.bodies.x[bc], reg.bodies.y[bc]};
    const Vec2 ra = c.point[i] - Vec2{reg.bodies.x[ba], reg.bodies.y[ba]};
    EXPECT_NEAR(c.cd_rn[i], rc.x * n.y - rc.y * n.x, 1e-15);
    EXPECT_NEAR(c.cd_rt[i], rc.x * t.y - rc.y * t.x, 1e-15);
    EXPECT_NEAR(c.an_rn[i], ra.x * n.y - ra.y * n.x, 1e-15);
    EXPECT_NEAR(c.an_rt[i], ra.x * t.y - ra.y * t.x, 1e-15);
    EXPECT_EQ(c.rn[i], 0.0);
    EXPECT_EQ(c.rt[i], 0.0);
    EXPECT_EQ(c.status[i], ContactStatus::Open);
    // laws: ballast–concrete is law 1 (μ 0.8), ballast–ballast the default law 0 (μ 0.5)
    const bool on_floor = c.antagonist[i].index() == floor;
    EXPECT_EQ(c.law[i], on_floor ? 1 : 0);
    EXPECT_EQ(c.mu[i], on_floor ? 0.8 : 0.5);
    EXPECT_NEAR(c.normal[i].x, 0.0, 1e-15);
    EXPECT_NEAR(c.normal[i].y, 1.0, 1e-15);
  }

  // P0: the antagonist is the big floor although its index is higher. Edge–edge, t = (−1,0):
  // extremity 0 at x = 0.30 + r sin36, extremity 1 at x = 0.30 − r sin36, y = −1e-4, gap −2e-4.
  // Lever arms of extremity 0 by hand: r_cd = (r sin36, −1e-4 − (r cos36 − 2e-4)):
  // cd_rn = r sin36 = 2.9389e-3, cd_rt = r_cd.y·1 = 1e-4 − r cos36; r_an = (0.30 + r sin36 − 0.75,
  // −1e-4 + 0.025): an_rn = −0.45 + r sin36, an_rt = 0.0249.
  std::size_t i = row_of(c, s.polyg[0]);
  ASSERT_LT(i + 1, c.size());
  EXPECT_EQ(c.antagonist[i].index(), floor);
  EXPECT_EQ(c.candidate[i + 1].index(), s.polyg[0]);
  EXPECT_NEAR(c.gap[i], -2e-4, 1e-15);
  EXPECT_NEAR(c.gap[i + 1], -2e-4, 1e-15);
  EXPECT_NEAR(c.point[i].x, 0.30 + kR * kS36, 1e-15);
  EXPECT_NEAR(c.point[i].y, -1e-4, 1e-15);
  EXPECT_NEAR(c.point[i + 1].x, 0.30 - kR * kS36, 1e-15);
  EXPECT_NEAR(c.cd_rn[i], kR * kS36, 1e-15);
  EXPECT_NEAR(c.cd_rt[i], 1e-4 - kR * kC36, 1e-15);
  EXPECT_NEAR(c.an_rn[i], -0.45 + kR * kS36, 1e-15);
  EXPECT_NEAR(c.an_rt[i], 0.0249, 1e-15);
  EXPECT_EQ(c.feature[i], make_feature(FeatureKind::EdgeEdge, 2, 2, 0));
  EXPECT_EQ(c.cd_body[i], s.body[0]);
  EXPECT_EQ(c.an_body[i], s.body[7]);
  // P1: one point, corner (0.5, −1e-4), point (0.5, −5e-5); r_cd = (0, −5e-5 − (r − 1e-4)):
  // cd_rn = r_cd.x = 0, cd_rt = cross(r_cd, (−1,0)) = r_cd.y = 5e-5 − r
  i = row_of(c, s.polyg[1]);
  ASSERT_LT(i, c.size());
  EXPECT_EQ(c.antagonist[i].index(), floor);
  EXPECT_NEAR(c.gap[i], -1e-4, 1e-15);
  EXPECT_NEAR(c.point[i].x, 0.5, 1e-15);
  EXPECT_NEAR(c.point[i].y, -5e-5, 1e-15);
  EXPECT_NEAR(c.cd_rn[i], 0.0, 1e-15);
  EXPECT_NEAR(c.cd_rt[i], 5e-5 - kR, 1e-15);
  EXPECT_EQ(c.feature[i], make_feature(FeatureKind::CandidateVertexOnAntagonistEdge, 0, 2));
  EXPECT_TRUE(i + 1 == c.size() || c.candidate[i + 1].index() != s.polyg[1]);
  // P2: two points with the positive gap 5e-4, at y = 2.5e-4
  i = row_of(c, s.polyg[2]);
  ASSERT_LT(i + 1, c.size());
  EXPECT_NEAR(c.gap[i], 5e-4, 1e-15);
  EXPECT_NEAR(c.gap[i + 1], 5e-4, 1e-15);
  EXPECT_NEAR(c.point[i].y, 2.5e-4, 1e-15);
  // P3 too far, T skipped
  EXPECT_EQ(row_of(c, s.polyg[3]), c.size());
  EXPECT_EQ(row_of(c, s.polyg[4]), c.size());
  EXPECT_EQ(row_of(c, s.polyg[4] + 1), c.size());
  // P5–P6: antagonist P5 (lower index), candidate P6, corner 1e-4 into P5's top edge 2 at
  // y = 0.1 + r cos36: gap −1e-4, point (1.2, 0.1 + r cos36 − 5e-5)
  i = row_of(c, s.polyg[6]);
  ASSERT_LT(i, c.size());
  EXPECT_EQ(c.antagonist[i].index(), s.polyg[5]);
  EXPECT_NEAR(c.gap[i], -1e-4, 1e-15);
  EXPECT_NEAR(c.point[i].x, 1.2, 1e-15);
  EXPECT_NEAR(c.point[i].y, 0.1 + kR * kC36 - 5e-5, 1e-15);
  EXPECT_EQ(c.feature[i], make_feature(FeatureKind::CandidateVertexOnAntagonistEdge, 0, 2));
}

TEST(Plplx, DetectionAtAnotherConfiguration) {
  // detect at q_m: every pentagon 1e-4 lower than in the registry (floor and wall unchanged):
  // floor gaps −3e-4 (P0), −2e-4 (P1), 4e-4 (P2); P5–P6 unchanged (both moved); the registry's
  // own configuration is not touched
  PlplxScene s;
  build(s);
  Registry& reg = s.reg;
  std::vector<double> y = reg.bodies.y;
  for (std::size_t b = 0; b < 7; ++b) y[s.body[b].index()] -= 1e-4;
  PlplxDetector det;
  detect_plplx(reg, det, Configuration{reg.bodies.x, y, reg.bodies.angle});
  const ContactTable& c = reg.contacts;
  ASSERT_EQ(c.size(), 6u);
  EXPECT_NEAR(c.gap[row_of(c, s.polyg[0])], -3e-4, 1e-15);
  EXPECT_NEAR(c.gap[row_of(c, s.polyg[1])], -2e-4, 1e-15);
  EXPECT_NEAR(c.gap[row_of(c, s.polyg[2])], 4e-4, 1e-15);
  EXPECT_NEAR(c.gap[row_of(c, s.polyg[6])], -1e-4, 1e-15);
  // the lever arms use the configuration detected at: P1's corner is at y = −2e-4, the point
  // half-way at −1e-4, its centre at r − 2e-4: cd_rt = point.y − G.y = 1e-4 − r (5e-5 − r at
  // the registry's configuration); the floor's an_rt = point.y + 0.025 = 0.0249
  EXPECT_NEAR(c.point[row_of(c, s.polyg[1])].y, -1e-4, 1e-15);
  EXPECT_NEAR(c.cd_rt[row_of(c, s.polyg[1])], 1e-4 - kR, 1e-15);
  EXPECT_NEAR(c.an_rt[row_of(c, s.polyg[1])], 0.0249, 1e-15);
  EXPECT_NEAR(reg.bodies.y[s.body[1].index()], kR - 1e-4, 1e-18);
  // a second detection at the registry's configuration replaces the table
  detect_plplx(reg, det);
  ASSERT_EQ(c.size(), 6u);
  EXPECT_NEAR(c.gap[row_of(c, s.polyg[0])], -2e-4, 1e-15);
  // a configuration of the wrong size is an error
  std::vector<double> shorter(reg.bodies.size() - 1, 0.0);
  EXPECT_THROW(detect_plplx(reg, det, Configuration{shorter, shorter, shorter}), std::exception);
}

TEST(Plplx, PairWithoutLawGetsLawMinusOne) {
  // the law index comes from the contact-law table; without any law it is −1 and μ = 0 (the
  // Moreau–Jean step skips such contacts); a 10 cm box 1e-4 into a 1 m plank: edge–edge
  Registry reg;
  const MaterialId m = add_material(reg, "m", 1000.0);
  add_polygon_body(reg, rectangle(1.0, 0.1), m, {0, -0.05});
  add_polygon_body(reg, rectangle(0.1, 0.1), m, {0, 0.05 - 1e-4});
  PlplxDetector det;
  detect_plplx(reg, det);
  ASSERT_EQ(reg.contacts.size(), 2u);
  EXPECT_EQ(reg.contacts.law[0], -1);
  EXPECT_EQ(reg.contacts.mu[0], 0.0);
}

}  // namespace
