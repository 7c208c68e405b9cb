// tests/unit/test_checkpoint.cpp — unit tests of src/io/checkpoint: a save → load round trip
// gives the very same bits in every table, and a resumed run continues bit for bit. Also
// TimeFunction::cosine with a start time (saved in the checkpoints of driven bodies). The files
// (written atomically, bad ones refused): test_checkpoint_files.cpp; the scene saved (a ground,
// pads on springs, grains, a driven sleeper, a wall; 300 steps): checkpoint_fixtures.hpp.
//
// Suites: CheckpointRoundTrip, TimeFunctionStart.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "nscd/core/error.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "checkpoint_fixtures.hpp"

namespace {

using namespace nscd;
namespace fs = std::filesystem;
using namespace nscd::checkpoint_fixtures;

// ---- bitwise comparison -----------------------------------------------------------------------

template <class T>
bool same_bits(const T& a, const T& b) {
  static_assert(std::is_trivially_copyable_v<T>);
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

template <class T>
void expect_same(const std::vector<T>& a, const std::vector<T>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if constexpr (std::is_same_v<T, std::string>) {
      EXPECT_EQ(a[i], b[i]) << what << "[" << i << "]";
    } else {
      EXPECT_TRUE(same_bits(a[i], b[i])) << what << "[" << i << "]";
    }
  }
}

void expect_same(const TimeFunction& a, const TimeFunction& b, const std::string& what) {
  EXPECT_EQ(a.kind(), b.kind()) << what;
  const double pa[] = {a.A(), a.B(), a.frequency(), a.phase(), a.ramp_duration(), a.start()};
  const double pb[] = {b.A(), b.B(), b.frequency(), b.phase(), b.ramp_duration(), b.start()};
  for (int k = 0; k < 6; ++k) EXPECT_TRUE(same_bits(pa[k], pb[k])) << what << " parameter " << k;
  for (const double t : {0.0, 0.004, 0.0051, 0.01, 0.2, 1.7}) EXPECT_TRUE(same_bits(a(t), b(t))) << what << " at t " << t;
}

/// Every table a checkpoint holds (Registry::contacts, rebuilt by each detection, is not saved).
void expect_same(const Registry& a, const Registry& b) {
  EXPECT_TRUE(same_bits(a.params.dt, b.params.dt));
  EXPECT_TRUE(same_bits(a.params.theta, b.params.theta));
  EXPECT_TRUE(same_bits(a.params.gravity, b.params.gravity));
  EXPECT_TRUE(same_bits(a.params.alert, b.params.alert));
  EXPECT_TRUE(same_bits(a.time, b.time));
  EXPECT_EQ(a.step, b.step);

  expect_same(a.materials.name, b.materials.name, "materials.name");
  expect_same(a.materials.density, b.materials.density, "materials.density");
  const ContactLawTable &la = a.contact_laws, &lb = b.contact_laws;
  ASSERT_EQ(la.laws.size(), lb.laws.size());
  for (std::size_t k = 0; k < la.laws.size(); ++k) {
    EXPECT_EQ(la.laws[k].kind, lb.laws[k].kind) << "law " << k;
    EXPECT_TRUE(same_bits(la.laws[k].mu, lb.laws[k].mu)) << "law " << k;
    EXPECT_TRUE(same_bits(la.laws[k].e_n, lb.laws[k].e_n)) << "law " << k;
    EXPECT_TRUE(same_bits(la.laws[k].e_t, lb.laws[k].e_t)) << "law " << k;
  }
  expect_same(la.pair_law, lb.pair_law, "contact_laws.pair_law");
  EXPECT_EQ(la.n_materials, lb.n_materials);
  EXPECT_EQ(la.default_law, lb.default_law);

  const BodyTable &ba = a.bodies, &bb = b.bodies;
  expect_same(ba.x, bb.x, "bodies.x");
  expect_same(ba.y, bb.y, "bodies.y");
  expect_same(ba.angle, bb.angle, "bodies.angle");
  expect_same(ba.vx, bb.vx, "bodies.vx");
  expect_same(ba.vy, bb.vy, "bodies.vy");
  expect_same(ba.spin, bb.spin, "bodies.spin");
  expect_same(ba.inv_mass_x, bb.inv_mass_x, "bodies.inv_mass_x");
  expect_same(ba.inv_mass_y, bb.inv_mass_y, "bodies.inv_mass_y");
  expect_same(ba.inv_inertia, bb.inv_inertia, "bodies.inv_inertia");
  expect_same(ba.mass, bb.mass, "bodies.mass");
  expect_same(ba.inertia, bb.inertia, "bodies.inertia");
  expect_same(ba.x0, bb.x0, "bodies.x0");
  expect_same(ba.y0, bb.y0, "bodies.y0");
  expect_same(ba.angle0, bb.angle0, "bodies.angle0");
  expect_same(ba.material, bb.material, "bodies.material");
  expect_same(ba.name, bb.name, "bodies.name");
  expect_same(ba.is_driven, bb.is_driven, "bodies.is_driven");
  ASSERT_EQ(ba.drives.size(), bb.drives.size());
  for (std::size_t k = 0; k < ba.drives.size(); ++k) {
    EXPECT_EQ(ba.drives[k].body, bb.drives[k].body) << "drive " << k;
    EXPECT_EQ(ba.drives[k].dof, bb.drives[k].dof) << "drive " << k;
    EXPECT_EQ(ba.drives[k].drive, bb.drives[k].drive) << "drive " << k;
    expect_same(ba.drives[k].value, bb.drives[k].value, "drive " + std::to_string(k));
  }

  const PolygTable &pa = a.polyg, &pb = b.polyg;
  expect_same(pa.body, pb.body, "polyg.body");
  expect_same(pa.first_vertex, pb.first_vertex, "polyg.first_vertex");
  expect_same(pa.vertex_count, pb.vertex_count, "polyg.vertex_count");
  expect_same(pa.radius, pb.radius, "polyg.radius");
  expect_same(pa.is_big, pb.is_big, "polyg.is_big");
  expect_same(pa.area, pb.area, "polyg.area");
  expect_same(pa.centre, pb.centre, "polyg.centre");
  expect_same(pa.vertex, pb.vertex, "polyg.vertex");
  expect_same(pa.edge_normal, pb.edge_normal, "polyg.edge_normal");

  expect_same(a.points.body, b.points.body, "points.body");
  expect_same(a.points.point, b.points.point, "points.point");

  const Ptpt2Table &ka = a.links, &kb = b.links;
  expect_same(ka.candidate, kb.candidate, "links.candidate");
  expect_same(ka.antagonist, kb.antagonist, "links.antagonist");
  expect_same(ka.law, kb.law, "links.law");
  expect_same(ka.length, kb.length, "links.length");
  expect_same(ka.normal, kb.normal, "links.normal");
  expect_same(ka.rn, kb.rn, "links.rn");
}

void expect_same_state(const Registry& a, const Registry& b, int step) {
  const BodyTable &ba = a.bodies, &bb = b.bodies;
  for (std::size_t i = 0; i < ba.size(); ++i) {
    const bool same = same_bits(ba.x[i], bb.x[i]) && same_bits(ba.y[i], bb.y[i]) && same_bits(ba.angle[i], bb.angle[i]) &&
                      same_bits(ba.vx[i], bb.vx[i]) && same_bits(ba.vy[i], bb.vy[i]) && same_bits(ba.spin[i], bb.spin[i]);
    ASSERT_TRUE(same) << "body " << i << " differs after resumed step " << step;
  }
  for (std::size_t k = 0; k < a.links.size(); ++k)
    ASSERT_TRUE(same_bits(a.links.rn[k], b.links.rn[k])) << "link " << k << " after resumed step " << step;
}

// ---- round trip -------------------------------------------------------------------------------

using CheckpointRoundTrip = CheckpointDir;

TEST_F(CheckpointRoundTrip, EveryTableComesBackBitForBitAndTheRunContinuesBitForBit) {
  CheckpointScene s = make_scene();
  MoreauJean mj(s.reg);
  for (int n = 0; n < 300; ++n) mj.step();
  // the state worth saving: moving bodies, loaded springs, contacts remembered
  ASSERT_GT(mj.warm_start_memory().size(), 3u);
  for (double rn : s.reg.links.rn) ASSERT_GT(rn, 1.0);
  ASSERT_NE(s.reg.bodies.vy[s.grains[0].index()], 0.0);
  ASSERT_NE(s.reg.bodies.spin[s.grains[1].index()], 0.0);
  ASSERT_NE(s.reg.bodies.x[s.sleeper.index()], s.reg.bodies.x0[s.sleeper.index()]);  // driven in X
  ASSERT_EQ(s.reg.polyg.is_big.back(), 1);  // the wall, classified by the stepper's detection
  // the links' frames were taken at q_m, not at the saved q_f: they must be saved, not recomputed
  ASSERT_NE(s.reg.links.length[0], link_frame(s.reg, LinkId(0), s.reg.bodies.x, s.reg.bodies.y, s.reg.bodies.angle).length);

  const fs::path file = dir / "state.nscd";
  save_checkpoint(file, s.reg, mj.warm_start_memory(), kExtra);
  const Checkpoint cp = load_checkpoint(file);
  expect_same(s.reg, cp.reg);
  EXPECT_EQ(cp.extra, kExtra);
  const auto& wa = mj.warm_start_memory();
  ASSERT_EQ(cp.warm_start.size(), wa.size());
  for (std::size_t k = 0; k < wa.size(); ++k) {
    EXPECT_EQ(cp.warm_start[k].pair, wa[k].pair);
    EXPECT_EQ(cp.warm_start[k].feature, wa[k].feature);
    EXPECT_TRUE(same_bits(cp.warm_start[k].rn, wa[k].rn));
    EXPECT_TRUE(same_bits(cp.warm_start[k].rt, wa[k].rt));
  }

  // Resume: the original goes on with its stepper, the copy with a fresh one fed the saved
  // warm-start memory; 200 steps later they agree to the last bit.
  Registry resumed = cp.reg;
  MoreauJean mr(resumed);
  mr.set_warm_start_memory(cp.warm_start);
  for (int n = 1; n <= 200; ++n) {
    const StepReport ra = mj.step();
    const StepReport rb = mr.step();
    ASSERT_EQ(ra.contacts, rb.contacts) << "step " << n;
    ASSERT_EQ(ra.sweeps, rb.sweeps) << "step " << n;
    expect_same_state(s.reg, resumed, n);
  }
  EXPECT_TRUE(same_bits(s.reg.time, resumed.time));
  EXPECT_EQ(s.reg.step, resumed.step);

  // a second save of the loaded scene is the same file, byte for byte
  const fs::path again = dir / "again.nscd";
  save_checkpoint(again, cp.reg, cp.warm_start, cp.extra);
  EXPECT_EQ(read_bytes(again), read_bytes(file));
}

TEST_F(CheckpointRoundTrip, ALinkSqueezedToZeroLengthReloads) {
  // The two points of a link may meet during a run (a pad pushed through its anchor); the
  // checkpoint keeps the link's last direction and loads it back.
  Registry reg;
  RigidBodySpec a, b;
  a.name = "anchor";
  a.mass = a.inertia = 1.0;
  b.name = "mover";
  b.mass = b.inertia = 1.0;
  b.position = {0.0, 1.0};
  const BodyId ba = add_body(reg, a), bb = add_body(reg, b);
  add_spring(reg, attach_point(reg, bb, {0.0, 0.0}), attach_point(reg, ba, {0.0, 0.0}), VoigtRod{10.0, 1.0, 0.0, 0.0});
  reg.bodies.y[bb.index()] = 0.0;  // now on the anchor
  reg.links.length[0] = 0.0;
  reg.links.rn[0] = 10.0;
  const fs::path file = dir / "zero.nscd";
  save_checkpoint(file, reg);
  Checkpoint cp;
  ASSERT_NO_THROW(cp = load_checkpoint(file));
  expect_same(reg, cp.reg);
  EXPECT_EQ(cp.reg.links.normal[0], (Vec2{0.0, 1.0}));
}

TEST_F(CheckpointRoundTrip, VersionTwoFilesStillLoad) {
  // Version 2 had no is_big flag on "p" lines and no length and normal on "lk" lines: the
  // links then take their frame from the saved configuration.
  CheckpointScene s = make_scene();
  const fs::path v3 = dir / "v3.nscd", v2 = dir / "v2.nscd";
  save_checkpoint(v3, s.reg);
  std::istringstream in(read_bytes(v3));
  std::string out, line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::vector<std::string> tok;
    for (std::string t; ls >> t;) tok.push_back(t);
    if (!tok.empty() && tok[0] == "nscd-checkpoint") tok[1] = "2";
    if (!tok.empty() && tok[0] == "p") tok.erase(tok.begin() + 2);
    if (!tok.empty() && tok[0] == "lk") tok.resize(tok.size() - 3);
    for (std::size_t k = 0; k < tok.size(); ++k) out += (k ? " " : "") + tok[k];
    out += '\n';
  }
  write_text(v2, out);
  const Checkpoint cp = load_checkpoint(v2);
  expect_same(s.reg, cp.reg);  // a fresh scene: frames at the saved configuration, is_big 0
}

// ---- TimeFunction with a start time -----------------------------------------------------------

TEST(TimeFunctionStart, CosineIsZeroBeforeTheStartAndRampsFromIt) {
  // f(t) = ramp(s) (A + B cos(2π f s − φ)), s = t − t0; A = 2, B = 1, f = 5 Hz, φ = 0,
  // ramp 0.1 s, t0 = 0.3 s:
  //   t < 0.3: 0;  t = 0.3: ramp 0 → 0;
  //   t = 0.35: s = 0.05, ramp 0.5, cos(π/2) = 0 → 0.5 × 2 = 1
  //   t = 0.4:  s = 0.1, ramp 1, cos(π) = −1 → 1
  //   t = 0.5:  s = 0.2, cos(2π) = 1 → 3
  const TimeFunction f = TimeFunction::cosine(2.0, 1.0, 5.0, 0.0, 0.1, 0.3);
  EXPECT_EQ(f.start(), 0.3);
  EXPECT_EQ(f(-1.0), 0.0);
  EXPECT_EQ(f(0.0), 0.0);
  EXPECT_EQ(f(0.2999), 0.0);
  EXPECT_EQ(f(0.3), 0.0);
  EXPECT_NEAR(f(0.35), 1.0, 1e-12);
  EXPECT_NEAR(f(0.4), 1.0, 1e-12);
  EXPECT_NEAR(f(0.5), 3.0, 1e-12);
  // without a ramp the load jumps on at t0: A + B cos(0) = 3
  const TimeFunction g = TimeFunction::cosine(2.0, 1.0, 5.0, 0.0, 0.0, 0.3);
  EXPECT_EQ(g(0.2999), 0.0);
  EXPECT_NEAR(g(0.3), 3.0, 1e-15);
  // the paper's load (A = −1000, B = −500, φ = −π) starts at A + B cos(π) = −500
  const TimeFunction p = TimeFunction::cosine(-1000.0, -500.0, 1.0, -kPi, 0.0, 2.0);
  EXPECT_NEAR(p(2.0), -1000.0 + 500.0, 1e-9);
  EXPECT_EQ(p(1.99), 0.0);
  // a start in the past is just a shifted phase: s = 0.1 at t = 0 → 2 + cos(π) = 1
  EXPECT_NEAR(TimeFunction::cosine(2.0, 1.0, 5.0, 0.0, 0.0, -0.1)(0.0), 1.0, 1e-12);
  // the default start is 0
  EXPECT_EQ(TimeFunction::cosine(2.0, 1.0, 5.0, 0.0).start(), 0.0);
  EXPECT_THROW(TimeFunction::cosine(2.0, 1.0, 5.0, 0.0, 0.0, std::numeric_limits<double>::infinity()), Error);
  EXPECT_THROW(TimeFunction::cosine(2.0, 1.0, 5.0, 0.0, 0.0, std::numeric_limits<double>::quiet_NaN()), Error);
}

}  // namespace
