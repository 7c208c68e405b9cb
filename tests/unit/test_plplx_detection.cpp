// tests/unit/test_plplx_detection.cpp — detect_plplx (plplx.hpp) on a small scene: pentagons of
// 1 cm resting on a fixed 1.5 m floor, with hand-computed gaps, frames, lever arms and laws.
// The broad phase it starts from: test_broad_phase.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/interactions/plplx.hpp"
#include "nscd/interactions/shadow_overlap.hpp"

namespace {

using namespace nscd;

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
}

// The same scene's contacts one by one, their values computed by hand.
TEST(Plplx, PentagonsOnAFloorByHand) {
  PlplxScene s;
  build(s);
  PlplxDetector det;
  detect_plplx(s.reg, det);
  const std::uint32_t floor = s.polyg[7];
  const ContactTable& c = s.reg.contacts;
  ASSERT_EQ(c.size(), 6u);
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
