// Narrow phases of the round contactors (DKDKx, DKKDx, DKPLx, DKJCx, PLJCx, PLKDx) and the mass
// properties of DISKx and JONCx: hand-computed configurations, then a property check on many
// random ones (the reported points lie on both boundaries, the gap is the signed distance).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "nscd/contactors/round_shapes.hpp"
#include "nscd/core/error.hpp"
#include "nscd/interactions/round_pairs.hpp"

namespace nscd {
namespace {

constexpr double kTol = 1e-12;

// A convex polygon in world coordinates with its edge normals.
struct Poly {
  std::vector<Vec2> v, n;
  ConvexView view() const { return {v.data(), n.data(), static_cast<std::uint32_t>(v.size())}; }
};
Poly make_poly(std::vector<Vec2> v) {
  Poly p{std::move(v), {}};
  for (std::size_t k = 0; k < p.v.size(); ++k) {
    const Vec2 e = p.v[(k + 1) % p.v.size()] - p.v[k];
    p.n.push_back(normalized(Vec2{e.y, -e.x}));
  }
  return p;
}
Poly square(Vec2 c, double h, double angle = 0.0) {
  const Rot2 R = Rot2::of(angle);
  return make_poly({c + R.apply({-h, -h}), c + R.apply({h, -h}), c + R.apply({h, h}), c + R.apply({-h, h})});
}

// Signed distance from x to the polygon's boundary (negative inside), by brute force.
double signed_distance(const Poly& p, Vec2 x) {
  double d = INFINITY;
  bool inside = true;
  for (std::size_t k = 0; k < p.v.size(); ++k) {
    const Vec2 a = p.v[k], b = p.v[(k + 1) % p.v.size()];
    double s = dot(x - a, b - a) / dot(b - a, b - a);
    s = std::clamp(s, 0.0, 1.0);
    d = std::min(d, norm(x - (a + s * (b - a))));
    if (dot(x - a, p.n[k]) > 0.0) inside = false;
  }
  return inside ? -d : d;
}

TEST(RoundPairs, DiskOnDisk) {
  const PairContacts r = dkdkx({{0, 0}, 1.0}, {{3, 4}, 2.0}, 1e-3);
  ASSERT_EQ(r.count, 0);  // gap 2 > alert
  const PairContacts s = dkdkx({{0, 0}, 1.0}, {{0.6, 0.8 * 1.0 + 0.0}, 0.5}, 1.0);
  ASSERT_EQ(s.count, 1);
  EXPECT_NEAR(s.points[0].gap, 1.0 - 1.5, kTol);
  EXPECT_NEAR(s.points[0].normal.x, 0.6, kTol);
  EXPECT_NEAR(s.points[0].normal.y, 0.8, kTol);
  // halfway between the antagonist's boundary (0.6, 0.8) and the candidate's (0.3, 0.4)
  EXPECT_NEAR(s.points[0].point.x, 0.45, kTol);
  EXPECT_NEAR(s.points[0].point.y, 0.6, kTol);
}

TEST(RoundPairs, DiskInsideRing) {
  // a disk of radius 0.1 at (0.85, 0) in a drum of radius 1: gap 0.05, normal toward the centre
  const PairContacts r = dkkdx({{0, 0}, 1.0}, {{0.85, 0.0}, 0.1}, 0.1);
  ASSERT_EQ(r.count, 1);
  EXPECT_NEAR(r.points[0].gap, 0.05, kTol);
  EXPECT_NEAR(r.points[0].normal.x, -1.0, kTol);
  EXPECT_NEAR(r.points[0].point.x, 0.975, kTol);
  EXPECT_EQ(dkkdx({{0, 0}, 1.0}, {{0.5, 0.0}, 0.1}, 0.1).count, 0);
}

TEST(RoundPairs, PolygonInsideRing) {
  // a square of half-side 0.1 resting flat at the bottom of a drum of radius 1: its two bottom
  // corners at distance sqrt(0.1² + y²) from the centre; put them exactly on the wall
  const double y = -std::sqrt(1.0 - 0.01);
  const Poly sq = square({0.0, y + 0.1}, 0.1);
  const PairContacts r = plkdx({{0, 0}, 1.0}, sq.view(), 1e-3);
  ASSERT_EQ(r.count, 2);  // the two bottom corners, the top ones far from the wall
  for (int k = 0; k < 2; ++k) {
    const ContactPoint& p = r.points[k];
    EXPECT_NEAR(p.gap, 0.0, kTol);
    EXPECT_NEAR(norm(p.point), 1.0, kTol);                      // on the wall
    EXPECT_NEAR(dot(p.normal, (-1.0 / norm(p.point)) * p.point), 1.0, kTol);  // toward the centre
    EXPECT_NEAR(std::abs(p.point.x), 0.1, kTol);
    EXPECT_EQ(p.feature >> 30, 1u);
  }
  EXPECT_NE(r.points[0].feature, r.points[1].feature);
  // tilted: one corner 0.02 into the wall, the other lifted by more than the alert
  const Poly tilted = square({0.0, y + 0.1}, 0.1, 0.3);
  const PairContacts t = plkdx({{0, 0}, 1.0}, tilted.view(), 1e-3);
  ASSERT_EQ(t.count, 1);
  double deepest = INFINITY;
  for (const Vec2& v : tilted.v) deepest = std::min(deepest, 1.0 - norm(v));
  EXPECT_NEAR(t.points[0].gap, deepest, kTol);
  EXPECT_LT(t.points[0].gap, 0.0);
  // in the middle of the drum: nothing
  EXPECT_EQ(plkdx({{0, 0}, 1.0}, square({0.0, 0.0}, 0.1).view(), 1e-3).count, 0);
}

TEST(RoundPairs, PolygonInsideRingRandomConfigurations) {
  // every point is a vertex on the wall's normal line: gap = R − |v − c| for that vertex, the
  // antagonist's point on the circle, and no vertex deeper than the first point
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.9, 0.9), ang(0.0, 2 * kPi), side(0.02, 0.3);
  int two = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Poly sq = square({u(rng), u(rng)}, side(rng), ang(rng));
    const RingView ring{{0.0, 0.0}, 1.0};
    const PairContacts r = plkdx(ring, sq.view(), 0.05);
    double deepest = INFINITY;
    for (const Vec2& v : sq.v) deepest = std::min(deepest, 1.0 - norm(v));
    if (deepest > 0.05) {
      EXPECT_EQ(r.count, 0);
      continue;
    }
    ASSERT_GE(r.count, 1);
    EXPECT_NEAR(r.points[0].gap, deepest, 1e-12);
    for (int k = 0; k < r.count; ++k) {
      const ContactPoint& p = r.points[k];
      const Vec2 pa = p.point - 0.5 * p.gap * p.normal, pc = p.point + 0.5 * p.gap * p.normal;
      EXPECT_NEAR(norm(pa), 1.0, 1e-12);
      EXPECT_NEAR(norm(pc - sq.v[p.feature & 0x3FFFFFFFu]), 0.0, 1e-12);  // the candidate's point is its vertex
      EXPECT_NEAR(norm(p.normal), 1.0, kTol);
      EXPECT_LE(p.gap, 0.05);
    }
    two += r.count == 2;
  }
  EXPECT_GT(two, 10);  // the sample covers two-point contacts
}

TEST(RoundPairs, DiskOnPolygonEdgeVertexAndInside) {
  const Poly sq = square({0, 0}, 1.0);
  // above the top edge: normal +y, gap 0.5 − 0.25
  PairContacts r = dkplx(sq.view(), {{0.3, 1.5}, 0.25}, 1.0);
  ASSERT_EQ(r.count, 1);
  EXPECT_NEAR(r.points[0].gap, 0.25, kTol);
  EXPECT_NEAR(r.points[0].normal.y, 1.0, kTol);
  EXPECT_EQ(r.points[0].feature, (1u << 30) | 2u);  // edge 2 = (v2, v3), the top
  // beyond the corner (1, 1): the normal points from the corner to the centre
  r = dkplx(sq.view(), {{1.3, 1.4}, 0.4}, 1.0);
  ASSERT_EQ(r.count, 1);
  EXPECT_NEAR(r.points[0].gap, 0.5 - 0.4, kTol);
  EXPECT_NEAR(r.points[0].normal.x, 0.6, kTol);
  EXPECT_NEAR(r.points[0].normal.y, 0.8, kTol);
  EXPECT_EQ(r.points[0].feature, (2u << 30) | 2u);  // vertex 2 = (1, 1)
  // the centre inside, nearest the right edge: gap −0.2 − r
  r = dkplx(sq.view(), {{0.8, 0.1}, 0.1}, 1.0);
  ASSERT_EQ(r.count, 1);
  EXPECT_NEAR(r.points[0].gap, -0.3, kTol);
  EXPECT_NEAR(r.points[0].normal.x, 1.0, kTol);
  EXPECT_EQ(dkplx(sq.view(), {{3, 0}, 0.5}, 1.0).count, 0);
}

TEST(RoundPairs, DiskOnJoncFaceAndEnds) {
  const JoncView wall{{0, 0}, {1, 0}, 2.0, 0.1};
  PairContacts r = dkjcx(wall, {{0.5, -0.5}, 0.3}, 1.0);  // below the face
  ASSERT_EQ(r.count, 1);
  EXPECT_NEAR(r.points[0].gap, 0.5 - 0.1 - 0.3, kTol);
  EXPECT_NEAR(r.points[0].normal.y, -1.0, kTol);
  EXPECT_EQ(r.points[0].feature, 1u);
  r = dkjcx(wall, {{2.3, 0.4}, 0.2}, 1.0);  // beyond the +a end: round end
  ASSERT_EQ(r.count, 1);
  EXPECT_NEAR(r.points[0].gap, 0.5 - 0.1 - 0.2, kTol);
  EXPECT_NEAR(r.points[0].normal.x, 0.6, kTol);
  EXPECT_EQ(r.points[0].feature, 3u);
  r = dkjcx(wall, {{-1.0, 0.0}, 0.2}, 1.0);  // centre on the core segment
  ASSERT_EQ(r.count, 1);
  EXPECT_NEAR(r.points[0].gap, -0.3, kTol);
  EXPECT_NEAR(r.points[0].normal.y, 1.0, kTol);
}

TEST(RoundPairs, PolygonOnJonc) {
  const JoncView floor{{0, 0}, {1, 0}, 5.0, 0.05};
  // a square resting flat, 0.01 into the floor: two points, one under each bottom vertex
  PairContacts r = pljcx(floor, square({0.5, 0.54}, 0.5).view(), 0.02);
  ASSERT_EQ(r.count, 2);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(r.points[k].gap, -0.01, kTol);
    EXPECT_NEAR(r.points[k].normal.y, 1.0, kTol);
    EXPECT_NEAR(r.points[k].point.y, 0.045, kTol);
  }
  EXPECT_NEAR(std::abs(r.points[0].point.x - r.points[1].point.x), 1.0, kTol);
  // on a corner (45°): one point
  r = pljcx(floor, square({0.0, 0.05 + std::sqrt(2.0) * 0.5 - 0.001}, 0.5, kPi / 4).view(), 0.02);
  ASSERT_EQ(r.count, 1);
  EXPECT_NEAR(r.points[0].gap, -0.001, 1e-12);
  // overhanging the +a end: one vertex on the face, and the round end under the bottom edge
  r = pljcx(floor, square({5.0, 0.54}, 0.5).view(), 0.02);
  ASSERT_EQ(r.count, 2);
  const double xs[2] = {std::min(r.points[0].point.x, r.points[1].point.x), std::max(r.points[0].point.x, r.points[1].point.x)};
  EXPECT_NEAR(xs[0], 4.5, kTol);
  EXPECT_NEAR(xs[1], 5.0, kTol);
  EXPECT_NEAR(r.points[0].normal.y, 1.0, kTol);
  EXPECT_NEAR(r.points[1].normal.y, 1.0, kTol);
  EXPECT_EQ(pljcx(floor, square({0.0, 2.0}, 0.5).view(), 0.02).count, 0);
}

// Random configurations: the antagonist's boundary point (point − g/2 n) lies on the
// antagonist, the candidate's (point + g/2 n) on the candidate, and g is the signed distance.
TEST(RoundPairs, RandomConfigurationsPutPointsOnBothBoundaries) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(-1.5, 1.5), ang(0.0, 2 * kPi), rad(0.05, 0.6);
  const Poly pent = [] {
    std::vector<Vec2> v;
    for (int k = 0; k < 5; ++k) v.push_back({0.8 * std::cos(2 * kPi * k / 5 + 0.3), 0.8 * std::sin(2 * kPi * k / 5 + 0.3)});
    return make_poly(v);
  }();
  int hits_pl = 0, hits_jc = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const DiskView d{{u(rng), u(rng)}, rad(rng)};
    const PairContacts r = dkplx(pent.view(), d, 10.0);
    ASSERT_EQ(r.count, 1);
    const ContactPoint& p = r.points[0];
    EXPECT_NEAR(norm(p.normal), 1.0, kTol);
    EXPECT_NEAR(signed_distance(pent, p.point - 0.5 * p.gap * p.normal), 0.0, 1e-12);
    EXPECT_NEAR(norm(p.point + 0.5 * p.gap * p.normal - d.centre), d.radius, 1e-12);
    EXPECT_NEAR(p.gap, signed_distance(pent, d.centre) - d.radius, 1e-12);
    hits_pl += p.gap < 0.0;

    const JoncView j{{u(rng), u(rng)}, Rot2::of(ang(rng)).apply({1, 0}), 0.5 * rad(rng), 0.3 * rad(rng)};
    const PairContacts q = dkjcx(j, d, 10.0);
    ASSERT_EQ(q.count, 1);
    const Vec2 pa = q.points[0].point - 0.5 * q.points[0].gap * q.points[0].normal;
    // the antagonist's point is at distance b from the core segment
    const Vec2 p0 = j.centre - j.half_length * j.axis, p1 = j.centre + j.half_length * j.axis;
    const double s = std::clamp(dot(pa - p0, p1 - p0) / dot(p1 - p0, p1 - p0), 0.0, 1.0);
    EXPECT_NEAR(norm(pa - (p0 + s * (p1 - p0))), j.half_thickness, 1e-12);
    EXPECT_NEAR(norm(q.points[0].point + 0.5 * q.points[0].gap * q.points[0].normal - d.centre), d.radius, 1e-12);
    hits_jc += q.points[0].gap < 0.0;
  }
  EXPECT_GT(hits_pl, 100);  // the sample covers overlaps and separations
  EXPECT_GT(hits_jc, 100);
}

// PLPLx's sibling on random configurations: every point lies on both boundaries, and when the
// polygon and the capsule are apart the deepest point's gap is their distance (found here by
// sampling the core segment finely: accurate to ~1e-4 of the scene size).
TEST(RoundPairs, PolygonOnJoncRandomConfigurations) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.2, 1.2), ang(0.0, 2 * kPi);
  std::vector<Vec2> v;
  for (int k = 0; k < 5; ++k) v.push_back({0.5 * std::cos(2 * kPi * k / 5), 0.5 * std::sin(2 * kPi * k / 5)});
  const Poly pent = make_poly(v);
  int apart = 0, two = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const JoncView j{{u(rng), u(rng)}, Rot2::of(ang(rng)).apply({1, 0}), 0.6, 0.05};
    const PairContacts r = pljcx(j, pent.view(), 10.0);
    ASSERT_GE(r.count, 1);
    const Vec2 p0 = j.centre - j.half_length * j.axis, p1 = j.centre + j.half_length * j.axis;
    double sampled = INFINITY;
    for (int i = 0; i <= 20000; ++i) sampled = std::min(sampled, signed_distance(pent, p0 + (i / 20000.0) * (p1 - p0)));
    if (sampled <= 0.0) continue;  // the core segment enters the polygon: see PolygonPiercedByJonc
    ++apart;
    EXPECT_NEAR(r.points[0].gap, sampled - j.half_thickness, 1e-4);
    for (int k = 0; k < r.count; ++k) {
      const ContactPoint& p = r.points[k];
      EXPECT_NEAR(norm(p.normal), 1.0, kTol);
      const Vec2 pa = p.point - 0.5 * p.gap * p.normal, pc = p.point + 0.5 * p.gap * p.normal;
      const double s = std::clamp(dot(pa - p0, p1 - p0) / dot(p1 - p0, p1 - p0), 0.0, 1.0);
      EXPECT_NEAR(norm(pa - (p0 + s * (p1 - p0))), j.half_thickness, 1e-12);
      EXPECT_NEAR(signed_distance(pent, pc), 0.0, 1e-12);
    }
    two += r.count == 2;
  }
  EXPECT_GT(apart, 200);
  EXPECT_GT(two, 0);
}

// A wall through the middle of a square, no vertex near it (only after a violent step): one
// point on the least penetrating axis, pushing the square off the wall's face.
TEST(RoundPairs, PolygonPiercedByJonc) {
  const JoncView wall{{0, 0}, {1, 0}, 3.0, 0.05};
  const PairContacts r = pljcx(wall, square({0.0, 0.3}, 1.0).view(), 0.01);
  ASSERT_EQ(r.count, 1);
  EXPECT_NEAR(r.points[0].normal.y, 1.0, kTol);
  EXPECT_NEAR(r.points[0].gap, -0.7 - 0.05, kTol);  // the bottom edge 0.7 below the core, b = 0.05
  // a short wall parallel to the right edge, inside the square: both round ends, the edge's normal
  const PairContacts s = pljcx({{0.8, 0.0}, {0, 1}, 0.2, 0.05}, square({0.0, 0.0}, 1.0).view(), 0.01);
  ASSERT_EQ(s.count, 2);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(s.points[k].normal.x, -1.0, kTol);
    EXPECT_NEAR(s.points[k].gap, -0.2 - 0.05, kTol);
  }
  EXPECT_NEAR(std::abs(s.points[0].point.y - s.points[1].point.y), 0.4, kTol);
}

TEST(RoundShapes, RoundMass) {
  const RoundMass d = diskx_mass(0.1, 2000.0);
  EXPECT_NEAR(d.mass, 2000.0 * kPi * 0.01, 1e-12);
  EXPECT_NEAR(d.inertia, 0.5 * d.mass * 0.01, 1e-15);
  const RoundMass j0 = joncx_mass(0.0, 0.1, 2000.0);  // a = 0: the disk
  EXPECT_NEAR(j0.mass, d.mass, 1e-12);
  EXPECT_NEAR(j0.inertia, d.inertia, 1e-15);
  const RoundMass rod = joncx_mass(1.0, 1e-4, 1000.0);  // b → 0: a thin rod of length 2
  EXPECT_NEAR(rod.inertia / (rod.mass * 4.0 / 12.0), 1.0, 1e-3);
  // a = b: rectangle 2×1 ... compare with a fine numerical integration over the capsule
  const double a = 0.3, b = 0.2, rho = 1.0;
  double m = 0.0, I = 0.0;
  const int N = 1200;
  for (int ix = 0; ix < N; ++ix)
    for (int iy = 0; iy < N; ++iy) {
      const double x = -(a + b) + (ix + 0.5) * 2 * (a + b) / N, y = -b + (iy + 0.5) * 2 * b / N;
      const double cx = std::clamp(x, -a, a);
      if ((x - cx) * (x - cx) + y * y > b * b) continue;
      const double dA = (2 * (a + b) / N) * (2 * b / N);
      m += rho * dA;
      I += rho * dA * (x * x + y * y);
    }
  const RoundMass c = joncx_mass(a, b, rho);
  EXPECT_NEAR(c.mass / m, 1.0, 1e-4);
  EXPECT_NEAR(c.inertia / I, 1.0, 1e-4);
  EXPECT_THROW(diskx_mass(-1.0, 1.0), Error);
  EXPECT_THROW(joncx_mass(1.0, 0.0, 1.0), Error);
  EXPECT_THROW(joncx_mass(1.0, 0.1, NAN), Error);
}

}  // namespace
}  // namespace nscd
