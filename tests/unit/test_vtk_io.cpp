// tests/unit/test_vtk_io.cpp — io/vtk_writer: writes a small scene, reads the .vtp files back
// with VTK's own reader and parses the .pvd collections; the springs file of a scene with
// PTPT2 links. Resuming the collections of a run restarted from a checkpoint:
// test_vtk_io_resume.cpp; the helpers both use: vtk_io_fixtures.hpp.
//
// VtkScene (SI units, material "rock" = 0, "steel" = 1):
//   body 0  floor     steel  4 × 0.2 rectangle at (0, -0.1), fixed      -> top edge y = 0
//   body 1  box A     rock   0.2 × 0.2 at (-0.3, 0.1), v = (0.3, -0.1), ω = 0.5  -> rests on the floor, gap 0
//           (not at x = 0: see the note in build_scene)
//   body 2  box B     rock   0.2 × 0.2 at (0.5, 0.098)                  -> 2 mm into the floor, top y = 0.198
//   body 3  pentagon  rock   regular, circumscribed diameter 0.2, first vertex at shape angle 0,
//                            created at (0.45, 0.35), angle -π/2 - 0.2, then moved to (0.5, 0.297),
//                            angle -π/2: vertex 0 points straight down to (0.5, 0.197), 1 mm into box B.
// Expected contacts (5): floor–A edge–edge (2 points, gap 0), floor–B edge–edge (2 points, gap −0.002),
// B–pentagon vertex–edge (1 point, gap −0.001). The floor is big, so it is the antagonist of its pairs.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <vtkDataArray.h>
#include <vtkPolyData.h>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "nscd/interactions/plplx.hpp"
#include "nscd/io/vtk_writer.hpp"
#include "vtk_io_fixtures.hpp"

namespace fs = std::filesystem;
using namespace nscd;
using namespace nscd::vtk_io_fixtures;

namespace {

struct VtkScene {
  Registry reg;
  PlplxDetector det;
};

void build_scene(VtkScene& s) {
  Registry& reg = s.reg;
  const MaterialId rock = add_material(reg, "rock", 2000.0);
  const MaterialId steel = add_material(reg, "steel", 7800.0);
  const BodyId floor = add_polygon_body(reg, rectangle(4.0, 0.2), steel, {0.0, -0.1}, 0.0, "floor");
  fix_body(reg, floor);
  // Box A is off the floor's axis x = 0 on purpose: a box centred exactly above the floor's
  // centre is missed by the narrow phase (the shadow-overlap walk starts on an edge normal whose
  // neighbouring breakpoints are 90° away, and gives up); reported separately.
  const BodyId a = add_polygon_body(reg, rectangle(0.2, 0.2), rock, {-0.3, 0.1}, 0.0, "A");
  add_polygon_body(reg, rectangle(0.2, 0.2), rock, {0.5, 0.098}, 0.0, "B");
  const BodyId p = add_polygon_body(reg, regular_polygon(5, 0.2), rock, {0.45, 0.35}, -0.5 * kPi - 0.2, "penta");
  reg.bodies.vx[a.index()] = 0.3;
  reg.bodies.vy[a.index()] = -0.1;
  reg.bodies.spin[a.index()] = 0.5;
  // move the pentagon: displacement (0.05, -0.053), rotation +0.2
  reg.bodies.x[p.index()] = 0.5;
  reg.bodies.y[p.index()] = 0.297;
  reg.bodies.angle[p.index()] = -0.5 * kPi;
  reg.bodies.vx[p.index()] = -1.5;
  reg.bodies.vy[p.index()] = 2.0;
  classify_big_polygons(reg, s.det.big_ratio);
  detect_plplx(reg, s.det);
  // forces by hand: contact k gets rn = 10 (k+1), rt = -2 (k+1), status k % 4
  for (std::size_t k = 0; k < reg.contacts.size(); ++k) {
    reg.contacts.rn[k] = 10.0 * static_cast<double>(k + 1);
    reg.contacts.rt[k] = -2.0 * static_cast<double>(k + 1);
    reg.contacts.status[k] = static_cast<ContactStatus>(k % 4);
  }
}

}  // namespace

TEST_F(VtkIo, BodiesFileHoldsWorldPolygonsAndBodyArrays) {
  VtkScene s;
  build_scene(s);
  s.reg.time = 0.1;
  VtkWriter w(root_ / "out" / "deep");  // parents are created
  EXPECT_TRUE(fs::is_directory(root_ / "out" / "deep"));
  w.write_frame(s.reg);
  EXPECT_EQ(w.frames(), 1);

  auto pd = read_vtp(root_ / "out" / "deep" / "bodies_000000.vtp");
  ASSERT_EQ(pd->GetNumberOfCells(), 4);  // one polygon per POLYG
  EXPECT_EQ(pd->GetNumberOfPoints(), 4 + 4 + 4 + 5);

  // Pentagon (cell 3): vertex k at centre + 0.1 (cos θk, sin θk), θk = -π/2 + 2πk/5.
  // k = 0: (0.5, 0.297 - 0.1) = (0.5, 0.197); k = 1: θ = -18°, (0.5 + 0.1 cos 18°, 0.297 - 0.1 sin 18°)
  //      = (0.595105651629515, 0.266098300562505).
  EXPECT_NEAR(cell_point(pd, 3, 0).x, 0.5, 1e-12);
  EXPECT_NEAR(cell_point(pd, 3, 0).y, 0.197, 1e-12);
  EXPECT_NEAR(cell_point(pd, 3, 1).x, 0.595105651629515, 1e-12);
  EXPECT_NEAR(cell_point(pd, 3, 1).y, 0.266098300562505, 1e-12);
  // Floor (cell 0): vertex 2 is the top-right corner (2, 0).
  EXPECT_NEAR(cell_point(pd, 0, 2).x, 2.0, 1e-12);
  EXPECT_NEAR(cell_point(pd, 0, 2).y, 0.0, 1e-12);

  vtkDataArray* body_id = cell_array(pd, "body_id", 1);
  vtkDataArray* polyg_id = cell_array(pd, "polyg_id", 1);
  vtkDataArray* material = cell_array(pd, "material", 1);
  vtkDataArray* velocity = cell_array(pd, "velocity", 3);
  vtkDataArray* spin = cell_array(pd, "spin", 1);
  vtkDataArray* disp = cell_array(pd, "displacement", 3);
  vtkDataArray* rotation = cell_array(pd, "rotation", 1);
  vtkDataArray* fixed = cell_array(pd, "fixed", 1);
  ASSERT_TRUE(body_id && polyg_id && material && velocity && spin && disp && rotation && fixed);
  EXPECT_EQ(body_id->GetDataType(), VTK_INT);
  EXPECT_EQ(velocity->GetDataType(), VTK_DOUBLE);
  for (int c = 0; c < 4; ++c) {
    EXPECT_EQ(body_id->GetComponent(c, 0), c);  // one polygon per body, in order
    EXPECT_EQ(polyg_id->GetComponent(c, 0), c);
    EXPECT_EQ(material->GetComponent(c, 0), c == 0 ? 1 : 0);
    EXPECT_EQ(fixed->GetComponent(c, 0), c == 0 ? 1 : 0);
  }
  EXPECT_EQ(velocity->GetComponent(1, 0), 0.3);
  EXPECT_EQ(velocity->GetComponent(1, 1), -0.1);
  EXPECT_EQ(velocity->GetComponent(1, 2), 0.0);
  EXPECT_EQ(spin->GetComponent(1, 0), 0.5);
  EXPECT_EQ(velocity->GetComponent(3, 0), -1.5);
  EXPECT_EQ(velocity->GetComponent(3, 1), 2.0);
  // displacement of the pentagon: (0.5 - 0.45, 0.297 - 0.35) = (0.05, -0.053); rotation 0.2
  EXPECT_NEAR(disp->GetComponent(3, 0), 0.05, 1e-15);
  EXPECT_NEAR(disp->GetComponent(3, 1), -0.053, 1e-15);
  EXPECT_EQ(disp->GetComponent(3, 2), 0.0);
  EXPECT_NEAR(rotation->GetComponent(3, 0), 0.2, 1e-15);
  // box A did not move
  EXPECT_EQ(disp->GetComponent(1, 0), 0.0);
  EXPECT_EQ(disp->GetComponent(1, 1), 0.0);
  EXPECT_EQ(rotation->GetComponent(1, 0), 0.0);
}

TEST_F(VtkIo, ContactsFileHoldsSegmentsAndForces) {
  VtkScene s;
  build_scene(s);
  const ContactTable& c = s.reg.contacts;
  ASSERT_EQ(c.size(), 5u);  // see the scene description at the top
  VtkWriter w(root_, "run1_");
  w.write_frame(s.reg);

  auto pd = read_vtp(root_ / "run1_contacts_000000.vtp");
  ASSERT_EQ(pd->GetNumberOfCells(), 5);
  vtkDataArray* normal = cell_array(pd, "normal", 3);
  vtkDataArray* rn = cell_array(pd, "rn", 1);
  vtkDataArray* rt = cell_array(pd, "rt", 1);
  vtkDataArray* force = cell_array(pd, "force", 3);
  vtkDataArray* gap = cell_array(pd, "gap", 1);
  vtkDataArray* status = cell_array(pd, "status", 1);
  vtkDataArray* point = cell_array(pd, "point", 3);
  vtkDataArray* cd = cell_array(pd, "candidate_body", 1);
  vtkDataArray* an = cell_array(pd, "antagonist_body", 1);
  ASSERT_TRUE(normal && rn && rt && force && gap && status && point && cd && an);
  EXPECT_EQ(status->GetDataType(), VTK_INT);

  int seen_floor_a = 0, seen_floor_b = 0, seen_b_penta = 0;
  for (vtkIdType k = 0; k < 5; ++k) {
    const auto i = static_cast<std::size_t>(k);
    EXPECT_EQ(cd->GetComponent(k, 0), c.cd_body[i].index());
    EXPECT_EQ(an->GetComponent(k, 0), c.an_body[i].index());
    EXPECT_EQ(status->GetComponent(k, 0), static_cast<double>(k % 4));
    // every normal here is vertical: n = (0, 1), t = perp(n) = (-1, 0)
    EXPECT_NEAR(normal->GetComponent(k, 0), 0.0, 1e-12);
    EXPECT_NEAR(normal->GetComponent(k, 1), 1.0, 1e-12);
    EXPECT_EQ(normal->GetComponent(k, 2), 0.0);
    // rn = 10 (k+1), rt = -2 (k+1): force = rn n + rt t = (-rt, rn) = (2 (k+1), 10 (k+1))
    EXPECT_EQ(rn->GetComponent(k, 0), 10.0 * static_cast<double>(k + 1));
    EXPECT_EQ(rt->GetComponent(k, 0), -2.0 * static_cast<double>(k + 1));
    EXPECT_NEAR(force->GetComponent(k, 0), 2.0 * static_cast<double>(k + 1), 1e-9);
    EXPECT_NEAR(force->GetComponent(k, 1), 10.0 * static_cast<double>(k + 1), 1e-9);
    EXPECT_EQ(force->GetComponent(k, 2), 0.0);
    EXPECT_EQ(gap->GetComponent(k, 0), c.gap[i]);
    EXPECT_EQ(point->GetComponent(k, 0), c.point[i].x);
    EXPECT_EQ(point->GetComponent(k, 1), c.point[i].y);

    const Vec2 from = cell_point(pd, k, 0), to = cell_point(pd, k, 1);
    const int bc = static_cast<int>(cd->GetComponent(k, 0)), ba = static_cast<int>(an->GetComponent(k, 0));
    if (ba == 0 && bc == 1) {
      // floor–A: gap 0, segment from A's centre (-0.3, 0.1) to the contact point (the floor is big)
      ++seen_floor_a;
      EXPECT_NEAR(gap->GetComponent(k, 0), 0.0, 1e-12);
      EXPECT_NEAR(from.x, -0.3, 1e-12);
      EXPECT_NEAR(from.y, 0.1, 1e-12);
      EXPECT_EQ(to.x, c.point[i].x);
      EXPECT_EQ(to.y, c.point[i].y);
      EXPECT_NEAR(std::abs(to.x + 0.3), 0.1, 1e-9);  // extremities of A's bottom edge, x = -0.4, -0.2
      EXPECT_NEAR(to.y, 0.0, 1e-9);
    } else if (ba == 0 && bc == 2) {
      // floor–B: B's bottom at y = -0.002, floor top at 0: gap -0.002, point halfway at y = -0.001
      ++seen_floor_b;
      EXPECT_NEAR(gap->GetComponent(k, 0), -0.002, 1e-12);
      EXPECT_NEAR(from.x, 0.5, 1e-12);
      EXPECT_NEAR(from.y, 0.098, 1e-12);
      EXPECT_NEAR(to.y, -0.001, 1e-9);
      EXPECT_NEAR(std::abs(to.x - 0.5), 0.1, 1e-9);
    } else if (ba == 2 && bc == 3) {
      // B–pentagon: vertex at y = 0.197 vs B's top 0.198: gap -0.001; segment between the
      // centres of mass, pentagon (0.5, 0.297) to B (0.5, 0.098)
      ++seen_b_penta;
      EXPECT_NEAR(gap->GetComponent(k, 0), -0.001, 1e-12);
      EXPECT_NEAR(from.x, 0.5, 1e-12);
      EXPECT_NEAR(from.y, 0.297, 1e-12);
      EXPECT_NEAR(to.x, 0.5, 1e-12);
      EXPECT_NEAR(to.y, 0.098, 1e-12);
    } else {
      ADD_FAILURE() << "unexpected contact candidate " << bc << " antagonist " << ba;
    }
  }
  EXPECT_EQ(seen_floor_a, 2);
  EXPECT_EQ(seen_floor_b, 2);
  EXPECT_EQ(seen_b_penta, 1);
}

TEST_F(VtkIo, CollectionsListEveryFrameWithExactTimes) {
  VtkScene s;
  build_scene(s);
  VtkWriter w(root_);
  EXPECT_EQ(w.directory(), root_);
  // 0.1 and 0.1 + 2e-4 are not exact in binary: only 17 significant digits bring them back bitwise
  const double t0 = 0.1, t1 = 0.1 + 2e-4;
  s.reg.time = t0;
  w.write_frame(s.reg);
  // The collection is valid after the first frame already (a killed run leaves it readable).
  ASSERT_EQ(read_pvd(root_ / "bodies.pvd").size(), 1u);
  s.reg.time = t1;
  s.reg.bodies.vx[1] = 0.7;
  w.write_frame(s.reg);
  EXPECT_EQ(w.frames(), 2);

  for (const char* kind : {"bodies", "contacts"}) {
    const auto e = read_pvd(root_ / (std::string(kind) + ".pvd"));
    ASSERT_EQ(e.size(), 2u) << kind;
    EXPECT_EQ(e[0].time, t0) << kind;  // exact equality, not near
    EXPECT_EQ(e[1].time, t1) << kind;
    EXPECT_EQ(e[0].file, std::string(kind) + "_000000.vtp");
    EXPECT_EQ(e[1].file, std::string(kind) + "_000001.vtp");
    EXPECT_TRUE(fs::exists(root_ / e[1].file));
  }
  EXPECT_FALSE(fs::exists(root_ / "bodies.pvd.tmp"));  // temporary files are renamed away
  // the second frame holds the second state
  auto pd = read_vtp(root_ / "bodies_000001.vtp");
  vtkDataArray* v = cell_array(pd, "velocity", 3);
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(v->GetComponent(1, 0), 0.7);
}

TEST_F(VtkIo, EmptyContactTableGivesAValidFile) {
  Registry reg;
  const MaterialId rock = add_material(reg, "rock", 2000.0);
  add_polygon_body(reg, rectangle(1.0, 1.0), rock, {0.0, 0.0});
  ASSERT_TRUE(reg.contacts.empty());
  VtkWriter w(root_);
  w.write_frame(reg);
  auto pd = read_vtp(root_ / "contacts_000000.vtp");
  EXPECT_EQ(pd->GetNumberOfCells(), 0);
  EXPECT_EQ(pd->GetNumberOfPoints(), 0);
  // the arrays are still declared (0 tuples), so a pipeline set up on frame 0 keeps working
  for (const char* name : {"normal", "force", "point"}) EXPECT_NE(cell_array(pd, name, 3), nullptr) << name;
  for (const char* name : {"rn", "rt", "gap", "status", "candidate_body", "antagonist_body"})
    EXPECT_NE(cell_array(pd, name, 1), nullptr) << name;
  EXPECT_EQ(read_pvd(root_ / "contacts.pvd").size(), 1u);
  EXPECT_EQ(read_vtp(root_ / "bodies_000000.vtp")->GetNumberOfCells(), 1);
}

TEST_F(VtkIo, FrameOptionsSelectTheKinds) {
  VtkScene s;
  build_scene(s);
  VtkWriter w(root_);
  w.write_frame(s.reg, {.bodies = true, .contacts = false});
  w.write_frame(s.reg, {.bodies = false, .contacts = true});
  EXPECT_TRUE(fs::exists(root_ / "bodies_000000.vtp"));
  EXPECT_FALSE(fs::exists(root_ / "contacts_000000.vtp"));
  EXPECT_FALSE(fs::exists(root_ / "bodies_000001.vtp"));
  EXPECT_TRUE(fs::exists(root_ / "contacts_000001.vtp"));
  EXPECT_EQ(read_pvd(root_ / "bodies.pvd").size(), 1u);
  EXPECT_EQ(read_pvd(root_ / "contacts.pvd").size(), 1u);
}

TEST_F(VtkIo, UnwritableDirectoryThrows) {
  fs::create_directories(root_);
  const fs::path file = root_ / "plain_file";
  std::ofstream(file) << "not a directory";
  // a directory cannot be created under a regular file, nor can the file itself be the directory
  EXPECT_THROW(VtkWriter(file / "out"), Error);
  EXPECT_THROW(VtkWriter{file}, Error);
  try {
    VtkWriter w(file / "out");
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("plain_file"), std::string::npos) << e.what();
  }
  // the directory disappears after construction: writing the frame throws, naming the file
  Registry reg;
  const MaterialId rock = add_material(reg, "rock", 2000.0);
  add_polygon_body(reg, rectangle(1.0, 1.0), rock, {0.0, 0.0});
  VtkWriter w(root_ / "gone");
  fs::remove_all(root_ / "gone");
  try {
    w.write_frame(reg);
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bodies_000000.vtp"), std::string::npos) << e.what();
  }
}

TEST_F(VtkIo, SpringsFileHoldsOneSegmentPerLink) {
  Registry reg;
  build_spring_scene(reg);
  ASSERT_EQ(reg.links.size(), 2u);
  EXPECT_EQ(reg.links.law[1].L0, 0.4);      // taken from the distance at creation
  EXPECT_NEAR(reg.links.length[0], 0.4, 1e-15);  // stale: the state at creation
  reg.time = 0.25;
  VtkWriter w(root_, "s_");
  w.write_frame(reg);
  auto pd = read_vtp(root_ / "s_springs_000000.vtp");
  ASSERT_EQ(pd->GetNumberOfCells(), 2);
  EXPECT_EQ(pd->GetNumberOfPoints(), 4);

  // Block corners in the block frame: (-0.2, 0.4) - (0, 0.5) = (-0.2, -0.1) and (0.2, -0.1).
  // R(π/2)(x, y) = (-y, x): (0.1, -0.2) and (0.1, 0.2); plus the centre (0.1, 0.6):
  // candidate points (0.2, 0.4) and (0.2, 0.8). The antagonist points stay at (∓0.2, 0).
  // Each segment goes from the antagonist point (cell point 0) to the candidate point (1).
  const Vec2 a0 = cell_point(pd, 0, 0), c0 = cell_point(pd, 0, 1);
  const Vec2 a1 = cell_point(pd, 1, 0), c1 = cell_point(pd, 1, 1);
  EXPECT_NEAR(a0.x, -0.2, 1e-12);
  EXPECT_NEAR(a0.y, 0.0, 1e-12);
  EXPECT_NEAR(c0.x, 0.2, 1e-12);
  EXPECT_NEAR(c0.y, 0.4, 1e-12);
  EXPECT_NEAR(a1.x, 0.2, 1e-12);
  EXPECT_NEAR(a1.y, 0.0, 1e-12);
  EXPECT_NEAR(c1.x, 0.2, 1e-12);
  EXPECT_NEAR(c1.y, 0.8, 1e-12);

  vtkDataArray* rn = cell_array(pd, "rn", 1);
  vtkDataArray* length = cell_array(pd, "length", 1);
  vtkDataArray* strain = cell_array(pd, "strain", 1);
  vtkDataArray* k = cell_array(pd, "k", 1);
  vtkDataArray* nu = cell_array(pd, "nu", 1);
  vtkDataArray* id = cell_array(pd, "link_id", 1);
  ASSERT_TRUE(rn && length && strain && k && nu && id);
  EXPECT_EQ(id->GetDataType(), VTK_INT);
  EXPECT_EQ(strain->GetDataType(), VTK_DOUBLE);
  EXPECT_EQ(id->GetComponent(0, 0), 0.0);
  EXPECT_EQ(id->GetComponent(1, 0), 1.0);
  // link 0: L = |(0.4, 0.4)| = 0.4 √2 = 0.565685424949238, strain = L / 0.3 − 1 − 0.1 = 0.785618083164127,
  //         rn = −2e6 (L − 0.3 · 1.1) = −471370.849898476 (as set)
  EXPECT_NEAR(length->GetComponent(0, 0), 0.565685424949238, 1e-12);
  EXPECT_NEAR(strain->GetComponent(0, 0), 0.785618083164127, 1e-12);
  EXPECT_EQ(rn->GetComponent(0, 0), -471370.849898476);
  EXPECT_EQ(k->GetComponent(0, 0), 2e6);
  EXPECT_EQ(nu->GetComponent(0, 0), 3e3);
  // link 1: L = 0.8, strain = 0.8 / 0.4 − 1 − 0 = 1, rn = −1e6 (0.8 − 0.4) = −4e5
  EXPECT_NEAR(length->GetComponent(1, 0), 0.8, 1e-12);
  EXPECT_NEAR(strain->GetComponent(1, 0), 1.0, 1e-12);
  EXPECT_EQ(rn->GetComponent(1, 0), -4.0e5);
  EXPECT_EQ(k->GetComponent(1, 0), 1e6);
  EXPECT_EQ(nu->GetComponent(1, 0), 500.0);

  const auto e = read_pvd(root_ / "s_springs.pvd");
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].time, 0.25);
  EXPECT_EQ(e[0].file, "s_springs_000000.vtp");
  // springs = false leaves the kind out of this frame
  w.write_frame(reg, {.springs = false});
  EXPECT_TRUE(fs::exists(root_ / "s_bodies_000001.vtp"));
  EXPECT_FALSE(fs::exists(root_ / "s_springs_000001.vtp"));
  EXPECT_EQ(read_pvd(root_ / "s_springs.pvd").size(), 1u);
}

TEST_F(VtkIo, SceneWithoutLinksWritesNoSpringsFile) {
  VtkScene s;
  build_scene(s);
  ASSERT_TRUE(s.reg.links.empty());
  VtkWriter w(root_);
  w.write_frame(s.reg);  // springs = true by default
  EXPECT_TRUE(fs::exists(root_ / "bodies_000000.vtp"));
  EXPECT_FALSE(fs::exists(root_ / "springs_000000.vtp"));
  EXPECT_FALSE(fs::exists(root_ / "springs.pvd"));
}
