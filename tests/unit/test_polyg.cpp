// tests/unit/test_polyg.cpp — unit tests of src/contactors (POLYG): polygon validation with
// one test per defect, the polygon builders, mass properties against closed forms, and the
// bodies built from polygons (add_polygon_body, attach_polyg, world_polygon).
//
// Suites: PolygValidation, PolygBuilders, MassProperties, PolygBody.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "error_assertions.hpp"

namespace {

using nscd::testing_support::error_message;
using nscd::testing_support::Contains;

using namespace nscd;

/// The message validate_polygon gives for `v`, with the context "grain 7".
std::string defect(const Polygon& v) {
  return error_message([&] { validate_polygon(v, "grain 7"); });
}

void expect_near(Vec2 a, Vec2 b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
}

// ---- validation: one test per defect --------------------------------------------------------

TEST(PolygValidation, FewerThanThreeVertices) {
  const std::string m = defect({{0.0, 0.0}, {1.0, 0.0}});
  EXPECT_TRUE(Contains(m, "POLYG of grain 7"));
  EXPECT_TRUE(Contains(m, "at least 3 vertices, got 2"));
  EXPECT_TRUE(Contains(defect({}), "got 0"));
}

TEST(PolygValidation, NonFiniteVertex) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::string m = defect({{0.0, 0.0}, {nan, 0.0}, {0.0, 1.0}});
  EXPECT_TRUE(Contains(m, "POLYG of grain 7"));
  EXPECT_TRUE(Contains(m, "vertex 1 is not finite"));
  EXPECT_TRUE(Contains(defect({{0.0, 0.0}, {1.0, 0.0}, {0.0, inf}}), "vertex 2 is not finite"));
}

TEST(PolygValidation, RepeatedVertex) {
  const std::string m = defect({{0.0, 0.0}, {1.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}});
  EXPECT_TRUE(Contains(m, "POLYG of grain 7"));
  EXPECT_TRUE(Contains(m, "vertex 2 repeats vertex 1"));
  // the last vertex repeating the first (a closed ring given explicitly)
  EXPECT_TRUE(Contains(defect({{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {0.0, 0.0}}), "vertex 0 repeats vertex 3"));
}

TEST(PolygValidation, ClockwiseOrder) {
  const std::string m = defect({{0.0, 0.0}, {0.0, 1.0}, {1.0, 0.0}});
  EXPECT_TRUE(Contains(m, "POLYG of grain 7"));
  EXPECT_TRUE(Contains(m, "clockwise"));
  // a clockwise square: the reversed rectangle
  Polygon r = rectangle(2.0, 1.0);
  EXPECT_TRUE(Contains(defect(Polygon(r.rbegin(), r.rend())), "clockwise"));
}

TEST(PolygValidation, ZeroAreaAllCollinear) {
  const std::string m = defect({{0.0, 0.0}, {1.0, 1.0}, {2.0, 2.0}});
  EXPECT_TRUE(Contains(m, "POLYG of grain 7"));
  EXPECT_TRUE(Contains(m, "area is zero"));
  EXPECT_TRUE(Contains(defect({{0.0, 0.0}, {1.0, 0.0}, {3.0, 0.0}, {2.0, 0.0}}), "area is zero"));
}

TEST(PolygValidation, ThreeCollinearConsecutiveVertices) {
  // a 2×1 rectangle with an extra vertex in the middle of its bottom edge
  const std::string m = defect({{0.0, 0.0}, {1.0, 0.0}, {2.0, 0.0}, {2.0, 1.0}, {0.0, 1.0}});
  EXPECT_TRUE(Contains(m, "POLYG of grain 7"));
  EXPECT_TRUE(Contains(m, "collinear"));
  EXPECT_TRUE(Contains(m, "degenerate vertex 1"));
}

TEST(PolygValidation, ReflexAngleIsNonConvex) {
  // a dart: vertex 1 = (2, 1) is pushed inside; area = ½(−4 + 12) = 4 > 0, counter-clockwise,
  // and at vertex 1 cross((2,1), (2,−1)) = −4 < 0: a right turn.
  const std::string m = defect({{0.0, 0.0}, {2.0, 1.0}, {4.0, 0.0}, {2.0, 3.0}});
  EXPECT_TRUE(Contains(m, "POLYG of grain 7"));
  EXPECT_TRUE(Contains(m, "not convex"));
  EXPECT_TRUE(Contains(m, "reflex angle at vertex 1"));
}

TEST(PolygValidation, SelfIntersectingStar) {
  // A pentagram: the regular pentagon's vertices taken every second one (0, 2, 4, 1, 3). Every
  // turn is a left turn of 144°, the signed area is positive, but the boundary winds twice
  // (total turning 5 × 144° = 720° = 4π).
  const Polygon p = regular_polygon(5, 2.0);
  const std::string m = defect({p[0], p[2], p[4], p[1], p[3]});
  EXPECT_TRUE(Contains(m, "POLYG of grain 7"));
  EXPECT_TRUE(Contains(m, "self-intersecting"));
}

TEST(PolygValidation, ValidInputsAccepted) {
  EXPECT_NO_THROW(validate_polygon(Polygon{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}));
  for (int n = 3; n <= 12; ++n) {
    SCOPED_TRACE(n);
    EXPECT_NO_THROW(validate_polygon(regular_polygon(n, 1.0)));
    EXPECT_NO_THROW(validate_polygon(regular_polygon(n, 0.3, 0.7)));
    EXPECT_NO_THROW(validate_polygon(regular_polygon(n, 1e-4, 0.1)));   // fine gravel
    EXPECT_NO_THROW(validate_polygon(regular_polygon(n, 1e3, -0.2)));   // a huge block
    EXPECT_NO_THROW(validate_polygon(transformed(regular_polygon(n, 0.05), {2.5e3, -1.2e3}, 0.3)));
    // a 0.1 mm grain 10 km away from the origin
    EXPECT_NO_THROW(validate_polygon(transformed(regular_polygon(n, 1e-4), {1e4, 1e4}, 0.0)));
  }
  EXPECT_NO_THROW(validate_polygon(rectangle(1e-4, 2e-4)));
  EXPECT_NO_THROW(validate_polygon(rectangle(1e3, 10.0)));
  EXPECT_NO_THROW(validate_polygon(transformed(rectangle(30.0, 0.5), {-1e5, 3e4}, 1.0)));
}

// ---- builders -------------------------------------------------------------------------------

TEST(PolygBuilders, RegularPolygonVerticesOnTheCircle) {
  const double d = 0.6, theta = 0.4;
  for (int n = 3; n <= 12; ++n) {
    SCOPED_TRACE(n);
    const Polygon p = regular_polygon(n, d, theta);
    ASSERT_EQ(p.size(), static_cast<std::size_t>(n));
    expect_near(p[0], {0.3 * std::cos(theta), 0.3 * std::sin(theta)}, 1e-15);
    const double step = 2.0 * kPi / n;
    for (int k = 0; k < n; ++k) {
      const Vec2 v = p[static_cast<std::size_t>(k)], w = p[static_cast<std::size_t>((k + 1) % n)];
      EXPECT_NEAR(norm(v), 0.5 * d, 1e-15);
      // consecutive vertices are `step` apart, counter-clockwise
      EXPECT_NEAR(std::atan2(cross(v, w), dot(v, w)), step, 1e-12);
    }
  }
  EXPECT_THROW(regular_polygon(2, 1.0), Error);
  EXPECT_THROW(regular_polygon(5, 0.0), Error);
  EXPECT_THROW(regular_polygon(5, -1.0), Error);
  EXPECT_THROW(regular_polygon(5, std::numeric_limits<double>::quiet_NaN()), Error);
}

TEST(PolygBuilders, Rectangle) {
  const Polygon r = rectangle(3.0, 2.0);
  ASSERT_EQ(r.size(), 4u);
  EXPECT_EQ(r[0], (Vec2{-1.5, -1.0}));
  EXPECT_EQ(r[1], (Vec2{1.5, -1.0}));
  EXPECT_EQ(r[2], (Vec2{1.5, 1.0}));
  EXPECT_EQ(r[3], (Vec2{-1.5, 1.0}));
  EXPECT_THROW(rectangle(0.0, 1.0), Error);
  EXPECT_THROW(rectangle(1.0, -1.0), Error);
  EXPECT_THROW(rectangle(std::numeric_limits<double>::infinity(), 1.0), Error);
}

TEST(PolygBuilders, Transformed) {
  // p -> (10, 0) + R(90°) p, and R(90°)(x, y) = (−y, x)
  const Polygon t = transformed(rectangle(2.0, 1.0), {10.0, 0.0}, kPi / 2.0);
  ASSERT_EQ(t.size(), 4u);
  expect_near(t[0], {10.5, -1.0}, 1e-15);  // (−1, −0.5) -> (0.5, −1)
  expect_near(t[2], {9.5, 1.0}, 1e-15);    // (1, 0.5) -> (−0.5, 1)
  EXPECT_EQ(transformed(rectangle(2.0, 1.0), {1.0, 2.0})[1], (Vec2{2.0, 1.5}));
  EXPECT_NO_THROW(validate_polygon(t));    // a rotation keeps the order counter-clockwise
}

// ---- mass properties --------------------------------------------------------------------------

TEST(MassProperties, Rectangle) {
  // A = w h = 6, J = A (w² + h²) / 12 = 6 · 13 / 12 = 6.5
  const MassProperties m = mass_properties(rectangle(3.0, 2.0));
  EXPECT_DOUBLE_EQ(m.area, 6.0);
  expect_near(m.centroid, {0.0, 0.0}, 1e-15);
  EXPECT_DOUBLE_EQ(m.polar_moment, 6.5);
}

TEST(MassProperties, RegularPolygon) {
  // The n-gon is n triangles (centre, v_k, v_k+1) with two sides R and apex angle α = 2π/n.
  // A triangle (0, p, q) has ∫|x|² dA = (A_t / 6)(|p|² + p·q + |q|²) = A_t R² (2 + cos α) / 6,
  // so A = n R² sin α / 2 and J = A R² (2 + cos α) / 6 about the centre (= the centroid).
  // Check, square (n = 4): side s = R√2, A = 2R² = s², J = A R² (2 + 0)/6 = A R²/3, and the
  // rectangle formula gives A (s² + s²)/12 = A · 2 · 2R² / 12 = A R²/3. Same.
  // Check, equilateral triangle: s = R√3, J = A R² (2 − ½)/6 = A R²/4 = A s²/12. Right.
  for (int n = 3; n <= 12; ++n) {
    SCOPED_TRACE(n);
    const double R = 0.7, alpha = 2.0 * kPi / n;
    const MassProperties m = mass_properties(regular_polygon(n, 2.0 * R, 0.3));
    const double A = n * R * R * std::sin(alpha) / 2.0;
    EXPECT_NEAR(m.area, A, 1e-14);
    expect_near(m.centroid, {0.0, 0.0}, 1e-15);
    EXPECT_NEAR(m.polar_moment, A * R * R * (2.0 + std::cos(alpha)) / 6.0, 1e-14);
  }
}

TEST(MassProperties, RightTriangle) {
  // legs a = 3 (along x) and b = 4 (along y): A = ab/2 = 6, centroid = mean of the vertices
  // = (1, 4/3); about the centroid I_x = a b³/36 = 16/3, I_y = b a³/36 = 3, J = 25/3
  // (= A (a² + b²)/18 = 6 · 25 / 18, and = A (3² + 4² + 5²)/36 from the side lengths).
  const MassProperties m = mass_properties(Polygon{{0.0, 0.0}, {3.0, 0.0}, {0.0, 4.0}});
  EXPECT_DOUBLE_EQ(m.area, 6.0);
  expect_near(m.centroid, {1.0, 4.0 / 3.0}, 1e-15);
  EXPECT_NEAR(m.polar_moment, 25.0 / 3.0, 1e-14);
}

TEST(MassProperties, IndependentOfTranslationAndFirstVertex) {
  // an irregular convex quadrilateral; shoelace: A = ½ (0 + 12 + 7 + 0) = 9.5
  const Polygon q{{0.0, 0.0}, {4.0, 0.0}, {5.0, 3.0}, {1.0, 2.0}};
  const MassProperties ref = mass_properties(q);
  EXPECT_DOUBLE_EQ(ref.area, 9.5);
  for (std::size_t s = 1; s < q.size(); ++s) {
    Polygon shifted;
    for (std::size_t k = 0; k < q.size(); ++k) shifted.push_back(q[(k + s) % q.size()]);
    const MassProperties m = mass_properties(shifted);
    EXPECT_NEAR(m.area, ref.area, 1e-13);
    expect_near(m.centroid, ref.centroid, 1e-14);
    EXPECT_NEAR(m.polar_moment, ref.polar_moment, 1e-12);
  }
  for (Vec2 off : {Vec2{1e3, -2e3}, Vec2{-5e5, 7e5}}) {
    const MassProperties m = mass_properties(transformed(q, off));
    EXPECT_NEAR(m.area, ref.area, 1e-9);
    expect_near(m.centroid, ref.centroid + off, 1e-9);
    EXPECT_NEAR(m.polar_moment, ref.polar_moment, 1e-8 * ref.polar_moment);
  }
  // and of a rotation about the centroid (J is a polar moment)
  const MassProperties rot = mass_properties(transformed(transformed(q, -ref.centroid), {}, 1.1));
  EXPECT_NEAR(rot.polar_moment, ref.polar_moment, 1e-12);
  EXPECT_THROW(mass_properties(Polygon{}), Error);
}

// ---- bodies made of polygons -------------------------------------------------------------------

TEST(PolygBody, MassInertiaAndFrames) {
  Registry reg;
  const MaterialId rock = add_material(reg, "ROCK", 2500.0);
  // a 0.2 × 0.1 rectangle whose centroid is at (1, 0.5) in the shape frame; the shape frame is
  // placed at (10, 2) and turned by 90°: the centre of mass lands at (10, 2) + (−0.5, 1).
  const Polygon shape = transformed(rectangle(0.2, 0.1), {1.0, 0.5});
  const BodyId b = add_polygon_body(reg, shape, rock, {10.0, 2.0}, kPi / 2.0, "grain 7");
  const auto& t = reg.bodies;
  // (the shape is off-centre, so the shoelace sums round at ~1e-15 relative)
  EXPECT_NEAR(t.mass[b.index()], 50.0, 1e-12);               // 2500 × 0.02
  EXPECT_NEAR(t.inertia[b.index()], 5.0 / 24.0, 1e-14);      // 2500 × 0.02 × (0.04 + 0.01) / 12
  EXPECT_NEAR(t.x[b.index()], 9.5, 1e-14);
  EXPECT_NEAR(t.y[b.index()], 3.0, 1e-14);
  EXPECT_EQ(t.angle[b.index()], kPi / 2.0);
  EXPECT_EQ(t.material[b.index()], rock);
  EXPECT_EQ(t.name[b.index()], "grain 7");

  ASSERT_EQ(reg.polyg.size(), 1u);
  const PolygId p(0);
  EXPECT_EQ(reg.polyg.body[0], b);
  ASSERT_EQ(reg.polyg.vertex_count[0], 4u);
  // body-frame vertices: centred at the centre of mass, i.e. the plain rectangle
  const Polygon local = rectangle(0.2, 0.1);
  for (std::uint32_t k = 0; k < 4; ++k) expect_near(reg.polyg.vertex[reg.polyg.first_vertex[0] + k], local[k], 1e-14);
  expect_near(reg.polyg.centre[0], {0.0, 0.0}, 1e-14);
  EXPECT_NEAR(reg.polyg.area[0], 0.02, 1e-15);
  EXPECT_NEAR(reg.polyg.radius[0], std::sqrt(0.1 * 0.1 + 0.05 * 0.05), 1e-14);
  // outward unit normals of a counter-clockwise rectangle: bottom, right, top, left
  const Vec2 normals[] = {{0.0, -1.0}, {1.0, 0.0}, {0.0, 1.0}, {-1.0, 0.0}};
  for (std::uint32_t k = 0; k < 4; ++k) expect_near(reg.polyg.edge_normal[k], normals[k], 1e-14);

  // world vertices = position + R(angle) · shape vertex: (0.9, 0.45) -> (10, 2) + (−0.45, 0.9)
  const Polygon w = world_polygon(reg, p);
  ASSERT_EQ(w.size(), 4u);
  expect_near(w[0], {9.55, 2.9}, 1e-13);
  for (std::uint32_t k = 0; k < 4; ++k) {
    const Vec2 expected = Vec2{10.0, 2.0} + Rot2::of(kPi / 2.0).apply(shape[k]);
    expect_near(w[k], expected, 1e-13);
    expect_near(world_vertex(reg, p, k), expected, 1e-13);
  }
}

TEST(PolygBody, TwoRectanglesHaveTheMassOfTheirUnion) {
  // Two unit squares side by side, [0,1]×[0,1] and [1,2]×[0,1], density 3. Union: a 2×1
  // rectangle, A = 2, J = 2 (4 + 1)/12 = 5/6. Parallel axes: each square J = 1/6 about its own
  // centroid, offset 0.5 from the common centroid (1, 0.5): 2 (1/6 + 1 · 0.5²) = 5/6.
  Registry reg;
  const MaterialId m = add_material(reg, "M", 3.0);
  const std::vector<Polygon> halves{transformed(rectangle(1.0, 1.0), {0.5, 0.5}),
                                    transformed(rectangle(1.0, 1.0), {1.5, 0.5})};
  const BodyId b = add_polygon_body(reg, halves, m, {0.0, 0.0}, 0.0, "pair");
  EXPECT_DOUBLE_EQ(reg.bodies.mass[b.index()], 6.0);
  EXPECT_NEAR(reg.bodies.inertia[b.index()], 2.5, 1e-14);
  EXPECT_NEAR(reg.bodies.x[b.index()], 1.0, 1e-15);
  EXPECT_NEAR(reg.bodies.y[b.index()], 0.5, 1e-15);
  ASSERT_EQ(reg.polyg.size(), 2u);
  EXPECT_EQ(reg.polyg.body[0], b);
  EXPECT_EQ(reg.polyg.body[1], b);
  expect_near(reg.polyg.centre[0], {-0.5, 0.0}, 1e-15);
  expect_near(reg.polyg.centre[1], {0.5, 0.0}, 1e-15);

  // the same as one 2×1 rectangle
  const BodyId whole = add_polygon_body(reg, rectangle(2.0, 1.0), m, {1.0, 0.5});
  EXPECT_DOUBLE_EQ(reg.bodies.mass[whole.index()], reg.bodies.mass[b.index()]);
  EXPECT_NEAR(reg.bodies.inertia[whole.index()], reg.bodies.inertia[b.index()], 1e-14);
}

TEST(PolygBody, ErrorsNameTheBody) {
  Registry reg;
  const MaterialId rock = add_material(reg, "ROCK", 2500.0);
  add_polygon_body(reg, rectangle(1.0, 1.0), rock, {0.0, 0.0});  // body 0
  const std::string no_material =
      error_message([&] { add_polygon_body(reg, rectangle(1.0, 1.0), MaterialId(4), {}, 0.0, "grain 7"); });
  EXPECT_TRUE(Contains(no_material, "body 1 'grain 7'"));
  EXPECT_TRUE(Contains(no_material, "material"));
  EXPECT_THROW(add_polygon_body(reg, rectangle(1.0, 1.0), MaterialId{}, {}, 0.0, "grain 7"), Error);

  const Polygon clockwise{{0.0, 0.0}, {0.0, 1.0}, {1.0, 0.0}};
  const std::string bad = error_message([&] { add_polygon_body(reg, clockwise, rock, {}, 0.0, "grain 7"); });
  EXPECT_TRUE(Contains(bad, "POLYG of body 1 'grain 7'"));
  EXPECT_TRUE(Contains(bad, "clockwise"));
  // the second of two shapes is invalid
  const std::vector<Polygon> shapes{rectangle(1.0, 1.0), {{0.0, 0.0}, {1.0, 0.0}}};
  EXPECT_TRUE(Contains(error_message([&] { add_polygon_body(reg, shapes, rock, {}, 0.0, "grain 7"); }),
                       "POLYG of body 1 'grain 7': needs at least 3 vertices"));
  EXPECT_TRUE(Contains(error_message([&] { add_polygon_body(reg, std::vector<Polygon>{}, rock, {}); }), "body 1"));
  // too many vertices for a POLYG: rejected before the body is created
  EXPECT_TRUE(Contains(error_message([&] { add_polygon_body(reg, regular_polygon(4097, 1.0), rock, {}); }),
                       "at most 4096 vertices"));
  // nothing was added by the failed calls
  EXPECT_EQ(reg.bodies.size(), 1u);
  EXPECT_EQ(reg.polyg.size(), 1u);
}

TEST(PolygBody, AttachPolygChecksItsInput) {
  Registry reg;
  const MaterialId rock = add_material(reg, "ROCK", 1.0);
  const BodyId b = add_polygon_body(reg, rectangle(1.0, 1.0), rock, {}, 0.0, "grain 7");
  // an extra contactor does not change the body's mass
  const PolygId extra = attach_polyg(reg, b, transformed(rectangle(0.2, 0.2), {0.6, 0.0}));
  EXPECT_EQ(extra.index(), 1u);
  EXPECT_EQ(reg.bodies.mass[b.index()], 1.0);
  EXPECT_EQ(reg.polyg.first_vertex[1], 4u);
  expect_near(reg.polyg.centre[1], {0.6, 0.0}, 1e-15);
  EXPECT_NEAR(reg.polyg.radius[1], std::hypot(0.7, 0.1), 1e-15);

  EXPECT_THROW(attach_polyg(reg, BodyId(3), rectangle(1.0, 1.0)), Error);
  EXPECT_THROW(attach_polyg(reg, BodyId{}, rectangle(1.0, 1.0)), Error);
  EXPECT_TRUE(Contains(error_message([&] { attach_polyg(reg, b, Polygon{{0.0, 0.0}, {0.0, 1.0}, {1.0, 0.0}}); }),
                       "POLYG of body 0 'grain 7': vertices are clockwise"));
  // kMaxPolygVertices: 4096 is accepted, 4097 rejected
  EXPECT_NO_THROW(attach_polyg(reg, b, regular_polygon(static_cast<int>(kMaxPolygVertices), 1.0)));
  const std::string many =
      error_message([&] { attach_polyg(reg, b, regular_polygon(static_cast<int>(kMaxPolygVertices) + 1, 1.0)); });
  EXPECT_TRUE(Contains(many, "'grain 7'"));
  EXPECT_TRUE(Contains(many, "at most 4096 vertices, got 4097"));
  EXPECT_EQ(reg.polyg.size(), 3u);
}

}  // namespace
