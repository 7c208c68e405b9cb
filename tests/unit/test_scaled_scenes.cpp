// Tests of the scaled scenes of issue #8: the paper's grading scaled to n grains
// (paper_grading(n), scaled_box_width, SampleOptions::grains) and settled samples copied side
// by side (tiling.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "nscd/shared/grading.hpp"
#include "nscd/shared/samples.hpp"
#include "nscd/shared/tiling.hpp"
#include "nscd/solvers/moreau_jean.hpp"

using namespace nscd;
using namespace nscd::scenes;

TEST(ScaledGrading, PaperSizeGivesThePaperGrading) {
  const Grading g = paper_grading(724), p = paper_grading();
  ASSERT_EQ(g.size(), p.size());
  for (std::size_t k = 0; k < g.size(); ++k) {
    EXPECT_EQ(g[k].count, p[k].count);
    EXPECT_EQ(g[k].diameter, p[k].diameter);
  }
}

TEST(ScaledGrading, LargestRemaindersSumToN) {
  // 7000 × (361, 242, 121) / 724 = 3490.33, 2339.78, 1169.89: the two largest remainders get one more
  const Grading g = paper_grading(7000);
  EXPECT_EQ(g[0].count, 3490u);
  EXPECT_EQ(g[1].count, 2340u);
  EXPECT_EQ(g[2].count, 1170u);
  for (std::size_t n : {1u, 2u, 3u, 7u, 700u, 70000u, 123457u}) EXPECT_EQ(grain_count(paper_grading(n)), n) << n;
  // one grain: the class with the largest share (1 cm, 361/724)
  EXPECT_EQ(paper_grading(1)[0].count, 1u);
  EXPECT_THROW(paper_grading(0), Error);
  EXPECT_THROW(paper_grading(kMaxScaledGrains + 1), Error);
}

TEST(ScaledSample, BoxWidthKeepsTheLayerDepth) {
  EXPECT_DOUBLE_EQ(scaled_box_width(7240), 10.0);
  EXPECT_DOUBLE_EQ(scaled_box_width(724), kPaperBoxWidth);
  EXPECT_GT(scaled_box_width(1), 0.024);  // one lattice column at least
  EXPECT_THROW(scaled_box_width(0), Error);
  SampleOptions o;
  o.grains = 7000;
  o.box_width = scaled_box_width(o.grains);
  const Scene big = paper_sample(o), paper = paper_sample_loose();
  EXPECT_EQ(big.grains.size(), 7000u);
  // the same number of lattice rows (± 1) as the paper's sample: the same fall, the same depth
  EXPECT_NEAR(big.box_height, paper.box_height, 0.022 * 1.01);
  for (std::size_t n : {1u, 5u}) {
    SampleOptions s;
    s.grains = n;
    s.box_width = scaled_box_width(n);
    EXPECT_EQ(paper_sample(s).grains.size(), n);
  }
}

TEST(Tiling, CopiesSideBySide) {
  SampleOptions o;
  o.grains = 40;
  o.box_width = scaled_box_width(o.grains);
  Scene s = paper_sample(o);
  s.reg.bodies.vx[s.grains[3].index()] = 0.25;
  Scene t = tile_scene(s.reg, 3, Seams::Mirrored);
  ASSERT_EQ(t.grains.size(), 120u);
  EXPECT_NEAR(sample_box_width(s.reg), o.box_width, 1e-12);
  EXPECT_NEAR(t.box_width, 3.0 * o.box_width, 1e-12);
  EXPECT_NEAR(sample_box_width(t.reg), t.box_width, 1e-12);
  const double w = o.box_width;
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t i = 0; i < 40; ++i) {
      const std::size_t a = s.grains[i].index(), b = t.grains[40 * k + i].index();
      const double sign = k == 1 ? -1.0 : 1.0;  // copy 1 is mirrored about its middle
      const double x = k == 1 ? 2.0 * w - s.reg.bodies.x[a] : s.reg.bodies.x[a] + static_cast<double>(k) * w;
      EXPECT_NEAR(t.reg.bodies.x[b], x, 1e-12);
      EXPECT_NEAR(t.reg.bodies.y[b], s.reg.bodies.y[a], 1e-12);
      EXPECT_NEAR(t.reg.bodies.angle[b], sign * s.reg.bodies.angle[a], 1e-12);
      EXPECT_NEAR(t.reg.bodies.mass[b], s.reg.bodies.mass[a], 1e-12 * s.reg.bodies.mass[a]);
      EXPECT_NEAR(t.reg.bodies.inertia[b], s.reg.bodies.inertia[a], 1e-9 * s.reg.bodies.inertia[a]);
      EXPECT_EQ(t.reg.bodies.vx[b], sign * s.reg.bodies.vx[a]);
    }
  // the mirrored copy's world polygons are the sample's reflected: compare the lowest vertex
  for (std::size_t i = 0; i < 40; ++i) {
    auto lowest = [](const std::vector<Vec2>& p) {
      return *std::min_element(p.begin(), p.end(), [](Vec2 u, Vec2 v) { return u.y < v.y; });
    };
    const Vec2 a = lowest(world_polygon(s.reg, PolygId(static_cast<std::uint32_t>(3 + i))));
    const Vec2 b = lowest(world_polygon(t.reg, PolygId(static_cast<std::uint32_t>(3 + 40 + i))));
    EXPECT_NEAR(b.x, 2.0 * w - a.x, 1e-12);
    EXPECT_NEAR(b.y, a.y, 1e-12);
  }
  // without mirroring every copy is a plain shift
  const Scene plain = tile_scene(s.reg, 2, Seams::Plain);
  EXPECT_NEAR(plain.reg.bodies.x[plain.grains[45].index()], s.reg.bodies.x[s.grains[5].index()] + w, 1e-12);
  // a step runs on the tiled scene
  MoreauJean mj(t.reg);
  const StepReport r = mj.step();
  EXPECT_TRUE(r.converged);
}

TEST(Tiling, SeamWallsKeepEachCopyInItsCompartment) {
  SampleOptions o;
  o.grains = 30;
  o.box_width = scaled_box_width(o.grains);
  const Scene s = paper_sample(o);
  Scene t = tile_scene(s.reg, 4);  // Seams::Walls
  const double pitch = o.box_width + kSeamWallThickness;
  EXPECT_EQ(t.grains.size(), 120u);
  EXPECT_NEAR(t.box_width, 3.0 * pitch + o.box_width, 1e-12);
  EXPECT_NEAR(t.reg.bodies.x[t.grains[3 * 30 + 7].index()], s.reg.bodies.x[s.grains[7].index()] + 3.0 * pitch, 1e-12);
  // 3 seam walls after the grains, fixed, as tall as the box, their faces where the sample's walls were
  ASSERT_EQ(t.reg.bodies.size(), 3u + 120u + 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t b = 123 + k;
    EXPECT_EQ(t.reg.bodies.name[b], "seam wall " + std::to_string(k));
    EXPECT_EQ(t.reg.bodies.inv_mass_x[b], 0.0);
    double xmin = 1e9, xmax = -1e9, ymax = -1e9;
    for (std::size_t p = 0; p < t.reg.polyg.size(); ++p)
      if (t.reg.polyg.body[p].index() == b)
        for (Vec2 v : world_polygon(t.reg, PolygId(static_cast<std::uint32_t>(p)))) {
          xmin = std::min(xmin, v.x);
          xmax = std::max(xmax, v.x);
          ymax = std::max(ymax, v.y);
        }
    EXPECT_NEAR(xmin, static_cast<double>(k) * pitch + o.box_width, 1e-12);
    EXPECT_NEAR(xmax, static_cast<double>(k + 1) * pitch, 1e-12);
    EXPECT_GE(ymax, t.box_height);
  }
}

TEST(Tiling, RowOrderNumbersBandsAcrossTheWholeWidth) {
  SampleOptions o;
  o.grains = 60;
  o.box_width = scaled_box_width(o.grains);
  const Scene s = paper_sample(o);
  const Scene copies = tile_scene(s.reg, 3), rows = tile_scene(s.reg, 3, Seams::Walls, TileOrder::Rows);
  ASSERT_EQ(rows.grains.size(), 180u);
  const double band = 0.02;  // the largest diameter
  for (std::size_t i = 1; i < rows.grains.size(); ++i) {
    const std::size_t a = rows.grains[i - 1].index(), b = rows.grains[i].index();
    const double ra = std::floor(rows.reg.bodies.y[a] / band), rb = std::floor(rows.reg.bodies.y[b] / band);
    ASSERT_LE(ra, rb) << i;
    if (ra == rb) {
      EXPECT_LT(rows.reg.bodies.x[a], rows.reg.bodies.x[b]) << i;
    }
  }
  // the same grains, only numbered differently: the same sum of x and of y
  double sx = 0, sy = 0, tx = 0, ty = 0;
  for (BodyId g : copies.grains) sx += copies.reg.bodies.x[g.index()], sy += copies.reg.bodies.y[g.index()];
  for (BodyId g : rows.grains) tx += rows.reg.bodies.x[g.index()], ty += rows.reg.bodies.y[g.index()];
  EXPECT_NEAR(sx, tx, 1e-9);
  EXPECT_NEAR(sy, ty, 1e-9);
  // the first grain numbered is in copy 0 (the lowest band starts at the left wall)
  EXPECT_LT(rows.reg.bodies.x[rows.grains.front().index()], o.box_width);
}

TEST(Tiling, RefusesWhatItCannotCopy) {
  const Scene s = paper_sample_loose();
  EXPECT_THROW(tile_scene(s.reg, 0), Error);
  const Scene field = pentagon_field(10, 0.01, 0.009);  // no walls
  EXPECT_THROW(tile_scene(field.reg, 2), Error);
}
