// tests/unit/test_plplx_kept.cpp — what detect_plplx keeps from one detection to the next (the
// broad phase's kept list, the narrow phase's results for polygons that have not moved) must not
// change a single bit of its contact table. A detector that lives through a sequence of
// configurations, some bodies moving and others still, is compared at every step with a fresh
// detector that has kept nothing; the sequence also changes what a kept result depends on
// besides the positions: the alert distance, a polygon's own vertices, a body made kinematic, a
// body moved and moved back, a detection that throws.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "nscd/core/error.hpp"
#include "nscd/interactions/plplx.hpp"
#include "nscd/shared/samples.hpp"

namespace nscd {
namespace {

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

/// Every column that detection writes, bit for bit.
void expect_same_table(const ContactTable& a, const ContactTable& b, int step) {
  ASSERT_EQ(a.size(), b.size()) << "step " << step;
  EXPECT_TRUE(same_bits(a.candidate, b.candidate)) << "step " << step;
  EXPECT_TRUE(same_bits(a.antagonist, b.antagonist)) << "step " << step;
  EXPECT_TRUE(same_bits(a.cd_body, b.cd_body)) << "step " << step;
  EXPECT_TRUE(same_bits(a.an_body, b.an_body)) << "step " << step;
  EXPECT_TRUE(same_bits(a.feature, b.feature)) << "step " << step;
  EXPECT_TRUE(same_bits(a.gap, b.gap)) << "step " << step;
  EXPECT_TRUE(same_bits(a.normal, b.normal)) << "step " << step;
  EXPECT_TRUE(same_bits(a.point, b.point)) << "step " << step;
  EXPECT_TRUE(same_bits(a.cd_rn, b.cd_rn) && same_bits(a.cd_rt, b.cd_rt)) << "step " << step;
  EXPECT_TRUE(same_bits(a.an_rn, b.an_rn) && same_bits(a.an_rt, b.an_rt)) << "step " << step;
  EXPECT_TRUE(same_bits(a.law, b.law) && same_bits(a.mu, b.mu)) << "step " << step;
}

TEST(PlplxKept, TheContactsAreThoseOfAFreshDetectorAtEveryStepOnOneAndTwoThreads) {
  for (const int threads : {1, 2}) {
    SCOPED_TRACE(testing::Message() << threads << " thread(s)");
    scenes::Scene s = scenes::pentagon_field(1200, 0.01, 0.009, 2006);
    Registry& reg = s.reg;
    PlplxDetector kept;
    kept.threads = threads;
    classify_big_polygons(reg, kept.big_ratio);
    std::mt19937 rng(5);
    std::normal_distribution<double> nudge(0.0, 2e-5);
    std::bernoulli_distribution moves(1.0 / 3.0);
    std::size_t kept_pairs = 0, candidate_pairs = 0, rebuilds_seen = 0;
    const std::size_t nb = reg.bodies.size();
    for (int step = 0; step < 60; ++step) {
      // a third of the bodies, drawn anew at each step, move a little (none at all every fifth
      // step); the rest stay put
      if (step % 5 != 4)
        for (std::size_t i = 0; i < nb; ++i)
          if (moves(rng)) {
            reg.bodies.x[i] += nudge(rng);
            reg.bodies.y[i] += nudge(rng);
            reg.bodies.angle[i] += 50.0 * nudge(rng);
          }
      if (step == 12) reg.params.alert *= 0.9;  // another alert distance (the boxes shrink by less than the slack: no rebuild)
      if (step == 19)  // (a step without motion) ten polygons' own shapes shrink by 0.5 % (no rebuild)
        for (std::size_t p = 40; p < 440; p += 40)
          for (std::uint32_t v = reg.polyg.first_vertex[p]; v < reg.polyg.first_vertex[p] + reg.polyg.vertex_count[p]; ++v)
            reg.polyg.vertex[v] = reg.polyg.centre[p] + 0.995 * (reg.polyg.vertex[v] - reg.polyg.centre[p]);
      if (step == 24)                                                     // two neighbours made kinematic
        for (const std::size_t i : {100u, 101u}) reg.bodies.inv_mass_x[i] = reg.bodies.inv_mass_y[i] = reg.bodies.inv_inertia[i] = 0.0;
      if (step == 30) reg.bodies.x[200] += 0.003;                         // away …
      if (step == 31) reg.bodies.x[200] -= 0.003;                         // … and back (near, not exactly)
      if (step == 36) {                                                   // a detection that throws
        const double x = reg.bodies.x[300];
        reg.bodies.x[300] = std::numeric_limits<double>::infinity();  // a box that is not finite
        EXPECT_THROW(detect_plplx(reg, kept), Error);
        reg.bodies.x[300] = x;
      }
      const DetectionStats st = detect_plplx(reg, kept);
      Registry fresh_reg = reg;
      PlplxDetector fresh;
      fresh.threads = threads;
      detect_plplx(fresh_reg, fresh);
      expect_same_table(reg.contacts, fresh_reg.contacts, step);
      EXPECT_GT(st.contact_points, nb);  // a packed field: the comparison is not vacuous
      kept_pairs += st.kept_pairs;
      candidate_pairs += st.candidate_pairs;
      rebuilds_seen = kept.broad.rebuilds;
    }
    // much was kept, not all: a pair is kept when both polygons were still at this detection and
    // the last ((2/3)^4 of the pairs, and more on the steps without motion)
    EXPECT_GT(kept_pairs, candidate_pairs / 10);
    EXPECT_LT(kept_pairs, candidate_pairs);
    EXPECT_GE(rebuilds_seen, 1u);
  }
}

TEST(PlplxKept, AStillSceneKeepsEveryPairAfterItsFirstTwoDetections) {
  scenes::Scene s = scenes::pentagon_field(300, 0.01, 0.009, 7);
  PlplxDetector det;
  classify_big_polygons(s.reg, det.big_ratio);
  // first: nothing to compare with; second: the pairs are still but were kept by no detection
  EXPECT_EQ(detect_plplx(s.reg, det).kept_pairs, 0u);
  EXPECT_EQ(detect_plplx(s.reg, det).kept_pairs, 0u);
  const DetectionStats third = detect_plplx(s.reg, det);
  EXPECT_EQ(third.kept_pairs, third.candidate_pairs);
  EXPECT_GT(third.candidate_pairs, 300u);
}

TEST(PlplxKept, TheLastDetectionsRowsAreWrittenOverAndCut) {
  // detect_plplx writes its points over the last detection's rows (and the forces a solve put
  // in them) and cuts the table to its points: after more points and after fewer, the table is
  // a fresh registry's, forces zero and statuses open, on one thread and on two.
  for (const int threads : {1, 2}) {
    SCOPED_TRACE(testing::Message() << threads << " thread(s)");
    scenes::Scene s = scenes::pentagon_field(1200, 0.01, 0.009, 11);
    Registry& reg = s.reg;
    PlplxDetector det;
    det.threads = threads;
    classify_big_polygons(reg, det.big_ratio);
    const std::vector<double> x0 = reg.bodies.x, y0 = reg.bodies.y;
    std::size_t points[3] = {};
    for (int k = 0; k < 3; ++k) {
      const double spread = k == 1 ? 1.06 : 1.0;  // the field spread out (fewer contacts), then back
      for (std::size_t i = 0; i < x0.size(); ++i) {
        reg.bodies.x[i] = spread * x0[i];
        reg.bodies.y[i] = spread * y0[i];
      }
      points[k] = detect_plplx(reg, det).contact_points;
      Registry fresh = reg;
      fresh.contacts = ContactTable{};
      PlplxDetector other;
      other.threads = threads;
      detect_plplx(fresh, other);
      expect_same_table(reg.contacts, fresh.contacts, k);
      const ContactTable& c = reg.contacts;
      EXPECT_EQ(c.size(), points[k]);
      EXPECT_TRUE(std::all_of(c.rn.begin(), c.rn.end(), [](double r) { return r == 0.0; }));
      EXPECT_TRUE(std::all_of(c.rt.begin(), c.rt.end(), [](double r) { return r == 0.0; }));
      EXPECT_TRUE(std::all_of(c.status.begin(), c.status.end(), [](ContactStatus x) { return x == ContactStatus::Open; }));
      std::fill(reg.contacts.rn.begin(), reg.contacts.rn.end(), 1.0);  // a solve's forces, to be written over
      std::fill(reg.contacts.rt.begin(), reg.contacts.rt.end(), -1.0);
      std::fill(reg.contacts.status.begin(), reg.contacts.status.end(), ContactStatus::Stick);
    }
    EXPECT_LT(points[1], points[0] * 9 / 10);  // fewer rows, then more again
    EXPECT_EQ(points[2], points[0]);
  }
}

}  // namespace
}  // namespace nscd
