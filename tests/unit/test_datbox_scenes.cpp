// tests/unit/test_datbox_scenes.cpp — LMGC90's own 2D rigid scenes (issue #39): the DATBOX
// folders tests/data/datbox/{disks_jcbox, polygons_jcbox, disk_drum, block_wall}, made by LMGC90's
// pre-processor (contrib/lmgc90/datbox_scenes.py), run as docs/benchmarks.md §9 runs them in both
// codes, and their end state checked against the figures LMGC90 3.0.0.rc1 gave for the same run
// (contrib/lmgc90/run_datbox.py, measured as contrib/lmgc90/compare_datbox.py measures them).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <ostream>
#include <set>
#include <string>
#include <utility>

#include "nscd/io/datbox.hpp"
#include "nscd/solvers/moreau_jean.hpp"

namespace {

using namespace nscd;
namespace fs = std::filesystem;

/// One scene: its run (the settings of side_by_side.sh), LMGC90's end figures and the tolerances.
struct DatboxScene {
  const char* name;
  double dt;
  int steps;
  int contacts, active;         ///< LMGC90: Vloc_Rloc records, those with rln ≠ 0
  double coordination, height;  ///< LMGC90: 2 × grain pairs with a force / grains; mean height of the grains
  double max_overlap;           ///< LMGC90: the largest −gapTT of its records (m)
  double coordination_tol;      ///< relative
};

// Tolerances, from docs/benchmarks.md §9 (what nscd gave against LMGC90): contacts within 3 %
// (measured: 2.0 % at most), those with a force within 4 % (3.4 %), the mean grain height within
// 0.5 % (0.24 %), the coordination within 2 % (0.5 %) — except the wall's, whose joints between
// bricks of one course carry statically indeterminate forces (13.5 % fewer pairs with a force in
// nscd, the same contacts) — and no overlap larger than LMGC90's.
const DatboxScene kScenes[] = {
    {"disks_jcbox", 5e-3, 400, 244, 225, 3.45, 6.04263, 9.28546e-06, 0.02},
    {"polygons_jcbox", 5e-3, 400, 248, 199, 3.24444, 3.10165, 0.0092703, 0.02},
    {"disk_drum", 1e-2, 500, 101, 87, 2.83019, 4.47625, 0.00211655, 0.02},
    {"block_wall", 1e-3, 300, 222, 177, 4.36364, 0.20227, 2.52477e-06, 0.15},
};

// ctest names a parameterised test by its parameter: the scene's name, not its bytes
void PrintTo(const DatboxScene& s, std::ostream* os) { *os << s.name; }

class LmgcScene : public ::testing::TestWithParam<DatboxScene> {};

TEST_P(LmgcScene, EndsAsLmgc90Ends) {
  const DatboxScene& s = GetParam();
  Datbox d = read_datbox(fs::path(NSCD_TEST_DATA_DIR) / "datbox" / s.name);
  Registry& reg = d.reg;
  reg.params.dt = s.dt;
  reg.params.theta = 0.5;
  StepperOptions o;  // datbox_run's defaults: QM/16, 1.666e-4, 10 sweeps a check, at most 1000
  MoreauJean mj(reg, o);
  for (int i = 0; i < s.steps; ++i) mj.step();

  std::set<std::uint32_t> grains;  // bodies with a DISKx or a POLYG
  for (BodyId b : reg.diskx.body) grains.insert(b.index());
  for (BodyId b : reg.polyg.body) grains.insert(b.index());
  double height = 0.0;
  for (std::uint32_t g : grains) height += reg.bodies.y[g];
  height /= static_cast<double>(grains.size());

  const std::vector<DatboxContact> cs = datbox_contacts(reg);
  int active = 0;
  double max_overlap = 0.0;
  std::set<std::pair<int, int>> pairs;
  for (const DatboxContact& c : cs) {
    max_overlap = std::max(max_overlap, -c.gap);
    if (c.rln == 0.0) continue;
    ++active;
    const int a = datbox_number(reg, c.cd).first - 1, b = datbox_number(reg, c.an).first - 1;
    if (grains.count(static_cast<std::uint32_t>(a)) && grains.count(static_cast<std::uint32_t>(b))) pairs.insert(std::minmax(a, b));
  }
  const double coordination = 2.0 * static_cast<double>(pairs.size()) / static_cast<double>(grains.size());

  EXPECT_NEAR(static_cast<double>(cs.size()), s.contacts, 0.03 * s.contacts) << s.name;
  EXPECT_NEAR(active, s.active, 0.04 * s.active) << s.name;
  EXPECT_NEAR(coordination, s.coordination, s.coordination_tol * s.coordination) << s.name;
  EXPECT_NEAR(height, s.height, 0.005 * s.height) << s.name;
  EXPECT_LE(max_overlap, s.max_overlap) << s.name;
}

INSTANTIATE_TEST_SUITE_P(Datbox, LmgcScene, ::testing::ValuesIn(kScenes),
                         [](const ::testing::TestParamInfo<DatboxScene>& i) { return std::string(i.param.name); });

}  // namespace
