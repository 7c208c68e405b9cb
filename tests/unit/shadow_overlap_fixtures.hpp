// tests/unit/shadow_overlap_fixtures.hpp — the polygons of the PLPLx narrow phase's tests
// (test_shadow_overlap.cpp, test_shadow_overlap_random.cpp): a convex polygon in world
// coordinates with its outward normals, a regular one, and the shadow overlap of two of them.
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "nscd/interactions/shadow_overlap.hpp"

namespace nscd::shadow_overlap_fixtures {

// ---- tiny helpers: a polygon in world coordinates with its outward normals ---------------------

struct Shape {
  std::vector<Vec2> v, n;  // counter-clockwise vertices, outward normal of edge k = (v_k, v_k+1)
  Vec2 g;                  // reference point (area centroid)
  ConvexView view() const { return {v.data(), n.data(), static_cast<std::uint32_t>(v.size())}; }
};

inline Shape make_shape(std::vector<Vec2> verts) {
  Shape s;
  s.v = std::move(verts);
  const std::size_t m = s.v.size();
  double a2 = 0.0;
  Vec2 c{};
  for (std::size_t k = 0; k < m; ++k) {
    const Vec2 p = s.v[k], q = s.v[(k + 1) % m], e = q - p;
    s.n.push_back(normalized(Vec2{e.y, -e.x}));  // outward for a counter-clockwise polygon
    a2 += cross(p, q);
    c += cross(p, q) * (p + q);
  }
  s.g = (1.0 / (3.0 * a2)) * c;
  return s;
}

// Regular n-gon, circumscribed diameter d, vertex 0 at angle `orient`, centred at c.
inline Shape regular(int n, double d, double orient, Vec2 c) {
  std::vector<Vec2> v;
  for (int k = 0; k < n; ++k) {
    const double a = orient + 2.0 * kPi * k / n;
    v.push_back(c + Vec2{0.5 * d * std::cos(a), 0.5 * d * std::sin(a)});
  }
  return make_shape(v);
}

inline ShadowOverlapResult detect(const Shape& A, const Shape& B, double alert) {
  return shadow_overlap(A.view(), A.g, B.view(), B.g, alert);
}

using FK = FeatureKind;

}  // namespace nscd::shadow_overlap_fixtures
