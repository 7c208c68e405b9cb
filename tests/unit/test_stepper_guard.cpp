// tests/unit/test_stepper_guard.cpp — the stepper's guard (issue #9): a non-finite value
// anywhere in a step (state, a user's force, warm-start impulses) refuses the step with an
// nscd::Error naming the step and the bodies, leaving the state as it was; the broad phase
// never reads out of bounds on non-finite or huge coordinates.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "nscd/interactions/broad_phase.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "temp_path.hpp"
#include "special_values.hpp"
#include "threads.hpp"
#include "nscd/solvers/thread_range.hpp"

namespace {

using namespace nscd;

using nscd::testing_support::kInf;
using nscd::testing_support::kNaN;

// A fixed floor (top face y = 0) and a 0.2 × 0.1 block resting on it, named "block".
struct BlockScene {
  Registry reg;
  BodyId floor, block;
  BlockScene() {
    reg.params.dt = 1e-3;
    const MaterialId m = add_material(reg, "STONE", 2000.0);
    set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.5});
    floor = add_polygon_body(reg, rectangle(4.0, 1.0), m, {0.0, -0.5}, 0.0, "floor");
    fix_body(reg, floor);
    block = add_polygon_body(reg, rectangle(0.2, 0.1), m, {0.0, 0.05}, 0.0, "block");
  }
};

struct State {
  std::vector<double> x, y, a, vx, vy, w;
  double t;
  std::int64_t step;
  explicit State(const Registry& r)
      : x(r.bodies.x), y(r.bodies.y), a(r.bodies.angle), vx(r.bodies.vx), vy(r.bodies.vy), w(r.bodies.spin),
        t(r.time), step(r.step) {}
  bool operator==(const State&) const = default;
};

std::string error_of(MoreauJean& mj) {
  try {
    mj.step();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(StepperGuard, NanForceFromAUserFunctionRefusesTheStep) {
  BlockScene s;
  impose_force(s.reg, s.block, Dof::Y, TimeFunction::lambda([](double t) { return t > 2.2e-3 ? kNaN : 0.0; }));
  MoreauJean mj(s.reg);
  mj.step();
  mj.step();
  const State before(s.reg);
  const std::string msg = error_of(mj);
  ASSERT_FALSE(msg.empty()) << "a NaN force must refuse the step";
  EXPECT_NE(msg.find("step 3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'block'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("force"), std::string::npos) << msg;
  EXPECT_TRUE(State(s.reg) == before) << "a refused step leaves the state as it was";
  // the stepper is usable again once the cause is removed
  s.reg.bodies.drives.clear();
  s.reg.bodies.is_driven[s.block.index()] = 0;
  EXPECT_NO_THROW(mj.step());
}

TEST(StepperGuard, NonFiniteStateIsAnNscdErrorNamingTheBody) {
  for (double bad : {kNaN, kInf, -kInf}) {
    BlockScene s;
    MoreauJean mj(s.reg);
    mj.step();
    s.reg.bodies.x[s.block.index()] = bad;
    const State before(s.reg);
    const std::string msg = error_of(mj);  // must not be std::length_error nor a crash
    ASSERT_FALSE(msg.empty());
    EXPECT_NE(msg.find("'block'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("step 2"), std::string::npos) << msg;
    EXPECT_EQ(s.reg.step, before.step);
  }
  BlockScene s;
  MoreauJean mj(s.reg);
  s.reg.bodies.vy[s.block.index()] = kInf;
  EXPECT_THROW(mj.step(), Error);
}

TEST(StepperGuard, ALargeScenesChecksOnTwoThreadsNameTheBody) {
  NSCD_SKIP_WITHOUT_THREADS();
  // From kLightParallelMin bodies on, the start state, the free state and the solution are read
  // on the threads: a bad value in the last body is still found and named, the state kept.
  BlockScene s;
  const MaterialId m = s.reg.bodies.material[s.block.index()];
  for (std::size_t k = 0; k < kLightParallelMin; ++k)
    add_polygon_body(s.reg, rectangle(0.02, 0.02), m, {-2.0 + 0.03 * double(k % 120), 1.0 + 0.05 * double(k / 120)},
                     0.0, "grain" + std::to_string(k));
  const std::size_t last = s.reg.bodies.size() - 1;
  StepperOptions o;
  o.threads = o.loop_threads = 2;
  MoreauJean mj(s.reg, o);
  mj.step();
  s.reg.bodies.angle[last] = kNaN;  // the start state
  const State before(s.reg);
  std::string msg = error_of(mj);
  EXPECT_NE(msg.find("non-finite state at the start"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'grain" + std::to_string(kLightParallelMin - 1) + "'"), std::string::npos) << msg;
  EXPECT_EQ(s.reg.step, before.step);
  s.reg.bodies.angle[last] = 0.0;
  const BodyId grain(static_cast<std::uint32_t>(last));
  impose_force(s.reg, grain, Dof::X, TimeFunction::lambda([](double) { return kInf; }));
  msg = error_of(mj);  // the free state
  EXPECT_NE(msg.find("non-finite free state"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'grain" + std::to_string(kLightParallelMin - 1) + "'"), std::string::npos) << msg;
}

TEST(StepperGuard, NonFiniteWarmStartImpulseRefusesTheStepAndDumpsTheProblem) {
  BlockScene s;
  const std::filesystem::path dump = nscd::testing_support::unique_temp_path("guard_dump").concat(".txt");
  std::filesystem::remove(dump);
  StepperOptions o;
  o.failure_dump = dump.string();
  MoreauJean mj(s.reg, o);
  mj.step();
  ContactHistory m = mj.warm_start_memory();
  ASSERT_FALSE(m.empty());
  for (auto& e : m) e.rn = kInf;  // a sample file's `w` line holding inf
  mj.set_warm_start_memory(m);
  const State before(s.reg);
  const std::string msg = error_of(mj);
  ASSERT_FALSE(msg.empty());
  EXPECT_NE(msg.find("step 2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'block'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("contact"), std::string::npos) << msg;
  EXPECT_NE(msg.find(dump.string()), std::string::npos) << msg;
  EXPECT_TRUE(std::filesystem::exists(dump));
  EXPECT_TRUE(State(s.reg) == before);
  std::filesystem::remove(dump);
}

TEST(StepperGuard, OverflowingPositionsAreRefused) {
  BlockScene s;
  s.reg.bodies.vy[s.block.index()] = 1e307;
  s.reg.params.dt = 1e3;
  MoreauJean mj(s.reg);
  const State before(s.reg);
  EXPECT_THROW(mj.step(), Error);
  EXPECT_TRUE(State(s.reg) == before);
}

TEST(BroadPhaseGuard, NonFiniteBoxesAreAnErrorNotAnOutOfBoundsRead) {
  BroadPhase ws;
  const std::vector<std::uint8_t> big(3, 0);
  for (double bad : {kNaN, kInf, -kInf}) {
    const std::vector<Aabb> boxes{{0, 0, 1, 1}, {0.5, 0.5, 1.5, 1.5}, {bad, 0, 1, 1}};
    EXPECT_THROW(find_pairs(boxes, big, ws), Error);
  }
}

TEST(BroadPhaseGuard, HugeCoordinatesGiveTheBruteForcePairs) {
  BroadPhase ws;
  const std::vector<std::uint8_t> big(4, 0);
  // spans that overflow to infinity when subtracted (x1 − x0 > max double)
  const std::vector<Aabb> boxes{{-1.7e308, 0, -1.6e308, 1}, {0, 0, 1, 1}, {0.5, 0.5, 1.5, 1.5}, {1.6e308, 0, 1.7e308, 1}};
  const std::vector<Aabb> far{{-1e300, 0, -1e300 + 1e290, 1}, {0, 0, 1, 1}, {0.5, 0.5, 1.5, 1.5}, {1e300, 0, 1e300 + 1e290, 1}};
  for (int threads : {1, 2}) {
    EXPECT_THROW(find_pairs(boxes, big, ws, threads), Error);
    find_pairs(far, big, ws, threads);
    EXPECT_EQ(ws.pairs, find_pairs_brute_force(far));
  }
}

}  // namespace
