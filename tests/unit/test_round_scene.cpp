// tests/unit/test_round_scene.cpp — the round contactors in a scene (issue #12): the one
// contact table (roles and ContactorIds per interaction kind), the big walls, the checkpoint
// (version 4 round section, a polygon scene still writes version 3) and the VTK bodies.
#include <gtest/gtest.h>

#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataReader.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <string_view>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/contactors/round_shapes.hpp"
#include "nscd/core/error.hpp"
#include "nscd/interactions/interaction_table.hpp"
#include "nscd/interactions/plplx.hpp"
#include "nscd/interactions/round_detection.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/io/vtk_writer.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "temp_path.hpp"

namespace nscd {
namespace {

namespace fs = std::filesystem;

constexpr std::uint8_t kPL = 0, kDK = 1, kJC = 2, kKD = 3;

// A small scene with every interaction kind: a JONCx floor, a square on it (PLJCx), a disk on
// the square (DKPLx), a disk on the floor (DKJCx) touching another disk (DKDKx), and a disk
// inside a fixed ring (DKKDx) off to the side.
struct RoundScene {
  Registry reg;
  BodyId floor, square, disk_on_square, disk1, disk2, drum, disk_in_drum;
};
RoundScene make_scene() {
  RoundScene s;
  const MaterialId m = add_material(s.reg, "stone", 2500.0);
  set_default_contact_law(s.reg, LawSpec{LawKind::IQS_CLB, 0.4});
  s.floor = add_jonc_body(s.reg, 2.0, 0.05, m, {0.0, -0.05}, 0.0, "floor");
  fix_body(s.reg, s.floor);
  s.square = add_polygon_body(s.reg, rectangle(0.2, 0.2), m, {-0.5, 0.1}, 0.0, "square");
  s.disk_on_square = add_disk_body(s.reg, 0.05, m, {-0.5, 0.25}, "on square");
  s.disk1 = add_disk_body(s.reg, 0.05, m, {0.5, 0.05}, "d1");
  s.disk2 = add_disk_body(s.reg, 0.05, m, {0.6, 0.05}, "d2");
  RigidBodySpec drum;
  drum.name = "drum";
  drum.material = m;
  drum.position = {5.0, 0.0};
  drum.mass = 10.0;
  drum.inertia = 1.0;
  s.drum = add_body(s.reg, drum);
  attach_xksid(s.reg, s.drum, {0.0, 0.0}, 0.5);
  fix_body(s.reg, s.drum);
  s.disk_in_drum = add_disk_body(s.reg, 0.05, m, {5.0, -0.45}, "in drum");
  return s;
}

TEST(RoundScene, OneContactTableHoldsEveryInteractionKindWithLmgcRoles) {
  RoundScene s = make_scene();
  PlplxDetector det;
  classify_big_polygons(s.reg, det.big_ratio);
  detect_plplx(s.reg, det);
  const ContactTable& c = s.reg.contacts;
  std::multiset<std::pair<int, int>> kinds;  // (candidate kind, antagonist kind) per point
  for (std::size_t k = 0; k < c.size(); ++k) {
    kinds.insert({contactor_kind_bits(c.candidate[k]), contactor_kind_bits(c.antagonist[k])});
    EXPECT_NEAR(c.gap[k], 0.0, 1e-12) << k;  // everything touches exactly
    EXPECT_EQ(c.cd_body[k], body_of(s.reg, c.candidate[k]));
    EXPECT_EQ(c.an_body[k], body_of(s.reg, c.antagonist[k]));
  }
  EXPECT_EQ(kinds.count({kPL, kJC}), 2u);  // the square's bottom edge on the floor: PLJCx, two points
  EXPECT_EQ(kinds.count({kDK, kPL}), 1u);  // DKPLx
  EXPECT_EQ(kinds.count({kDK, kJC}), 2u);  // DKJCx, both disks on the floor
  EXPECT_EQ(kinds.count({kDK, kDK}), 1u);  // DKDKx
  EXPECT_EQ(kinds.count({kDK, kKD}), 1u);  // DKKDx
  EXPECT_EQ(c.size(), 7u);
  std::multiset<std::string_view> names;  // the same, by the interaction table's names
  for (std::size_t k = 0; k < c.size(); ++k) names.insert(name_of(interaction_of(c.candidate[k], c.antagonist[k])));
  EXPECT_EQ(names, (std::multiset<std::string_view>{"PLJCx", "PLJCx", "DKPLx", "DKJCx", "DKJCx", "DKDKx", "DKKDx"}));
  // the floor and the ring are big (out of the grid): the drum's box covers far more than a grain
  EXPECT_EQ(det.is_big.size(), s.reg.polyg.size() + s.reg.diskx.size() + s.reg.joncx.size() + s.reg.xksid.size());
  EXPECT_EQ(det.is_big.back(), 1);
}

TEST(RoundScene, APolygonSceneKeepsItsIdsAndCheckpointVersion) {
  Registry reg;
  const MaterialId m = add_material(reg, "stone", 2500.0);
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.4});
  const BodyId floor = add_polygon_body(reg, rectangle(4.0, 0.2), m, {0.0, -0.1});
  fix_body(reg, floor);
  add_polygon_body(reg, rectangle(0.2, 0.2), m, {0.0, 0.1});
  PlplxDetector det;
  classify_big_polygons(reg, det.big_ratio);
  detect_plplx(reg, det);
  ASSERT_EQ(reg.contacts.size(), 2u);
  EXPECT_EQ(reg.contacts.candidate[0].value, 1u);  // a POLYG's ContactorId is its index
  EXPECT_EQ(reg.contacts.antagonist[0].value, 0u);
  const fs::path f = nscd::testing_support::unique_temp_path("round_scene_poly").concat(".nscd");
  save_checkpoint(f, reg);
  std::ifstream in(f);
  std::string magic, version;
  in >> magic >> version;
  EXPECT_EQ(version, "3");
  fs::remove(f);
}

TEST(RoundScene, CheckpointRoundTripAndResumeBitForBit) {
  RoundScene a = make_scene();
  MoreauJean mj(a.reg);
  for (int n = 0; n < 20; ++n) mj.step();
  const fs::path f = nscd::testing_support::unique_temp_path("round_scene").concat(".nscd");
  save_checkpoint(f, a.reg, mj.warm_start_memory());
  {
    std::ifstream in(f);
    std::string magic, version;
    in >> magic >> version;
    EXPECT_EQ(version, "4");
  }
  Checkpoint cp = load_checkpoint(f);
  fs::remove(f);
  ASSERT_EQ(cp.reg.diskx.size(), a.reg.diskx.size());
  ASSERT_EQ(cp.reg.joncx.size(), 1u);
  ASSERT_EQ(cp.reg.xksid.size(), 1u);
  EXPECT_EQ(cp.reg.joncx.axis[0], a.reg.joncx.axis[0]);
  EXPECT_EQ(cp.reg.diskx.radius, a.reg.diskx.radius);
  MoreauJean resumed(cp.reg);
  resumed.set_warm_start_memory(cp.warm_start);
  for (int n = 0; n < 30; ++n) {
    mj.step();
    resumed.step();
  }
  for (std::size_t i = 0; i < a.reg.bodies.size(); ++i) {
    EXPECT_EQ(a.reg.bodies.x[i], cp.reg.bodies.x[i]) << i;
    EXPECT_EQ(a.reg.bodies.y[i], cp.reg.bodies.y[i]) << i;
    EXPECT_EQ(a.reg.bodies.spin[i], cp.reg.bodies.spin[i]) << i;
  }
}

TEST(RoundScene, AWarmStartKeyNamingAMissingDiskIsRefused) {
  RoundScene a = make_scene();
  MoreauJean mj(a.reg);
  mj.step();
  ASSERT_FALSE(mj.warm_start_memory().empty());
  const fs::path f = nscd::testing_support::unique_temp_path("round_scene_warm").concat(".nscd");
  save_checkpoint(f, a.reg, mj.warm_start_memory());
  std::ifstream in(f);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  fs::remove(f);
  // the first warm-start record's candidate becomes DISKx 99 (kind 1 in the top bits)
  const std::size_t w = text.find("\nw ");
  ASSERT_NE(w, std::string::npos);
  const std::size_t key_end = text.find(' ', w + 3);
  const std::uint64_t key = (std::uint64_t(make_contactor(1, 99).value) << 32) | 0u;
  text = text.substr(0, w + 3) + std::to_string(key) + text.substr(key_end);
  try {
    load_checkpoint_text(text, "edited");
    ADD_FAILURE() << "accepted a key naming DISKx 99";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("4 DISKx"), std::string::npos) << e.what();
  }
}

/// Writes one VTK frame of `reg` into a fresh `dir` and reads back its file `name` (the reader
/// owns the data).
vtkSmartPointer<vtkXMLPolyDataReader> write_and_read_frame(const Registry& reg, const fs::path& dir, const std::string& name) {
  fs::remove_all(dir);
  {
    VtkWriter w(dir);
    w.write_frame(reg);
  }
  auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
  r->SetFileName((dir / name).string().c_str());
  r->Update();
  return r;
}

TEST(RoundScene, VtkDrawsDisksJoncsAndRingsWithTheirKind) {
  RoundScene s = make_scene();
  const fs::path dir = nscd::testing_support::unique_temp_path("round_scene_vtk");
  const auto r = write_and_read_frame(s.reg, dir, "bodies_000000.vtp");
  vtkPolyData* pd = r->GetOutput();
  ASSERT_EQ(pd->GetNumberOfCells(), 6 + 64);  // square, 4 disks, the floor, the ring's 64 quads
  vtkDataArray* kind = pd->GetCellData()->GetArray("contactor_kind");
  ASSERT_NE(kind, nullptr);
  EXPECT_EQ(kind->GetTuple1(0), 0.0);  // polygons first, then disks, then joncs
  EXPECT_EQ(kind->GetTuple1(1), 1.0);
  EXPECT_EQ(kind->GetTuple1(5), 2.0);
  for (vtkIdType c = 6; c < 70; ++c) EXPECT_EQ(kind->GetTuple1(c), 3.0);
  // the ring's band: every quad has two points on the hole (r = 0.5 about the drum's centre at
  // (5, 0)) and two outside it, none inside
  for (vtkIdType c = 6; c < 70; ++c) {
    vtkCell* q = pd->GetCell(c);
    ASSERT_EQ(q->GetNumberOfPoints(), 4);
    int on_hole = 0;
    for (vtkIdType k = 0; k < 4; ++k) {
      double pt[3];
      pd->GetPoint(q->GetPointId(k), pt);
      const double r = std::hypot(pt[0] - 5.0, pt[1]);
      EXPECT_GE(r, 0.5 - 1e-12);
      if (std::abs(r - 0.5) < 1e-12) ++on_hole;
    }
    EXPECT_EQ(on_hole, 2);
  }
  double p[3];
  // a disk's 32 points lie on its circle
  const vtkIdType first = 4;  // the square's 4 points come first
  for (vtkIdType k = 0; k < 32; ++k) {
    pd->GetPoint(first + k, p);
    EXPECT_NEAR(std::hypot(p[0] + 0.5, p[1] - 0.25), 0.05, 1e-12);
  }
  fs::remove_all(dir);
}

TEST(RoundScene, VtkContactsCarryTheirInteraction) {
  RoundScene s = make_scene();
  PlplxDetector det;
  classify_big_polygons(s.reg, det.big_ratio);
  detect_plplx(s.reg, det);
  const fs::path dir = nscd::testing_support::unique_temp_path("round_scene_vtk_contacts");
  const auto r = write_and_read_frame(s.reg, dir, "contacts_000000.vtp");
  vtkPolyData* pd = r->GetOutput();
  ASSERT_EQ(pd->GetNumberOfCells(), static_cast<vtkIdType>(s.reg.contacts.size()));
  vtkDataArray* inter = pd->GetCellData()->GetArray("interaction");
  ASSERT_NE(inter, nullptr);
  auto* names = vtkStringArray::SafeDownCast(pd->GetFieldData()->GetAbstractArray("interaction_names"));
  ASSERT_NE(names, nullptr);
  std::multiset<std::string> got;
  for (vtkIdType k = 0; k < pd->GetNumberOfCells(); ++k) {
    const auto i = static_cast<vtkIdType>(inter->GetTuple1(k));
    ASSERT_GE(i, 0);
    ASSERT_LT(i, names->GetNumberOfValues());
    got.insert(names->GetValue(i));
  }
  EXPECT_EQ(got, (std::multiset<std::string>{"PLJCx", "PLJCx", "DKPLx", "DKJCx", "DKJCx", "DKDKx", "DKKDx"}));
  fs::remove_all(dir);
}

TEST(RoundScene, AttachRefusesBadGeometry) {
  Registry reg;
  const MaterialId m = add_material(reg, "stone", 2500.0);
  const BodyId b = add_disk_body(reg, 0.1, m, {0, 0});
  EXPECT_THROW(attach_diskx(reg, b, {0, 0}, 0.0), Error);
  EXPECT_THROW(attach_diskx(reg, BodyId(7), {0, 0}, 0.1), Error);
  EXPECT_THROW(attach_joncx(reg, b, {0, 0}, {0, 0}, 1.0, 0.1), Error);
  EXPECT_THROW(attach_joncx(reg, b, {0, 0}, {1, 0}, -1.0, 0.1), Error);
  EXPECT_THROW(attach_xksid(reg, b, {NAN, 0}, 1.0), Error);
  EXPECT_THROW(add_disk_body(reg, 0.1, MaterialId(3), {0, 0}), Error);
  try {
    attach_diskx(reg, b, {0, 0}, -2.0);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("DISKx of body 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace nscd
