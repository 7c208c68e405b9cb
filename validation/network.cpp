// validation/network.cpp — the contact-network series (shared/postpro.hpp: coordination
// number, strong / weak split, statuses) on a scene whose forces statics gives.
//
// Four boxes 0.2 m × 0.1 m (m = 2000 × 0.02 = 40 kg/m each) stacked exactly on a fixed floor,
// IQS_CLB μ = 0.5. Each interface is an edge–edge contact of two points; by the symmetry of each
// box (its moment balance) the two points share the interface's load equally, and the interface
// under box k (k = 1..4 from the floor) carries (5 − k) m g:
//     point forces 2, 2, 1.5, 1.5, 1, 1, 0.5, 0.5 (× m g), Σ = 10 m g, mean 1.25 m g,
//     strong (above the mean): the 4 points under boxes 1 and 2, carrying 7/10 of Σ r_n;
//     weak: the other 4, 3/10;
//     z = (1 floor–box pair × 1 end + 3 box–box pairs × 2 ends) / 4 grains = 7/4;
//     no tangential load: every active point sticks, sliding share 0.
// Run with NLGS and (nscd_validation_newton) NEWTON_AC.
//
// Suite: Network.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "nscd/shared/postpro.hpp"
#include "validation_support.hpp"

namespace {

using namespace nscd;
using nscd::validation::add_block;
using nscd::validation::add_floor;
using nscd::validation::rel_err;
using nscd::validation::tight_options;

TEST(Network, StackOfFourBoxesHasTheStaticsSplit) {
  Registry reg;
  reg.params.dt = 1e-3;
  reg.params.theta = 0.5;
  reg.params.gravity = {0.0, -9.81};
  const MaterialId m = add_material(reg, "box", 2000.0);
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.5});
  add_floor(reg, m);
  std::vector<BodyId> boxes;
  for (int k = 0; k < 4; ++k) boxes.push_back(add_block(reg, m, 0.2, 0.1, 0.0, 0.1 * k, "box"));
  const double mg = reg.bodies.mass[boxes[0].index()] * 9.81;
  MoreauJean mj(reg, tight_options(1e-12));
  const scenes::NetworkMeter meter(reg, boxes);
  for (int n = 1; n <= 100; ++n) ASSERT_TRUE(mj.step().converged) << "step " << n;
  const scenes::NetworkSample s = meter.measure(reg);
  EXPECT_EQ(s.active_points, 8u);
  EXPECT_EQ(s.active_pairs, 4u);
  EXPECT_DOUBLE_EQ(s.coordination_number, 1.75);
  EXPECT_DOUBLE_EQ(s.double_contact_share, 1.0);
  EXPECT_LT(rel_err(s.mean_normal_force, 1.25 * mg), 1e-9);
  EXPECT_EQ(s.strong, 4u);
  EXPECT_EQ(s.weak, 4u);
  EXPECT_LT(rel_err(s.strong_force_share, 0.7), 1e-9);
  EXPECT_LT(rel_err(s.weak_force_share, 0.3), 1e-9);
  EXPECT_EQ(s.status.stick, 8u);
  EXPECT_EQ(s.status.slip_forward + s.status.slip_backward, 0u);
  EXPECT_EQ(s.sliding_share, 0.0);
  EXPECT_EQ(s.status.open + 8u, reg.contacts.size());
  // each strong point carries 2 or 1.5 m g, each weak one 1 or 0.5 m g
  for (std::size_t k = 0; k < reg.contacts.size(); ++k) {
    const double r = reg.contacts.rn[k] / mg;
    if (r > 0.0) {
      EXPECT_TRUE(std::abs(r - 2.0) < 1e-6 || std::abs(r - 1.5) < 1e-6 || std::abs(r - 1.0) < 1e-6 || std::abs(r - 0.5) < 1e-6) << r;
    }
  }
  std::printf("[ measured ] stack of 4: z %.4f, strong %zu (share %.12f), weak %zu (share %.12f), mean r_n / m g %.12f\n",
              s.coordination_number, s.strong, s.strong_force_share, s.weak, s.weak_force_share, s.mean_normal_force / mg);
}

}  // namespace
