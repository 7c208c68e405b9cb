// tests/unit/test_shadow_overlap.cpp — the PLPLx narrow phase (Moreau's shadow overlap,
// interactions/shadow_overlap.hpp) against hand computations; the randomized property test
// against an independent separating-axis test and an exact polygon distance is in
// test_shadow_overlap_random.cpp, the polygons both use in shadow_overlap_fixtures.hpp.
//
// Conventions checked everywhere: A = antagonist, B = candidate, the normal points toward the
// candidate, gap < 0 is an overlap, the point sits half-way between the two boundaries, an
// edge–edge contact gives the two extremities of the common segment.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "nscd/interactions/shadow_overlap.hpp"
#include "shadow_overlap_fixtures.hpp"

namespace {

using namespace nscd;
using namespace nscd::shadow_overlap_fixtures;

// ---- tiny helpers: boxes, rigid motions, the expected points -------------------------------------

Shape box(double x0, double y0, double x1, double y1) { return make_shape({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}); }

// Rigid motion p -> offset + R(angle) p applied to the vertices (normals rotated).
Shape moved(const Shape& s, double angle, Vec2 offset = {}) {
  const Rot2 r = Rot2::of(angle);
  Shape o = s;
  for (auto& p : o.v) p = offset + r.apply(p);
  for (auto& q : o.n) q = r.apply(q);
  o.g = offset + r.apply(s.g);
  return o;
}

constexpr double kTol = 1e-12;

void expect_point(const ContactPoint& p, double gap, Vec2 normal, Vec2 point, std::uint32_t feature, double tol = kTol) {
  EXPECT_NEAR(p.gap, gap, tol);
  EXPECT_NEAR(p.normal.x, normal.x, tol);
  EXPECT_NEAR(p.normal.y, normal.y, tol);
  EXPECT_NEAR(p.point.x, point.x, tol);
  EXPECT_NEAR(p.point.y, point.y, tol);
  EXPECT_EQ(p.feature, feature);
}

const double kS30 = 0.5, kC30 = std::sqrt(3.0) / 2.0;
const double kSin36 = std::sin(kPi / 5.0), kCos36 = std::cos(kPi / 5.0);

// The unit square rotated by 30° about its centre c. Vertex 0 = R30(−½,−½) is the lowest:
// c + ((sin30 − cos30)/2, −(cos30 + sin30)/2) = c + (−0.1830127, −0.6830127); its neighbours
// v1 = v0 + (cos30, sin30) and v3 = v0 + (−sin30, cos30) sit 0.5 and 0.866 higher.
Shape square30(Vec2 c) { return moved(box(-0.5, -0.5, 0.5, 0.5), kPi / 6.0, c); }
Vec2 square30_low(Vec2 c) { return c + Vec2{0.5 * (kS30 - kC30), -0.5 * (kC30 + kS30)}; }

// ---- separated pairs ------------------------------------------------------------------------------

TEST(ShadowOverlap, SeparatedBeyondAlertGivesNothing) {
  // box [−2,2]×[−1,0]; the 30° square's lowest corner 0.01 above the top: gap 0.01 > alert 1e-3
  const Shape A = box(-2, -1, 2, 0);
  const Vec2 c{0.5, 0.5 * (kC30 + kS30) + 0.01};
  EXPECT_EQ(detect(A, square30(c), 1e-3).count, 0);
  // two unit squares side by side, 0.01 apart: shadows apart along (1, 0)
  EXPECT_EQ(detect(box(0, 0, 1, 1), box(1.01, 0.3, 2.01, 1.3), 1e-3).count, 0);
  // corner to corner along the diagonal: distance 1e-3·√2 = 1.414e-3 > alert 1.25e-3, although
  // the shadows on the edge normals are only 1e-3 apart
  EXPECT_EQ(detect(box(0, 0, 1, 1), box(1.001, 1.001, 2.001, 2.001), 1.25e-3).count, 0);
  // the same corners facing each other, but the start direction G_A G_B = (5.501, 1.001) is
  // far from the diagonal: shov there is −1e-3 (cos 10.3° + sin 10.3°) = −1.163e-3, within the
  // alert; the walk stops on (0,1) where the shadows are 1e-3 apart, yet the corners (10,1)
  // and (10.001,1.001) are 1.414e-3 > 1.25e-3 apart: nothing to report
  const Shape flat = box(0, 0, 10, 1), corner = box(10.001, 1.001, 11.001, 2.001);
  EXPECT_EQ(detect(flat, corner, 1.25e-3).count, 0);
  EXPECT_EQ(detect(corner, flat, 1.25e-3).count, 0);
  // with alert 1.5e-3 the pair is within reach: one point, the shadow gap 1e-3 along (0,1)
  // (a lower bound of the distance), the candidate's corner 0 against the top edge 2, point
  // half-way: (10.001, 1.001 − 5e-4)
  const auto r = detect(flat, corner, 1.5e-3);
  ASSERT_EQ(r.count, 1);
  expect_point(r.points[0], 1e-3, {0, 1}, {10.001, 1.0005}, make_feature(FK::CandidateVertexOnAntagonistEdge, 0, 2));
}

TEST(ShadowOverlap, SeparatedWithinAlertGivesPositiveGaps) {
  // vertex–edge: lowest corner (x, 5e-4) above the top y = 0: gap 5e-4, point half-way (x, 2.5e-4)
  const Shape A = box(-2, -1, 2, 0);
  const Vec2 c{0.5, 0.5 * (kC30 + kS30) + 5e-4};
  const Vec2 low = square30_low(c);
  const auto r = detect(A, square30(c), 1e-3);
  ASSERT_EQ(r.count, 1);
  expect_point(r.points[0], 5e-4, {0, 1}, {low.x, 2.5e-4}, make_feature(FK::CandidateVertexOnAntagonistEdge, 0, 2));
  // edge–edge: box [0,1]² and [0.5,1.5]×[1.0005,2.0005]: common segment x in [0.5, 1], gap 5e-4
  // along (0,1); t = perp(n) = (−1,0) so the first extremity is the larger x
  const auto e = detect(box(0, 0, 1, 1), box(0.5, 1.0005, 1.5, 2.0005), 1e-3);
  ASSERT_EQ(e.count, 2);
  expect_point(e.points[0], 5e-4, {0, 1}, {1.0, 1.00025}, make_feature(FK::EdgeEdge, 2, 0, 0));
  expect_point(e.points[1], 5e-4, {0, 1}, {0.5, 1.00025}, make_feature(FK::EdgeEdge, 2, 0, 1));
  // corner to corner along the diagonal, 1e-4 apart on each axis: distance 1.41e-4 <= alert,
  // reported along an edge normal with the shadow gap 1e-4 (a lower bound of the distance)
  const auto d = detect(box(0, 0, 1, 1), box(1.0001, 1.0001, 2.0001, 2.0001), 1e-3);
  ASSERT_GE(d.count, 1);
  EXPECT_NEAR(d.points[0].gap, 1e-4, kTol);
}

TEST(ShadowOverlap, ExactlyTouchingHasZeroGap) {
  // diamond (0,1),(1,2),(0,3),(−1,2) on the top y = 1 of [−2,2]×[−1,1]: corner (0,1) on the
  // edge, gap 0 exactly, normal (0,1), point (0,1); the diamond's vertex 0 on box edge 2
  const Shape A = box(-2, -1, 2, 1), B = make_shape({{0, 1}, {1, 2}, {0, 3}, {-1, 2}});
  const auto r = detect(A, B, 1e-3);
  ASSERT_EQ(r.count, 1);
  expect_point(r.points[0], 0.0, {0, 1}, {0, 1}, make_feature(FK::CandidateVertexOnAntagonistEdge, 0, 2), 0.0);
}

// ---- vertex–edge, both roles ---------------------------------------------------------------------

// Box A = [−2,2]×[−1,0] (top = edge 2, vertices (2,0),(−2,0)); the 30° square's corner v0 at
// depth 0.01: c = (0.5, 0.6830127 − 0.01), v0 = (0.3169873, −0.01). Its neighbours are 0.49
// and 0.856 above the top line: far beyond the alert, so vertex–edge.
// gap = v0·n − 0 = −0.01, n = (0,1), point = v0 + ½·0.01·n = (0.3169873, −0.005).
TEST(ShadowOverlap, CandidateCornerIntoAntagonistEdge) {
  const Shape A = box(-2, -1, 2, 0);
  const Vec2 c{0.5, 0.5 * (kC30 + kS30) - 0.01};
  const Vec2 low = square30_low(c);
  EXPECT_NEAR(low.y, -0.01, kTol);
  const auto r = detect(A, square30(c), 1e-3);
  ASSERT_EQ(r.count, 1);
  expect_point(r.points[0], -0.01, {0, 1}, {low.x, -0.005}, make_feature(FK::CandidateVertexOnAntagonistEdge, 0, 2));
  EXPECT_GE(r.rotations, 1);
}

// Same scene, roles swapped: the square is the antagonist, the box the candidate. The normal
// points toward the candidate: (0,−1); the box's top edge 2 is now the candidate's edge.
// gap = line − a·n with line = min over the box of b·n = 0 and a·n = 0.01: −0.01;
// point = a + ½ gap n = (x, −0.01) + (0, 0.005) = (x, −0.005), the same material point.
TEST(ShadowOverlap, AntagonistCornerIntoCandidateEdge) {
  const Shape A = box(-2, -1, 2, 0);
  const Vec2 c{0.5, 0.5 * (kC30 + kS30) - 0.01};
  const Vec2 low = square30_low(c);
  const auto r = detect(square30(c), A, 1e-3);
  ASSERT_EQ(r.count, 1);
  expect_point(r.points[0], -0.01, {0, -1}, {low.x, -0.005}, make_feature(FK::AntagonistVertexOnCandidateEdge, 0, 2));
  // the antagonist square below, its top corner v2 = c − (v0 − c) poking 0.01 into the bottom
  // edge 0 of the candidate box [−2,2]×[0,1]: n = (0,1) toward the candidate, point (x, 0.005)
  const Vec2 c2{-0.4, -0.5 * (kC30 + kS30) + 0.01};
  const Vec2 top = c2 - (square30_low(c2) - c2);
  EXPECT_NEAR(top.y, 0.01, kTol);
  const auto s = detect(square30(c2), box(-2, 0, 2, 1), 1e-3);
  ASSERT_EQ(s.count, 1);
  expect_point(s.points[0], -0.01, {0, 1}, {top.x, 0.005}, make_feature(FK::AntagonistVertexOnCandidateEdge, 2, 0));
}

// ---- edge–edge -------------------------------------------------------------------------------------

// A = [0,4]×[−1,0] (top edge 2), B = [3,5]×[−0.002,0.998] (bottom edge 0): parallel, depth
// 0.002. n = (0,1), t = (−1,0); tangent coordinates: A's top [−4,0], B's bottom [−5,−3];
// common [−4,−3]: extremity 0 at x = 4, extremity 1 at x = 3; points at y = −0.001.
TEST(ShadowOverlap, EdgeEdgeParallelPartialOverlap) {
  const auto r = detect(box(0, -1, 4, 0), box(3, -0.002, 5, 0.998), 1e-3);
  ASSERT_EQ(r.count, 2);
  expect_point(r.points[0], -0.002, {0, 1}, {4, -0.001}, make_feature(FK::EdgeEdge, 2, 0, 0));
  expect_point(r.points[1], -0.002, {0, 1}, {3, -0.001}, make_feature(FK::EdgeEdge, 2, 0, 1));
}

// A short box [−0.5,0.5]×[−0.001,0.999] on a long one [−3,3]×[−1,0]: the common segment is
// the short edge, extremities x = 0.5 then x = −0.5 (t = (−1,0)). Centred exactly above (the
// start direction (0,1) is itself an edge normal) and shifted by 1.7 (x = 2.2, 1.2).
TEST(ShadowOverlap, EdgeEdgeNestedLengths) {
  for (double dx : {0.0, 1.7, -2.2}) {
    SCOPED_TRACE(dx);
    const auto r = detect(box(-3, -1, 3, 0), box(dx - 0.5, -0.001, dx + 0.5, 0.999), 1e-3);
    ASSERT_EQ(r.count, 2);
    expect_point(r.points[0], -0.001, {0, 1}, {dx + 0.5, -0.0005}, make_feature(FK::EdgeEdge, 2, 0, 0));
    expect_point(r.points[1], -0.001, {0, 1}, {dx - 0.5, -0.0005}, make_feature(FK::EdgeEdge, 2, 0, 1));
  }
}

// Box [−3,3]×[−1,0]; the unit square [−0.5,0.5]×[0,1] rotated by ε = 1e-3 about the origin, then
// lowered by s. Bottom corners p0 = (−½cos ε, −½sin ε − s), p1 = (½cos ε, ½sin ε − s).
// The walk stops on the box's normal (0,1) (shov ½ sin ε + s there, 3 sin ε + s on the square's
// normal); p1 is ½ sin ε ≈ 5e-4 <= alert above p0, so edge–edge. The segment's extremities are
// measured along the mean tangent t = perp(normalized((0,1) − n_B)) = (−cos ε/2, −sin ε/2):
// t·p1 < t·p0, so p1 is extremity 0. Both extremities are vertices of B (its edge is the
// shorter) over the box's edge: each is that vertex–edge contact, normal (0,1), gap p.y,
// point (p.x, ½ p.y).
TEST(ShadowOverlap, NearParallelEdgesStillTwoPoints) {
  const double e = 1e-3;
  for (double s : {0.0, 2e-3}) {
    SCOPED_TRACE(s);
    const Shape A = box(-3, -1, 3, 0);
    const Shape B = moved(box(-0.5, 0, 0.5, 1), e, {0, -s});
    const Vec2 p0{-0.5 * std::cos(e), -0.5 * std::sin(e) - s}, p1{0.5 * std::cos(e), 0.5 * std::sin(e) - s};
    const auto r = detect(A, B, 1.25e-3);
    ASSERT_EQ(r.count, 2);
    expect_point(r.points[0], p1.y, {0, 1}, {p1.x, 0.5 * p1.y}, make_feature(FK::EdgeEdge, 2, 0, 0));
    expect_point(r.points[1], p0.y, {0, 1}, {p0.x, 0.5 * p0.y}, make_feature(FK::EdgeEdge, 2, 0, 1));
  }
  // with alert 1e-4 < ½ sin ε the second corner is out of reach: one vertex–edge point p0,
  // gap p0.y = −½ sin ε along (0,1), point (p0.x, ½ p0.y)
  const Shape B = moved(box(-0.5, 0, 0.5, 1), e);
  const auto r = detect(box(-3, -1, 3, 0), B, 1e-4);
  ASSERT_EQ(r.count, 1);
  expect_point(r.points[0], -0.5 * std::sin(e), {0, 1}, {-0.5 * std::cos(e), -0.25 * std::sin(e)},
               make_feature(FK::CandidateVertexOnAntagonistEdge, 0, 2));
}

// ---- deep overlap ----------------------------------------------------------------------------------

// A = [−1,1]². B = [−0.1,0.1]² centred at (0.3, 1): half inside through the top, depth 0.1;
// shov is 0.1 on (0,1) and 0.8 on (1,0): n = (0,1), points at x = 0.4 and 0.2, y = 0.95.
// Centred at (1, 0.3): through the right edge 1, n = (1,0), t = (0,1): points y = 0.2, 0.4 at
// x = 0.95 (B's left edge is edge 3). The 30° square of side 0.2 with its corner 0.05 deep:
// neighbours 0.05 and 0.123 above the line, vertex–edge with gap −0.05.
TEST(ShadowOverlap, DeepOverlapGapIsMinusDepth) {
  const Shape A = box(-1, -1, 1, 1);
  const auto top = detect(A, box(0.2, 0.9, 0.4, 1.1), 1e-3);
  ASSERT_EQ(top.count, 2);
  expect_point(top.points[0], -0.1, {0, 1}, {0.4, 0.95}, make_feature(FK::EdgeEdge, 2, 0, 0));
  expect_point(top.points[1], -0.1, {0, 1}, {0.2, 0.95}, make_feature(FK::EdgeEdge, 2, 0, 1));
  const auto right = detect(A, box(0.9, 0.2, 1.1, 0.4), 1e-3);
  ASSERT_EQ(right.count, 2);
  expect_point(right.points[0], -0.1, {1, 0}, {0.95, 0.2}, make_feature(FK::EdgeEdge, 1, 3, 0));
  expect_point(right.points[1], -0.1, {1, 0}, {0.95, 0.4}, make_feature(FK::EdgeEdge, 1, 3, 1));
  const Shape small = moved(box(-0.1, -0.1, 0.1, 0.1), kPi / 6.0, {0.3, 1.0 + 0.1 * (kC30 + kS30) - 0.05});
  const auto v = detect(A, small, 1e-3);
  ASSERT_EQ(v.count, 1);
  expect_point(v.points[0], -0.05, {0, 1}, {0.3 + 0.1 * (kS30 - kC30), 0.975}, make_feature(FK::CandidateVertexOnAntagonistEdge, 0, 2));
}

// ---- symmetric configurations -------------------------------------------------------------------

// Two unit squares stacked exactly, overlap 0.001: with the lower one as antagonist n = (0,1),
// t = (−1,0), points (0.5, 0.4995) then (−0.5, 0.4995); with the upper one as antagonist
// n = (0,−1), t = (1,0), points (−0.5, 0.4995) then (0.5, 0.4995), its bottom edge 0 against
// the candidate's top edge 2.
TEST(ShadowOverlap, IdenticalSquaresStackedExactly) {
  const Shape lo = box(-0.5, -0.5, 0.5, 0.5), hi = box(-0.5, 0.499, 0.5, 1.499);
  const auto r = detect(lo, hi, 1e-3);
  ASSERT_EQ(r.count, 2);
  expect_point(r.points[0], -0.001, {0, 1}, {0.5, 0.4995}, make_feature(FK::EdgeEdge, 2, 0, 0));
  expect_point(r.points[1], -0.001, {0, 1}, {-0.5, 0.4995}, make_feature(FK::EdgeEdge, 2, 0, 1));
  const auto s = detect(hi, lo, 1e-3);
  ASSERT_EQ(s.count, 2);
  expect_point(s.points[0], -0.001, {0, -1}, {-0.5, 0.4995}, make_feature(FK::EdgeEdge, 0, 2, 0));
  expect_point(s.points[1], -0.001, {0, -1}, {0.5, 0.4995}, make_feature(FK::EdgeEdge, 0, 2, 1));
}

// Pentagon A (d = 1, vertex 0 down at −90°): vertices at −90°, −18°, 54°, 126°, 198°; top edge 2
// from (½ sin36, ½ cos36) to (−½ sin36, ½ cos36). B its mirror image through y = ½ cos36 − δ/2:
// vertex 0 up, centre (0, cos36 − δ), bottom edge 2 from 234° to 306°. Overlap δ = 1e-3.
// Points x = ±½ sin36, y = ½ cos36 − δ/2; n = (0,1) (first point x > 0), or (0,−1) swapped.
TEST(ShadowOverlap, MirroredPentagonPair) {
  const double d = 1e-3, y = 0.5 * kCos36 - 0.5 * d, x = 0.5 * kSin36;
  const Shape A = regular(5, 1.0, -kPi / 2, {0, 0}), B = regular(5, 1.0, kPi / 2, {0, kCos36 - d});
  const auto r = detect(A, B, 1e-3);
  ASSERT_EQ(r.count, 2);
  expect_point(r.points[0], -d, {0, 1}, {x, y}, make_feature(FK::EdgeEdge, 2, 2, 0));
  expect_point(r.points[1], -d, {0, 1}, {-x, y}, make_feature(FK::EdgeEdge, 2, 2, 1));
  const auto s = detect(B, A, 1e-3);
  ASSERT_EQ(s.count, 2);
  expect_point(s.points[0], -d, {0, -1}, {-x, y}, make_feature(FK::EdgeEdge, 2, 2, 0));
  expect_point(s.points[1], -d, {0, -1}, {x, y}, make_feature(FK::EdgeEdge, 2, 2, 1));
}

// Coincident centres: the start direction is undefined (the code takes (1,0)). Identical unit
// squares: shov = 1 on every edge normal, so some contact with gap −1. A triangle inside a
// hexagon, same centre: some contact, gap <= −(the smaller depth), finite unit normal.
TEST(ShadowOverlap, CoincidentCentres) {
  const auto r = detect(box(-0.5, -0.5, 0.5, 0.5), box(-0.5, -0.5, 0.5, 0.5), 1e-3);
  ASSERT_GE(r.count, 1);
  for (int k = 0; k < r.count; ++k) {
    EXPECT_NEAR(r.points[k].gap, -1.0, kTol);
    EXPECT_NEAR(norm(r.points[k].normal), 1.0, kTol);
  }
  const auto t = detect(regular(6, 2.0, 0.1, {0.3, 0.3}), regular(3, 0.5, 0.7, {0.3, 0.3}), 1e-3);
  ASSERT_GE(t.count, 1);
  EXPECT_TRUE(std::isfinite(t.points[0].gap) && std::isfinite(t.points[0].point.x));
  EXPECT_LT(t.points[0].gap, -0.5);  // depth >= apothem of the hexagon (0.866) − triangle radius (0.25)
}

// The walk keeps V in the half-plane V·G_A G_B > 0 (paper §2.3), also on its first move.
// A: triangle, circumradius 2 (apothem 1), vertices at 270°, 30°, 150°, normals of edges 0, 1, 2
// at 330°, 90°, 210°. B: triangle, circumradius 4 (apothem 2), vertices at 190°, 310°, 70°
// about G_B = 0.1 (cos 95°, sin 95°); minus its normals: 70°, 190°, 310°. With δ = |G_A G_B|,
// shov(U) = supp_A(U) + supp_B0(−U) − δ cos(U − 95°):
//   U =  90° (A's normal, 5° from the start):  1 + 4 cos 40° − δ cos 5°  = 4.064 − 0.0996
//   U = 190° (95° from the start, outside):    2 cos 40° + 2 + 0.0087    = 3.541
//   U =  70° (B's, 25° from the start):        2 cos 40° + 2 − δ cos 25° = 3.442
// The better neighbour of the start (190°) lies outside the half-plane: the walk must take
// 90°, then 70° (a local minimum: its other neighbour 330° is outside). There A's corner at 30°
// intrudes, and its neighbour at 150° too (deep overlap): edge–edge between A's edge 1
// (normal 90°) and B's edge 0 (minus normal 70°); each extremity takes the normal of the edge
// its vertex faces, 90° under a vertex of B, 70° under a vertex of A.
TEST(ShadowOverlap, WalkStaysInTheCentreHalfPlane) {
  const Vec2 gB = 0.1 * Vec2{std::cos(95.0 * kPi / 180.0), std::sin(95.0 * kPi / 180.0)};
  Shape A = regular(3, 4.0, -kPi / 2, {0, 0}), B = regular(3, 8.0, 190.0 * kPi / 180.0, gB);
  A.g = {0, 0};
  B.g = gB;
  const auto r = detect(A, B, 1e-3);
  ASSERT_EQ(r.count, 2);
  const Vec2 n70{std::cos(70.0 * kPi / 180.0), std::sin(70.0 * kPi / 180.0)}, n90{0.0, 1.0};
  for (int k = 0; k < 2; ++k) {
    const Vec2 n = r.points[k].normal;
    EXPECT_TRUE(norm(n - n70) < kTol || norm(n - n90) < kTol) << "normal (" << n.x << ", " << n.y << ")";
    EXPECT_LT(r.points[k].gap, 0.0);
    EXPECT_GT(dot(r.points[k].normal, gB), 0.0);
    EXPECT_EQ(r.points[k].feature, make_feature(FK::EdgeEdge, 1, 0, static_cast<std::uint32_t>(k)));
  }
  EXPECT_EQ(r.rotations, 2);
}

// ---- rotated scenes: the answer rotates with the scene ----------------------------------------

TEST(ShadowOverlap, RotatedScenesGiveRotatedAnswers) {
  struct Scene { Shape A, B; double alert; };
  const Vec2 c{0.5, 0.5 * (kC30 + kS30) - 0.01};
  const std::vector<Scene> scenes = {
      {box(-2, -1, 2, 0), square30(c), 1e-3},                                   // vertex–edge
      {square30(c), box(-2, -1, 2, 0), 1e-3},                                   // roles swapped
      {box(0, -1, 4, 0), box(3, -0.002, 5, 0.998), 1e-3},                       // partial edge–edge
      {box(-3, -1, 3, 0), box(-0.5, -0.001, 0.5, 0.999), 1e-3},                 // nested
      {box(-3, -1, 3, 0), moved(box(-0.5, 0, 0.5, 1), 1e-3), 1.25e-3},          // near-parallel
      {regular(5, 1.0, -kPi / 2, {0, 0}), regular(5, 1.0, kPi / 2, {0.2, kCos36 - 1e-3}), 1e-3}};
  for (double deg : {30.0, 137.0}) {
    const double a = deg * kPi / 180.0;
    const Rot2 R = Rot2::of(a);
    const Vec2 off{0.3, -0.7};
    for (std::size_t i = 0; i < scenes.size(); ++i) {
      SCOPED_TRACE(testing::Message() << deg << " deg, scene " << i);
      const auto& s = scenes[i];
      const auto ref = detect(s.A, s.B, s.alert);
      const auto rot = detect(moved(s.A, a, off), moved(s.B, a, off), s.alert);
      ASSERT_GE(ref.count, 1);
      ASSERT_EQ(rot.count, ref.count);
      for (int k = 0; k < ref.count; ++k)
        expect_point(rot.points[k], ref.points[k].gap, R.apply(ref.points[k].normal), off + R.apply(ref.points[k].point),
                     ref.points[k].feature, 1e-11);
    }
  }
}

// ---- size ratio 1:100 and the ballast pentagons -------------------------------------------------

// Pentagon B (diameter dB) on the flat top of A. A: vertex 0 down (orientation −90°), top edge
// 2 at y = rA cos36 spanning x in [−rA sin36, rA sin36]. Vertex–edge: B vertex 0 down at
// (xo, rA cos36 − δ) — its neighbours are rB(1 − sin18) ≥ 3.4 mm higher, beyond the alert —
// gap −δ, point (xo, rA cos36 − δ/2). Edge–edge: B vertex 0 up, bottom edge 2 (234°→306°) at
// y = cB − rB cos36 spanning [xo − rB sin36, xo + rB sin36]; the extremities are the ends of
// the intersection of both spans, the larger x first (t = (−1,0)); gap −δ.
struct PentagonCase {
  int count;
  double gap;
  Vec2 p[2];
  std::uint32_t f[2];
};

PentagonCase pentagon_on_top(double rA, double rB, double xo, double delta, bool edge) {
  PentagonCase e{};
  const double ytop = rA * kCos36;
  if (!edge) {
    e.count = 1;
    e.gap = -delta;
    e.p[0] = {xo, ytop - 0.5 * delta};
    e.f[0] = make_feature(FK::CandidateVertexOnAntagonistEdge, 0, 2);
    return e;
  }
  const double hi = std::min(rA * kSin36, xo + rB * kSin36), lo = std::max(-rA * kSin36, xo - rB * kSin36);
  e.count = 2;
  e.gap = -delta;
  e.p[0] = {hi, ytop - 0.5 * delta};
  e.p[1] = {lo, ytop - 0.5 * delta};
  e.f[0] = make_feature(FK::EdgeEdge, 2, 2, 0);
  e.f[1] = make_feature(FK::EdgeEdge, 2, 2, 1);
  return e;
}

void check_pentagon_on_top(double dA, double dB, double xo, double delta, bool edge, double alert) {
  const double rA = 0.5 * dA, rB = 0.5 * dB;
  const Shape A = regular(5, dA, -kPi / 2, {0, 0});
  const Shape B = edge ? regular(5, dB, kPi / 2, {xo, rA * kCos36 + rB * kCos36 - delta})
                       : regular(5, dB, -kPi / 2, {xo, rA * kCos36 + rB - delta});
  const PentagonCase e = pentagon_on_top(rA, rB, xo, delta, edge);
  for (double deg : {0.0, 30.0, 137.0}) {
    SCOPED_TRACE(testing::Message() << "dA " << dA << " dB " << dB << " xo " << xo << " delta " << delta
                                    << (edge ? " edge" : " vertex") << " rotated " << deg);
    const double a = deg * kPi / 180.0;
    const Rot2 R = Rot2::of(a);
    const Vec2 off{0.37, 0.11};
    const auto r = detect(moved(A, a, off), moved(B, a, off), alert);
    if (-delta > alert) {
      EXPECT_EQ(r.count, 0);
      continue;
    }
    ASSERT_EQ(r.count, e.count);
    for (int k = 0; k < e.count; ++k)
      expect_point(r.points[k], e.gap, R.apply({0, 1}), off + R.apply(e.p[k]), e.f[k], 1e-12);
    // roles swapped (B antagonist): normal (0,−1), same points; vertex–edge becomes B's corner 0
    // on A's edge 2; edge–edge has t = (1,0), so the extremities come in the other order
    const auto s = detect(moved(B, a, off), moved(A, a, off), alert);
    ASSERT_EQ(s.count, e.count);
    for (int k = 0; k < e.count; ++k) {
      const int m = e.count == 2 ? 1 - k : k;
      const std::uint32_t f = edge ? make_feature(FK::EdgeEdge, 2, 2, static_cast<std::uint32_t>(k))
                                   : make_feature(FK::AntagonistVertexOnCandidateEdge, 0, 2);
      expect_point(s.points[k], e.gap, R.apply({0, -1}), off + R.apply(e.p[m]), f, 1e-12);
    }
  }
}

TEST(ShadowOverlap, CentimetrePentagonOnMetreBox) {
  // box [−0.5,0.5]×[−0.1,0] (top edge 2), pentagon d = 1 cm (r = 5 mm), δ = 1e-4:
  // vertex–edge: vertex 0 down at (xo, −δ): gap −1e-4, point (xo, −5e-5);
  // edge–edge: bottom edge y = −δ from xo − r sin36 to xo + r sin36 (= ±2.939 mm).
  const double d = 0.01, r = 0.005, dl = 1e-4;
  for (double xo : {0.0, 0.123, -0.4}) {
    SCOPED_TRACE(xo);
    const auto v = detect(box(-0.5, -0.1, 0.5, 0), regular(5, d, -kPi / 2, {xo, r - dl}), 1.25e-3);
    ASSERT_EQ(v.count, 1);
    expect_point(v.points[0], -dl, {0, 1}, {xo, -0.5 * dl}, make_feature(FK::CandidateVertexOnAntagonistEdge, 0, 2));
    const auto e = detect(box(-0.5, -0.1, 0.5, 0), regular(5, d, kPi / 2, {xo, r * kCos36 - dl}), 1.25e-3);
    ASSERT_EQ(e.count, 2);
    expect_point(e.points[0], -dl, {0, 1}, {xo + r * kSin36, -0.5 * dl}, make_feature(FK::EdgeEdge, 2, 2, 0));
    expect_point(e.points[1], -dl, {0, 1}, {xo - r * kSin36, -0.5 * dl}, make_feature(FK::EdgeEdge, 2, 2, 1));
  }
}

TEST(ShadowOverlap, BallastPentagons) {
  // diameters of the grading: 1, 1.5, 2 cm; every ordered pair, vertex–edge and edge–edge,
  // overlapping (δ = 2e-4), separated within the alert (δ = −5e-4) and beyond it (δ = −2e-3),
  // offset xo = 0.3 rA sin36 (nested or partial common segment), scene rotated 0°, 30°, 137°
  const double alert = 1.25e-3;
  for (double dA : {0.01, 0.015, 0.02})
    for (double dB : {0.01, 0.015, 0.02})
      for (bool edge : {false, true})
        for (double delta : {2e-4, -5e-4, -2e-3}) check_pentagon_on_top(dA, dB, 0.3 * 0.5 * dA * kSin36, delta, edge, alert);
}

}  // namespace
