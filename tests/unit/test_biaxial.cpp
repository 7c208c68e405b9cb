// tests/unit/test_biaxial.cpp — the biaxial test's stress measures (shared/biaxial.hpp): the
// time average of the wall stresses over a row, the internal (Love–Weber) stress of the grains,
// and the peak and residual friction angles of a curve.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "nscd/core/error.hpp"
#include "nscd/shared/biaxial.hpp"

namespace nscd {
namespace {

double deg(double rad) { return rad * 180.0 / kPi; }

TEST(BiaxialStressAverage, WeightsEachStepByItsDuration) {
  scenes::StressAverage a;
  a.add(1e-4, 3.0, 1.0, {2.0, 4.0, 0.5});
  a.add(3e-4, 1.0, 2.0, {6.0, 8.0, -0.5});
  EXPECT_EQ(a.steps(), 2u);
  EXPECT_NEAR(a.duration(), 4e-4, 1e-18);
  // Σ dt σ / Σ dt, not the plain mean of the two steps (2.0 and 1.5) nor the last step's value
  EXPECT_NEAR(a.sigma1(), (1e-4 * 3.0 + 3e-4 * 1.0) / 4e-4, 1e-12);
  EXPECT_NEAR(a.sigma3(), (1e-4 * 1.0 + 3e-4 * 2.0) / 4e-4, 1e-12);
  const scenes::Stress2 s = a.internal();
  EXPECT_NEAR(s.xx, 5.0, 1e-12);
  EXPECT_NEAR(s.yy, 7.0, 1e-12);
  EXPECT_NEAR(s.xy, -0.25, 1e-12);
}

TEST(BiaxialStressAverage, TheRowAngleIsThatOfTheMeanStressesNotTheMeanAngle) {
  // two equal steps: (σ₁, σ₃) = (3, 1) then (1, 1). Mean stresses (2, 1): sin φ = 1/3, 19.47°;
  // the mean of the two steps' angles would be (30° + 0°) / 2 = 15°.
  scenes::StressAverage a;
  a.add(2e-4, 3.0, 1.0);
  a.add(2e-4, 1.0, 1.0);
  const double phi = scenes::mobilized_friction_deg(a.sigma1(), a.sigma3());
  EXPECT_NEAR(phi, deg(std::asin(1.0 / 3.0)), 1e-9);
  EXPECT_GT(std::abs(phi - 15.0), 4.0);
}

TEST(BiaxialStressAverage, ClearStartsANewRowAndBadInputIsRefused) {
  scenes::StressAverage a;
  EXPECT_THROW(a.sigma1(), Error);  // no step yet
  a.add(1e-4, 5.0, 5.0);
  a.clear();
  a.add(1e-4, 2.0, 1.0);
  EXPECT_EQ(a.steps(), 1u);
  EXPECT_DOUBLE_EQ(a.sigma1(), 2.0);
  EXPECT_THROW(a.add(0.0, 1.0, 1.0), Error);
  EXPECT_THROW(a.add(-1e-4, 1.0, 1.0), Error);
  EXPECT_THROW(a.add(1e-4, std::nan(""), 1.0), Error);
}

TEST(BiaxialStress, PrincipalValuesOfARotatedStress) {
  // diag(3, 1) rotated by 30°: xx = 2 + cos 60°, yy = 2 − cos 60°, xy = sin 60°
  const scenes::Stress2 s{2.0 + 0.5, 2.0 - 0.5, std::sqrt(3.0) / 2.0};
  EXPECT_NEAR(s.major(), 3.0, 1e-12);
  EXPECT_NEAR(s.minor(), 1.0, 1e-12);
}

TEST(BiaxialStress, InternalStressOfOneDiskSqueezedBetweenTheWalls) {
  scenes::BiaxialOptions o;
  o.grains = 1;
  scenes::BiaxialBox b = scenes::biaxial_box(o);
  const BodyId g = b.grains.front();
  const Vec2 c{b.reg.bodies.x[g.index()], b.reg.bodies.y[g.index()]};
  const double r = b.reg.diskx.radius.front(), F = 50.0, T = 10.0;
  // the disk (candidate) on the bottom wall and under the top wall, the normal from the wall to
  // the disk; a tangential force T at the bottom, −T at the top (a couple the walls balance)
  ContactTable& t = b.reg.contacts;
  t.resize(2);
  t.cd_body[0] = g, t.an_body[0] = b.bottom, t.normal[0] = {0.0, 1.0}, t.point[0] = {c.x, c.y - r};
  t.cd_body[1] = g, t.an_body[1] = b.top, t.normal[1] = {0.0, -1.0}, t.point[1] = {c.x, c.y + r};
  t.rn[0] = F, t.rt[0] = T, t.rn[1] = F, t.rt[1] = T;
  const scenes::WallState w = scenes::wall_state(b);
  EXPECT_NEAR(w.sigma1, F / w.width, 1e-9);  // the top wall carries F
  EXPECT_NEAR(w.sigma3, 0.0, 1e-12);
  const scenes::Stress2 s = scenes::internal_stress(b, w);
  const double area = w.width * w.height;
  EXPECT_NEAR(s.yy, 2.0 * F * r / area, 1e-9);  // compression positive
  EXPECT_NEAR(s.xx, 0.0, 1e-12);
  // perp((0, 1)) = (−1, 0): the tangential forces on the disk are ∓T along x at y ∓ r
  const Vec2 t0 = perp(t.normal[0]), t1 = perp(t.normal[1]);
  const double fxy = T * t0.x * (-r) + T * t1.x * r;  // Σ f_x ℓ_y
  EXPECT_NEAR(s.xy, -0.5 * fxy / area, 1e-9);
  EXPECT_GT(std::abs(s.xy), 0.0);
}

TEST(BiaxialHexagonal, LatticeTouchesItsNeighboursAndTheWalls) {
  scenes::HexagonalOptions o;
  o.columns = 4, o.rows = 3, o.radius = 0.01;
  const scenes::BiaxialBox b = scenes::hexagonal_biaxial_box(o);
  ASSERT_EQ(b.grains.size(), 4u + 3u + 4u);  // long, short, long rows
  const scenes::WallState w = scenes::wall_state(b);
  EXPECT_NEAR(w.width, 8.0 * o.radius, 1e-12);
  EXPECT_NEAR(w.height, 2.0 * o.radius + 2.0 * std::sqrt(3.0) * o.radius, 1e-12);
  // every disk of the short row touches its four neighbours below and above (distance 2r)
  const BodyTable& bt = b.reg.bodies;
  auto dist = [&](std::size_t i, std::size_t j) {
    return std::hypot(bt.x[b.grains[i].index()] - bt.x[b.grains[j].index()], bt.y[b.grains[i].index()] - bt.y[b.grains[j].index()]);
  };
  for (std::size_t j = 0; j < 3; ++j) {
    const std::size_t mid = 4 + j;
    for (std::size_t k : {j, j + 1, 7 + j, 8 + j}) EXPECT_NEAR(dist(mid, k), 2.0 * o.radius, 1e-12) << mid << " " << k;
  }
  // the long rows' end disks touch the side walls; the first and last rows the bottom and top
  EXPECT_NEAR(bt.x[b.grains[0].index()] - o.radius, 0.0, 1e-12);
  EXPECT_NEAR(bt.x[b.grains[3].index()] + o.radius, w.width, 1e-12);
  EXPECT_NEAR(bt.y[b.grains[10].index()] + o.radius, w.height, 1e-12);
}

TEST(BiaxialHexagonal, BadSizesAreRefused) {
  scenes::HexagonalOptions o;
  o.columns = 1;
  EXPECT_THROW(scenes::hexagonal_biaxial_box(o), Error);
  o.columns = 4, o.rows = 1;
  EXPECT_THROW(scenes::hexagonal_biaxial_box(o), Error);
  o.rows = 3, o.radius = 0.0;
  EXPECT_THROW(scenes::hexagonal_biaxial_box(o), Error);
  o.radius = 0.01, o.density = std::nan("");
  EXPECT_THROW(scenes::hexagonal_biaxial_box(o), Error);
}

TEST(BiaxialFrictionAngles, PeakIsTheLargestRunningMeanAndResidualTheTail) {
  const std::vector<double> strain{0.0, 0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.09};
  const std::vector<double> phi{10.0, 20.0, 26.0, 30.0, 24.0, 20.0, 18.0, 16.0, 18.0, 16.0};
  const scenes::FrictionAngles a = scenes::friction_angles(strain, phi, 0.06);
  // running means over 5 rows: at row 2 (10+20+26+30+24)/5 = 22, row 3 (20+26+30+24+20)/5 = 24
  EXPECT_NEAR(a.peak, 24.0, 1e-12);
  EXPECT_NEAR(a.peak_strain, 0.03, 1e-12);
  EXPECT_EQ(a.residual_rows, 4u);
  EXPECT_NEAR(a.residual, 17.0, 1e-12);
  EXPECT_NEAR(a.spread, 1.0, 1e-12);
  // a start-up spike in the first rows is not the peak once peak_from passes it
  std::vector<double> spiked = phi;
  spiked[0] = 80.0;
  EXPECT_NEAR(scenes::friction_angles(strain, spiked, 0.06).peak, (80.0 + 20.0 + 26.0) / 3.0, 1e-12);
  // from 0.015 on the rows are 26, 30, 24, 20, ...: the largest mean (26+30+24)/3 at 0.02
  const scenes::FrictionAngles b = scenes::friction_angles(strain, spiked, 0.06, 0.015);
  EXPECT_NEAR(b.peak, 80.0 / 3.0, 1e-12);
  EXPECT_NEAR(b.peak_strain, 0.02, 1e-12);
  EXPECT_THROW(scenes::friction_angles(strain, phi, 0.06, 0.5), Error);  // no row past peak_from
  EXPECT_THROW(scenes::friction_angles({0.0}, {1.0, 2.0}, 0.0), Error);
  EXPECT_THROW(scenes::friction_angles({}, {}, 0.0), Error);
}

}  // namespace
}  // namespace nscd
