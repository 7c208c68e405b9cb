// tests/unit/checkpoint_fixtures.hpp — what the tests of src/io/checkpoint share
// (test_checkpoint.cpp, test_checkpoint_files.cpp): a fresh directory per test, files read and
// written whole, and the scene saved.
//
// The scene: a fixed ground (no contactor, no material) anchoring three pads on VOIGT_ROD
// springs (one with a prestrain, one with its L0 left to default), three pentagonal grains
// dropped on the pads, a sleeper on top driven by a cosine force with a ramp and a start time
// and an imposed horizontal velocity, a fixed "big" wall, three contact laws (a default and two
// material pairs). After 300 steps it has velocities, contact and spring forces and a
// warm-start memory.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/contactors/pt2dx.hpp"
#include "nscd/interactions/ptpt2.hpp"

namespace nscd::checkpoint_fixtures {

namespace fs = std::filesystem;

inline std::string read_bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

inline void write_text(const fs::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary | std::ios::trunc);
  f << text;
}

/// A fresh directory per test, removed afterwards.
class CheckpointDir : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = fs::temp_directory_path() /
          ("nscd_checkpoint_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
  fs::path dir;
};

// ---- the scene --------------------------------------------------------------------------------

struct CheckpointScene {
  Registry reg;
  BodyId ground, wall, sleeper;
  std::vector<BodyId> pads, grains;
};

inline CheckpointScene make_scene() {
  CheckpointScene s;
  Registry& reg = s.reg;
  reg.params.dt = 5e-4;
  reg.params.theta = 0.55;
  reg.params.gravity = {0.2, -9.81};
  reg.params.alert = 2e-3;
  const MaterialId grain = add_material(reg, "grain", 2367.0);
  const MaterialId pad = add_material(reg, "pad", 800.0);
  const MaterialId alu = add_material(reg, "aluminium", 2700.0);
  const MaterialId steel = add_material(reg, "steel", 7800.0);
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.5, 0.0, 0.0});
  set_contact_law(reg, alu, grain, LawSpec{LawKind::RST_CLB, 0.4, 0.3, 0.1});
  set_contact_law(reg, pad, grain, LawSpec{LawKind::GAP_SGR_CLB, 0.6, 0.0, 0.0});

  RigidBodySpec g;  // no material, no contactor: the springs' anchor
  g.name = "ground";
  g.mass = 1.0;
  g.inertia = 1.0;
  s.ground = add_body(reg, g);
  fix_body(reg, s.ground);

  const double xs[3] = {-0.11, 0.0, 0.11};
  const double L0 = 0.2, pad_h = 0.02;
  for (int i = 0; i < 3; ++i) {
    const BodyId p = add_polygon_body(reg, rectangle(0.1, pad_h), pad, {xs[i], L0 + 0.5 * pad_h}, 0.0, "pad " + std::to_string(i));
    fix_dof(reg, p, Dof::X);
    fix_dof(reg, p, Dof::Rot);
    const PointId top = attach_point_world(reg, p, {xs[i], L0});
    const PointId anchor = attach_point_world(reg, s.ground, {xs[i], 0.0});
    const double L0_given = i == 2 ? 0.0 : L0;      // pad 2: L0 from the current length
    const double eps0 = i == 1 ? 0.05 : 0.0;        // pad 1: prestrained
    add_spring(reg, top, anchor, VoigtRod{4100.0, 80.0, L0_given, eps0});
    s.pads.push_back(p);
  }
  // pentagons (vertex up, flat bottom R cos 36° = 0.01618 below the centre) 1 mm above the pads
  const double R = 0.02, bottom = R * std::cos(kPi / 5.0);
  for (int i = 0; i < 3; ++i) {
    const BodyId b = add_polygon_body(reg, regular_polygon(5, 2.0 * R, 0.5 * kPi), grain,
                                      {xs[i] + 0.003 * i, L0 + pad_h + bottom + 1e-3}, 0.0, "grain " + std::to_string(i));
    reg.bodies.vy[b.index()] = -0.1;
    reg.bodies.spin[b.index()] = 0.5 - 0.5 * i;
    s.grains.push_back(b);
  }
  // the sleeper 2 mm above the grains' tops, driven: Y by a cosine force (ramp 0.01 s, starting
  // at t = 0.005 s), X at an imposed velocity, Rot fixed
  const double top = L0 + pad_h + bottom + 1e-3 + R;
  s.sleeper = add_polygon_body(reg, rectangle(0.3, 0.04), alu, {0.0, top + 2e-3 + 0.02}, 0.0, "sleeper");
  impose_force(reg, s.sleeper, Dof::Y, TimeFunction::cosine(-50.0, -20.0, 5.0, -kPi, 0.01, 0.005));
  impose_velocity(reg, s.sleeper, Dof::X, TimeFunction::constant(0.002));
  fix_dof(reg, s.sleeper, Dof::Rot);
  // a fixed side wall, well away, tall enough to be "big" (radius 0.6 > 8 × the median 0.05)
  s.wall = add_polygon_body(reg, rectangle(0.02, 1.2), steel, {0.3, 0.6}, 0.0, "wall");
  fix_body(reg, s.wall);
  return s;
}

inline const std::map<std::string, std::string> kExtra{{"kind", "unit test"},
                                                       {"cycles done", "12"},
                                                       {"with \"quotes\" and \\ backslash", "a value with spaces"},
                                                       {"empty", ""}};

}  // namespace nscd::checkpoint_fixtures
