// Tests of the contact-network time series (shared/postpro.hpp) on a hand-made contact table
// whose answers are counted by hand: coordination number, sliding share, the strong / weak
// split about the mean normal force, the status counts; and their CSV columns.
#include <gtest/gtest.h>

#include <cmath>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/core/error.hpp"
#include "nscd/core/thread_share.hpp"
#include "nscd/shared/analysis.hpp"
#include "nscd/shared/postpro.hpp"
#include "threads.hpp"

using namespace nscd;
using namespace nscd::scenes;

namespace {

struct Row {
  BodyId cd, an;
  double rn;
  ContactStatus status;
};

// Grains g0..g3 (g3 a rattler, no contact) and a wall.
struct HandScene {
  Registry reg;
  std::vector<BodyId> grains;
  BodyId wall;
};

HandScene hand_scene() {
  HandScene s;
  for (int i = 0; i < 5; ++i) {
    RigidBodySpec b;
    b.name = i < 4 ? "grain" : "wall";
    b.mass = 1.0;
    b.inertia = 1.0;
    b.position = {double(i), 0.0};
    const BodyId id = add_body(s.reg, b);
    if (i < 4) s.grains.push_back(id);
    else s.wall = id;
  }
  return s;
}

void fill(Registry& reg, const std::vector<Row>& rows) {
  reg.contacts.resize(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    reg.contacts.cd_body[k] = rows[k].cd;
    reg.contacts.an_body[k] = rows[k].an;
    reg.contacts.rn[k] = rows[k].rn;
    reg.contacts.rt[k] = 0.0;
    reg.contacts.status[k] = rows[k].status;
  }
}

// rows (points of a pair consecutive, as detection lists them):
//   g0–g1: r_n 3 (stick), 1 (slip +)     an active pair touching by two points: 2 grain ends
//   g1–g2: 2 (stick)                     2 ends
//   g2–wall: 8 (slip −)                  1 end (the wall is no grain)
//   g0–g2: 0 (open)                      inactive
//   g1–wall: 5 (stick)                   1 end
// active points 5, Σ r_n = 19, mean 3.8: strong {8, 5} (13/19 of the force), weak {3, 1, 2}
// (6/19); z = 6 ends / 4 grains = 1.5; pairs 4, one by two points; sliding 2/5.
TEST(Postpro, NetworkOfAHandMadeTableIsCountedByHand) {
  HandScene s = hand_scene();
  const auto& g = s.grains;
  fill(s.reg, {{g[0], g[1], 3.0, ContactStatus::Stick},
               {g[0], g[1], 1.0, ContactStatus::SlipForward},
               {g[1], g[2], 2.0, ContactStatus::Stick},
               {g[2], s.wall, 8.0, ContactStatus::SlipBackward},
               {g[0], g[2], 0.0, ContactStatus::Open},
               {g[1], s.wall, 5.0, ContactStatus::Stick}});
  const NetworkMeter meter(s.reg, g);
  const NetworkSample n = meter.measure(s.reg);
  EXPECT_DOUBLE_EQ(n.coordination_number, 1.5);
  EXPECT_EQ(n.active_pairs, 4u);
  EXPECT_EQ(n.active_points, 5u);
  EXPECT_DOUBLE_EQ(n.double_contact_share, 0.25);
  EXPECT_DOUBLE_EQ(n.sliding_share, 0.4);
  EXPECT_DOUBLE_EQ(n.mean_normal_force, 3.8);
  EXPECT_EQ(n.strong, 2u);
  EXPECT_EQ(n.weak, 3u);
  EXPECT_DOUBLE_EQ(n.strong_force_share, 13.0 / 19.0);
  EXPECT_DOUBLE_EQ(n.weak_force_share, 6.0 / 19.0);
  EXPECT_EQ(n.status.open, 1u);
  EXPECT_EQ(n.status.stick, 3u);
  EXPECT_EQ(n.status.slip_forward, 1u);
  EXPECT_EQ(n.status.slip_backward, 1u);
  // the summaries' contact_network is the same definition
  const ContactNetwork c = contact_network(s.reg, g);
  EXPECT_DOUBLE_EQ(c.coordination_number, 1.5);
  EXPECT_DOUBLE_EQ(c.double_contact_share, 0.25);
  EXPECT_EQ(c.active_pairs, 4u);
  EXPECT_EQ(c.active_points, 5u);
  // a force exactly at the mean is weak (strong: above the mean)
  fill(s.reg, {{g[0], g[1], 2.0, ContactStatus::Stick}, {g[1], g[2], 2.0, ContactStatus::Stick}});
  const NetworkSample eq = meter.measure(s.reg);
  EXPECT_EQ(eq.strong, 0u);
  EXPECT_EQ(eq.weak, 2u);
  EXPECT_DOUBLE_EQ(eq.weak_force_share, 1.0);
  EXPECT_DOUBLE_EQ(eq.coordination_number, 1.0);  // 4 ends / 4 grains
}

TEST(Postpro, NoActiveContactGivesZeros) {
  HandScene s = hand_scene();
  fill(s.reg, {{s.grains[0], s.grains[1], 0.0, ContactStatus::Open}});
  const NetworkSample n = NetworkMeter(s.reg, s.grains).measure(s.reg);
  EXPECT_EQ(n.coordination_number, 0.0);
  EXPECT_EQ(n.sliding_share, 0.0);
  EXPECT_EQ(n.strong + n.weak, 0u);
  EXPECT_EQ(n.strong_force_share, 0.0);
  EXPECT_EQ(n.weak_force_share, 0.0);
  EXPECT_EQ(n.status.open, 1u);
}

TEST(Postpro, ColumnsMatchTheValuesAndBadInputIsRefused) {
  HandScene s = hand_scene();
  std::vector<double> row = {42.0};
  append_network_values(NetworkMeter(s.reg, s.grains).measure(s.reg), row);
  EXPECT_EQ(row.size(), 1 + network_columns().size());
  EXPECT_EQ(row[0], 42.0);
  EXPECT_EQ(network_columns().front(), "coordination_number");
  // a grain that is not a body; a registry of another size than the meter was built for
  const std::vector<BodyId> bad = {BodyId(17)};
  EXPECT_THROW(NetworkMeter(s.reg, bad), Error);
  const NetworkMeter meter(s.reg, s.grains);
  RigidBodySpec extra;
  extra.mass = 1.0;
  extra.inertia = 1.0;
  add_body(s.reg, extra);
  EXPECT_THROW(meter.measure(s.reg), Error);
}

// The hand table's six rows again and again, turned so that its two-point pair (g0–g1) lies
// across chunk ends (rows kSumWhole − 1 and kSumWhole, among others): a cut there would count
// it as two pairs of one point. Three head rows (g2–wall, g0–g2, g1–wall), then m whole tables.
TEST(Postpro, ThreadsMeasureTheSameNetworkAndNoPairIsCutAtAChunkEnd) {
  NSCD_SKIP_WITHOUT_THREADS();
  HandScene s = hand_scene();
  const auto& g = s.grains;
  const std::vector<Row> table = {{g[0], g[1], 3.0, ContactStatus::Stick},   {g[0], g[1], 1.0, ContactStatus::SlipForward},
                                  {g[1], g[2], 2.0, ContactStatus::Stick},   {g[2], s.wall, 8.0, ContactStatus::SlipBackward},
                                  {g[0], g[2], 0.0, ContactStatus::Open},    {g[1], s.wall, 5.0, ContactStatus::Stick}};
  const std::size_t m = 2 * kSumWhole / 6 + 700, n = 3 + 6 * m;  // 10 chunks
  std::vector<Row> rows;
  for (std::size_t k = 0; k < n; ++k) rows.push_back(table[(k + 3) % 6]);
  ASSERT_TRUE(rows[kSumWhole - 1].rn == 3.0 && rows[kSumWhole].rn == 1.0 && kSumWhole % kSumChunk == 0);
  fill(s.reg, rows);
  const NetworkMeter meter(s.reg, g);
  const NetworkSample one = meter.measure(s.reg, 1);
  EXPECT_EQ(one.active_pairs, 4 * m + 2);
  EXPECT_EQ(one.active_points, 5 * m + 2);
  EXPECT_DOUBLE_EQ(one.double_contact_share, double(m) / double(4 * m + 2));
  EXPECT_DOUBLE_EQ(one.coordination_number, double(6 * m + 2) / 4.0);
  EXPECT_EQ(one.status.stick, 3 * m + 1);
  EXPECT_EQ(one.strong, 2 * m + 2);  // (the mean is 19m + 13 over 5m + 2: below 5)
  for (const int threads : {2, 3}) {
    const NetworkSample t = meter.measure(s.reg, threads);
    EXPECT_EQ(t.active_pairs, one.active_pairs);
    EXPECT_EQ(t.active_points, one.active_points);
    EXPECT_EQ(t.strong, one.strong);
    EXPECT_EQ(t.status.slip_backward, one.status.slip_backward);
    EXPECT_EQ(t.mean_normal_force, one.mean_normal_force);  // the same bits
    EXPECT_EQ(t.strong_force_share, one.strong_force_share);
    EXPECT_EQ(t.coordination_number, one.coordination_number);
  }
}

// The sums over the bodies: the same bits on 1, 2 and 3 threads beyond kSumWhole bodies, and
// up to kSumWhole the plain loop's.
TEST(Postpro, ThreadsSumTheBodiesEnergyAndSpeedAlike) {
  NSCD_SKIP_WITHOUT_THREADS();
  Registry reg;
  std::vector<BodyId> all;
  for (std::size_t i = 0; i < 2 * kSumWhole + 123; ++i) {
    RigidBodySpec b;
    b.mass = 1.0 + 1e-3 * double(i % 97);
    b.inertia = 0.5;
    b.position = {double(i), 0.0};
    b.velocity = {std::sin(double(i)), 0.1 * std::cos(3.0 * double(i))};
    b.spin = 0.01 * double(i % 13);
    all.push_back(add_body(reg, b));
  }
  const double e1 = kinetic_energy(reg, 1), v1 = rms_speed(reg, all, 1);
  for (const int threads : {2, 3}) {
    EXPECT_EQ(kinetic_energy(reg, threads), e1);
    EXPECT_EQ(rms_speed(reg, all, threads), v1);
  }
  long double e = 0.0L;  // the sum in long double: the chunks change only its last bits
  for (std::size_t i = 0; i < reg.bodies.size(); ++i)
    e += 0.5L * reg.bodies.mass[i] * (reg.bodies.vx[i] * reg.bodies.vx[i] + reg.bodies.vy[i] * reg.bodies.vy[i]) +
         0.25L * reg.bodies.spin[i] * reg.bodies.spin[i];
  EXPECT_NEAR(e1, static_cast<double>(e), 1e-12 * e1);
  double plain = 0.0;  // one chunk: the plain loop
  for (std::size_t i = 0; i < kSumWhole; ++i) plain += 1.0 / double(i + 1);
  EXPECT_EQ(ordered_sum(kSumWhole, 2, [](std::size_t i) { return 1.0 / double(i + 1); }), plain);
}

}  // namespace
