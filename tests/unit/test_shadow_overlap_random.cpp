// tests/unit/test_shadow_overlap_random.cpp — the PLPLx narrow phase (Moreau's shadow overlap,
// interactions/shadow_overlap.hpp): a randomized property test against an independent
// separating-axis test and an exact polygon distance (the hand computations:
// test_shadow_overlap.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "nscd/interactions/shadow_overlap.hpp"
#include "shadow_overlap_fixtures.hpp"

namespace {

using namespace nscd;
using namespace nscd::shadow_overlap_fixtures;

// ---- randomized property test -----------------------------------------------------------------

// Independent separating-axis test: the smallest overlap of the two shadows over all edge
// normals of both polygons (both senses); < 0 means a separating axis exists. For convex
// polygons it equals the minimum penetration depth when they overlap.
double sat_min_overlap(const Shape& P, const Shape& Q) {
  double best = 1e300;
  auto axis = [&](Vec2 u) {
    double p0 = 1e300, p1 = -1e300, q0 = 1e300, q1 = -1e300;
    for (Vec2 a : P.v) { p0 = std::min(p0, dot(a, u)); p1 = std::max(p1, dot(a, u)); }
    for (Vec2 b : Q.v) { q0 = std::min(q0, dot(b, u)); q1 = std::max(q1, dot(b, u)); }
    best = std::min({best, p1 - q0, q1 - p0});
  };
  for (Vec2 u : P.n) axis(u);
  for (Vec2 u : Q.n) axis(u);
  return best;
}

double point_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double u = std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
  return norm(p - (a + u * ab));
}

// Exact distance of two disjoint convex polygons: min over vertex–segment distances.
double exact_distance(const Shape& P, const Shape& Q) {
  double d = 1e300;
  for (int pass = 0; pass < 2; ++pass) {
    const Shape& X = pass ? Q : P;
    const Shape& Y = pass ? P : Q;
    for (Vec2 x : X.v)
      for (std::size_t k = 0; k < Y.v.size(); ++k) d = std::min(d, point_segment(x, Y.v[k], Y.v[(k + 1) % Y.v.size()]));
  }
  return d;
}

TEST(ShadowOverlap, RandomPairsAgainstSeparatingAxes) {
  std::mt19937_64 rng(20060101);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const double alert = 0.02;
  const int pairs = 200000;
  int overlapping = 0, separated_far = 0, separated_near = 0, vertex_edge = 0, not_global = 0, edge_edge = 0;
  int edge_below_sat = 0, edge_backward = 0, backward = 0, missed = 0, false_far = 0, false_overlap = 0, below_sat = 0, bad_point = 0;
  double worst_excess = 0.0;
  auto report = [](int& counter, int it, const char* what, double a, double b) {
    if (++counter <= 3) ADD_FAILURE() << "pair " << it << ": " << what << " (" << a << ", " << b << ")";
  };
  for (int it = 0; it < pairs; ++it) {
    const int nA = 3 + static_cast<int>(uni(rng) * 6), nB = 3 + static_cast<int>(uni(rng) * 6);
    // diameters 0.2–2, one pair in ten at a 1:100 ratio
    const double dA = 0.2 + 1.8 * uni(rng), dB = (it % 10 == 0 ? 0.01 : 1.0) * (0.2 + 1.8 * uni(rng));
    const Vec2 gA{4.0 * uni(rng) - 2.0, 4.0 * uni(rng) - 2.0};
    // centre distance: one pair in four anywhere from coincident to apart, the others in the
    // band where the polygons touch (sum of inradii to sum of circumradii, plus the alert)
    const double in_sum = 0.5 * (dA * std::cos(kPi / nA) + dB * std::cos(kPi / nB)), out_sum = 0.5 * (dA + dB) + 3.0 * alert;
    const double lo = it % 4 == 0 ? 0.0 : in_sum - 0.05 * std::min(dA, dB);
    const double dir = 2.0 * kPi * uni(rng), dist = lo + (out_sum - lo) * uni(rng);
    const Vec2 gB = gA + dist * Vec2{std::cos(dir), std::sin(dir)};
    const Shape A = regular(nA, dA, 2.0 * kPi * uni(rng), gA), B = regular(nB, dB, 2.0 * kPi * uni(rng), gB);
    const double sat = sat_min_overlap(A, B);
    const auto r = detect(A, B, alert);
    double min_gap = 1e300;
    for (int k = 0; k < r.count; ++k) {
      min_gap = std::min(min_gap, r.points[k].gap);
      if (!(std::abs(norm(r.points[k].normal) - 1.0) < 1e-12 && r.points[k].gap <= alert))
        report(bad_point, it, "non-unit normal or gap above the alert", r.points[k].gap, norm(r.points[k].normal));
      // the walk's V stays in the half-plane V·G_A G_B > 0 (paper §2.3); an edge–edge normal
      // averages V with the other edge's normal, which may leave it in deep overlaps
      if (!(dot(r.points[k].normal, gB - gA) > 0.0)) {
        if (feature_kind(r.points[k].feature) != FK::EdgeEdge)
          report(backward, it, "normal against G_A G_B: n·G_A G_B, gap", dot(r.points[k].normal, gB - gA), r.points[k].gap);
        else
          ++edge_backward;
      }
    }
    if (sat > 1e-12) {  // the polygons truly overlap
      ++overlapping;
      if (r.count == 0 || !(min_gap < 0.0)) { report(missed, it, "overlap missed: SAT depth, min gap", sat, min_gap); continue; }
      if (r.count == 1 && feature_kind(r.points[0].feature) != FK::EdgeEdge) {
        ++vertex_edge;
        // the walk may stop at a local minimum of shov, never below the global one
        if (-min_gap < sat - 1e-12) report(below_sat, it, "penetration below the SAT minimum", -min_gap, sat);
        if (-min_gap > sat + 1e-12) {
          ++not_global;
          worst_excess = std::max(worst_excess, (-min_gap - sat) / sat);
        }
      } else {
        ++edge_edge;  // penetration measured along the averaged normal: information only
        if (-min_gap < sat - 1e-12) ++edge_below_sat;
      }
    } else if (sat < -1e-12) {  // a separating axis exists
      const double d = exact_distance(A, B);
      if (d > alert) {
        ++separated_far;
        if (r.count != 0) report(false_far, it, "contact beyond the alert: distance, gap", d, min_gap);
      } else {
        ++separated_near;
        if (r.count > 0 && !(min_gap > 0.0)) report(false_overlap, it, "overlap reported for a separated pair", d, min_gap);
      }
    }
  }
  std::printf("[ random shadow overlap ] %d pairs: %d overlapping (%d vertex-edge, %d edge-edge), %d separated "
              "within alert, %d beyond; the walk stopped above the global SAT minimum in %d of %d vertex-edge cases "
              "(worst relative excess %.3g)\n",
              pairs, overlapping, vertex_edge, edge_edge, separated_near, separated_far, not_global, vertex_edge, worst_excess);
  std::printf("[ random shadow overlap ] edge-edge pairs whose deepest extremity is shallower than the SAT minimum: %d; "
              "edge-edge points whose averaged normal points against G_A G_B: %d\n",
              edge_below_sat, edge_backward);
  std::printf("[ random shadow overlap ] violations: missed %d, beyond alert %d, false overlap %d, below SAT %d, bad point %d, "
              "backward normal %d\n",
              missed, false_far, false_overlap, below_sat, bad_point, backward);
  EXPECT_EQ(missed + false_far + false_overlap + below_sat + bad_point + backward, 0);
  EXPECT_GT(overlapping, pairs / 10);
  EXPECT_GT(separated_far, pairs / 20);
}

}  // namespace
