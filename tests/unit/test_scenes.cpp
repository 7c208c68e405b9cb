// Tests of the scene builders (shared/grading.hpp, shared/samples.hpp): the paper's grading,
// seeded determinism, the box and lattice geometry, and what detection finds on the loose and
// packed samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "nscd/interactions/plplx.hpp"
#include "nscd/shared/grading.hpp"
#include "nscd/shared/samples.hpp"

using namespace nscd;
using namespace nscd::scenes;

namespace {

// Number of grains of a scene whose pentagon has circumradius r (the POLYG radius).
std::size_t grains_with_radius(const Scene& s, double r) {
  std::size_t n = 0;
  for (BodyId b : s.grains)
    for (std::size_t p = 0; p < s.reg.polyg.size(); ++p)
      if (s.reg.polyg.body[p] == b && std::abs(s.reg.polyg.radius[p] - r) < 1e-12) ++n;
  return n;
}

// Every vertex of every grain inside [0, W] × [0, H].
void expect_grains_inside_box(const Scene& s) {
  for (std::size_t p = 0; p < s.reg.polyg.size(); ++p) {
    const BodyId b = s.reg.polyg.body[p];
    if (std::find(s.grains.begin(), s.grains.end(), b) == s.grains.end()) continue;
    for (Vec2 v : world_polygon(s.reg, PolygId(static_cast<std::uint32_t>(p)))) {
      ASSERT_GE(v.x, 0.0) << s.reg.bodies.name[b.index()];
      ASSERT_LE(v.x, s.box_width) << s.reg.bodies.name[b.index()];
      ASSERT_GE(v.y, 0.0) << s.reg.bodies.name[b.index()];
      ASSERT_LE(v.y, s.box_height) << s.reg.bodies.name[b.index()];
    }
  }
}

}  // namespace

TEST(Grading, PaperGradingClasses) {
  const Grading g = paper_grading();
  ASSERT_EQ(g.size(), 3u);
  EXPECT_EQ(g[0].count, 361u);
  EXPECT_DOUBLE_EQ(g[0].diameter, 0.010);
  EXPECT_EQ(g[1].count, 242u);
  EXPECT_DOUBLE_EQ(g[1].diameter, 0.015);
  EXPECT_EQ(g[2].count, 121u);
  EXPECT_DOUBLE_EQ(g[2].diameter, 0.020);
  EXPECT_EQ(grain_count(g), 724u);  // 361 + 242 + 121
  EXPECT_DOUBLE_EQ(largest_diameter(g), 0.020);
}

TEST(Grading, ExpandKeepsCountsAndIsDeterministic) {
  const std::vector<double> a = expand_grading(paper_grading(), 42), b = expand_grading(paper_grading(), 42);
  const std::vector<double> c = expand_grading(paper_grading(), 43);
  ASSERT_EQ(a.size(), 724u);
  EXPECT_EQ(std::count(a.begin(), a.end(), 0.010), 361);
  EXPECT_EQ(std::count(a.begin(), a.end(), 0.015), 242);
  EXPECT_EQ(std::count(a.begin(), a.end(), 0.020), 121);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  // Shuffled: the unshuffled list starts with 361 small grains; a shuffle leaves the first 20
  // all small with probability (361/724)^20 ≈ 1e-6.
  EXPECT_TRUE(std::any_of(a.begin(), a.begin() + 20, [](double d) { return d != 0.010; }));
  EXPECT_THROW(expand_grading({{3, -0.01}}, 1), Error);
}

TEST(Grading, UniformRadius) {
  const Grading g = uniform_radius_grading(700, 0.0125, 0.025, 5);
  ASSERT_EQ(g.size(), 700u);
  double sum = 0.0;
  for (const auto& c : g) {
    EXPECT_EQ(c.count, 1u);
    EXPECT_GE(c.diameter, 0.025);
    EXPECT_LE(c.diameter, 0.050);
    sum += c.diameter;
  }
  // Mean diameter 2·(12.5 + 25)/2 mm = 37.5 mm; standard error of the mean of 700 draws
  // = 25 mm / √12 / √700 ≈ 0.27 mm, so 1.5 mm is more than 5 standard errors.
  EXPECT_NEAR(sum / 700.0, 0.0375, 0.0015);
  EXPECT_EQ(uniform_radius_grading(700, 0.0125, 0.025, 5)[17].diameter, g[17].diameter);
  EXPECT_THROW(uniform_radius_grading(10, 0.02, 0.01, 1), Error);
  EXPECT_THROW(uniform_radius_grading(0, 0.01, 0.02, 1), Error);
}

TEST(Grading, RandomHelpersAreStandardIndependent) {
  // The C++ standard fixes the 10000th output of a default-seeded mt19937_64:
  // 9981545732273789042. Its top 53 bits over 2^53 = 9981545732273789042 / 2^64 (to double
  // precision) = 0.5411006783847329.
  std::mt19937_64 rng;
  rng.discard(9999);
  EXPECT_NEAR(uniform01(rng), 0.5411006783847329, 1e-15);
  std::mt19937_64 r2(3);
  for (int k = 0; k < 1000; ++k) {
    const double u = uniform01(r2);
    EXPECT_GE(u, 0.0);
    EXPECT_LT(u, 1.0);
    EXPECT_LT(uniform_below(r2, 7), 7u);
  }
  EXPECT_THROW(uniform_below(r2, 0), Error);
}

TEST(Samples, BoxGeometry) {
  Registry reg;
  const MaterialId m = add_material(reg, "steel", 7800.0);
  const BoxWalls w = add_box(reg, m, 1.0, 0.5, 0.1);
  // Floor: 1.2 × 0.1 centred at (0.5, −0.05): x in [−0.1, 1.1], y in [−0.1, 0].
  // Left wall: 0.1 × 0.6 centred at (−0.05, 0.2): x in [−0.1, 0], y in [−0.1, 0.5].
  // Right wall: x in [1, 1.1].
  auto bounds = [&](BodyId b) {
    double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
    for (Vec2 v : world_polygon(reg, PolygId(b.value))) {  // one POLYG per wall, in body order
      x0 = std::min(x0, v.x); x1 = std::max(x1, v.x); y0 = std::min(y0, v.y); y1 = std::max(y1, v.y);
    }
    return std::array<double, 4>{x0, x1, y0, y1};
  };
  const auto f = bounds(w.floor), l = bounds(w.left), r = bounds(w.right);
  EXPECT_NEAR(f[0], -0.1, 1e-12); EXPECT_NEAR(f[1], 1.1, 1e-12); EXPECT_NEAR(f[3], 0.0, 1e-12);
  EXPECT_NEAR(l[1], 0.0, 1e-12); EXPECT_NEAR(l[2], -0.1, 1e-12); EXPECT_NEAR(l[3], 0.5, 1e-12);
  EXPECT_NEAR(r[0], 1.0, 1e-12); EXPECT_NEAR(r[3], 0.5, 1e-12);
  for (BodyId b : {w.floor, w.left, w.right}) {
    EXPECT_EQ(drive_of(reg, b, Dof::X), Drive::Fixed);
    EXPECT_EQ(reg.bodies.inv_mass_y[b.index()], 0.0);
    EXPECT_EQ(reg.polyg.is_big[b.index()], 1);  // POLYG k belongs to body k here
  }
  EXPECT_EQ(reg.bodies.name[w.left.index()], "left wall");
  EXPECT_THROW(add_box(reg, m, -1.0, 0.5, 0.1), Error);
  EXPECT_THROW(add_box(reg, m, 1.0, 0.5, 0.0), Error);
}

TEST(Samples, LatticeSitesNamesAndOrientations) {
  Registry reg;
  const MaterialId m = add_material(reg, "stone", 2000.0);
  const std::vector<double> d(7, 0.02);
  const LatticeSpec L{1.0, 2.0, 3, 0.5, 0.25, 11};
  const std::vector<BodyId> g = add_pentagons_on_lattice(reg, m, d, L);
  ASSERT_EQ(g.size(), 7u);
  // grain 4: column 4 mod 3 = 1, row 4 div 3 = 1 → (1 + 0.5, 2 + 0.25).
  EXPECT_NEAR(reg.bodies.x[g[4].index()], 1.5, 1e-12);
  EXPECT_NEAR(reg.bodies.y[g[4].index()], 2.25, 1e-12);
  // grain 6: column 0, row 2 → (1, 2.5).
  EXPECT_NEAR(reg.bodies.x[g[6].index()], 1.0, 1e-12);
  EXPECT_NEAR(reg.bodies.y[g[6].index()], 2.5, 1e-12);
  EXPECT_EQ(reg.bodies.name[g[4].index()], "grain 4");
  for (BodyId b : g) {
    EXPECT_GE(reg.bodies.angle[b.index()], 0.0);
    EXPECT_LT(reg.bodies.angle[b.index()], 2.0 * kPi / 5.0);
  }
  EXPECT_NEAR(reg.polyg.radius[0], 0.01, 1e-12);  // circumradius = d/2
  EXPECT_NE(reg.bodies.angle[g[0].index()], reg.bodies.angle[g[1].index()]);
  EXPECT_THROW(add_pentagons_on_lattice(reg, m, d, LatticeSpec{0, 0, 0, 0.1, 0.1, 1}), Error);
}

TEST(Samples, PaperLooseLayoutCountsAndNoContact) {
  Scene s = paper_sample_loose();
  // Hand computation (d_max = 0.02, pitch = 0.022, clearance c = 0.002, width 1):
  //   columns = floor((1 − 0.02 − 0.004) / 0.022) + 1 = floor(44.36) + 1 = 45,
  //   rows = ceil(724 / 45) = 17,
  //   height = (c + d_max/2) + 16 · 0.022 + d_max/2 + c = 0.012 + 0.352 + 0.012 = 0.376.
  EXPECT_EQ(s.lattice.columns, 45);
  EXPECT_NEAR(s.box_height, 0.376, 1e-12);
  EXPECT_EQ(s.grains.size(), 724u);
  EXPECT_EQ(s.reg.bodies.size(), 727u);  // + floor and two walls
  EXPECT_EQ(grains_with_radius(s, 0.005), 361u);
  EXPECT_EQ(grains_with_radius(s, 0.0075), 242u);
  EXPECT_EQ(grains_with_radius(s, 0.010), 121u);
  expect_grains_inside_box(s);
  PlplxDetector det;
  const DetectionStats st = detect_plplx(s.reg, det);
  EXPECT_EQ(st.contact_points, 0u);
  EXPECT_EQ(s.reg.contacts.size(), 0u);
}

TEST(Samples, PaperPackedHasManyContactsInsideTheBox) {
  Scene s = paper_sample_packed();
  EXPECT_EQ(s.grains.size(), 724u);
  expect_grains_inside_box(s);
  PlplxDetector det;
  const DetectionStats st = detect_plplx(s.reg, det);
  // Pitch 1.6 cm: two 2 cm pentagons (inradius sum 2·0.809 cm = 1.62 cm) always overlap, and
  // 1.5–2 cm pairs often do. Seed 2006 gives 241 points; require at least 100 and some
  // edge–edge (double) contacts.
  EXPECT_GT(st.contact_points, 100u);
  EXPECT_GT(st.contact_pairs, 100u);
  EXPECT_GT(st.double_contacts, 0u);
  // No grain touches the box (clearance 2 mm > alert 1.25 mm): every contact is grain–grain.
  for (std::size_t k = 0; k < s.reg.contacts.size(); ++k) {
    EXPECT_GE(s.reg.contacts.an_body[k].index(), 3u);
    EXPECT_GE(s.reg.contacts.cd_body[k].index(), 3u);
  }
}

TEST(Samples, SeededDeterminism) {
  const Scene a = paper_sample_packed(7), b = paper_sample_packed(7), c = paper_sample_packed(8);
  EXPECT_EQ(a.reg.bodies.angle, b.reg.bodies.angle);
  EXPECT_EQ(a.reg.polyg.radius, b.reg.polyg.radius);
  EXPECT_EQ(a.reg.bodies.x, b.reg.bodies.x);
  EXPECT_NE(a.reg.bodies.angle, c.reg.bodies.angle);
  EXPECT_NE(a.reg.polyg.radius, c.reg.polyg.radius);
}

TEST(Samples, PaperSampleRejectsBadSizes) {
  SampleOptions o;
  o.box_width = 0.02;  // narrower than d_max + 2c = 0.024
  EXPECT_THROW(paper_sample(o), Error);
  o.box_width = 1.0;
  o.pitch_factor = -1.0;
  EXPECT_THROW(paper_sample(o), Error);
}

TEST(Samples, PentagonField) {
  const Scene s = pentagon_field(10, 0.01, 0.009, 3);
  ASSERT_EQ(s.grains.size(), 10u);
  // columns = ceil(√10) = 4; grain 5 at column 1, row 1: (0.0045 + 0.009, 0.0045 + 0.009).
  EXPECT_EQ(s.lattice.columns, 4);
  EXPECT_NEAR(s.reg.bodies.x[s.grains[5].index()], 0.0135, 1e-12);
  EXPECT_NEAR(s.reg.bodies.y[s.grains[5].index()], 0.0135, 1e-12);
  EXPECT_FALSE(s.walls.floor.valid());
  EXPECT_THROW(pentagon_field(0, 0.01, 0.009), Error);
}
