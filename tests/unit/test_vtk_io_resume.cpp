// tests/unit/test_vtk_io_resume.cpp — io/vtk_writer: resuming the collections of a run restarted
// from a checkpoint, on the scene with PTPT2 links of vtk_io_fixtures.hpp: the frames up to the
// checkpoint kept, the numbering continued after the highest kept frame, a malformed collection
// refused with its name.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <vtkDataArray.h>
#include <vtkPolyData.h>

#include "nscd/core/error.hpp"
#include "nscd/io/vtk_writer.hpp"
#include "vtk_io_fixtures.hpp"

namespace fs = std::filesystem;
using namespace nscd;
using namespace nscd::vtk_io_fixtures;

namespace {

// Writes `text` as the file `path` (replacing it).
void write_vtk_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  ASSERT_TRUE(out.good()) << path;
}

}  // namespace

TEST_F(VtkIo, ResumeKeepsFramesUpToTheCheckpointAndContinuesTheNumbering) {
  Registry reg;
  build_spring_scene(reg);
  {
    VtkWriter first(root_, "r_");
    for (int f = 0; f < 3; ++f) {  // frames 0, 1, 2 at t = 0, 1, 2, block vx = 10, 11, 12
      reg.time = f;
      reg.bodies.vx[1] = 10.0 + f;
      first.write_frame(reg);
    }
  }
  // restart from a checkpoint at t = 1: frame 2 (t = 2) is dropped, the next frame is number 2
  VtkWriter w(root_, "r_");
  w.resume(1.0);
  EXPECT_EQ(w.frames(), 2);
  for (const char* kind : {"bodies", "contacts", "springs"})  // the .pvd files are rewritten at once
    EXPECT_EQ(read_pvd(root_ / ("r_" + std::string(kind) + ".pvd")).size(), 2u) << kind;
  reg.time = 1.5;
  reg.bodies.vx[1] = 99.0;
  w.write_frame(reg);
  EXPECT_EQ(w.frames(), 3);

  const double times[] = {0.0, 1.0, 1.5};
  for (const char* kind : {"bodies", "contacts", "springs"}) {
    const auto e = read_pvd(root_ / ("r_" + std::string(kind) + ".pvd"));
    ASSERT_EQ(e.size(), 3u) << kind;
    for (int f = 0; f < 3; ++f) {
      char name[64];
      std::snprintf(name, sizeof name, "r_%s_%06d.vtp", kind, f);
      EXPECT_EQ(e[f].time, times[f]) << kind;
      EXPECT_EQ(e[f].file, name);
      EXPECT_TRUE(fs::exists(root_ / name)) << name;
    }
  }
  // frame 2 was overwritten with the state at t = 1.5; frame 1 is the one of the first run
  auto pd2 = read_vtp(root_ / "r_bodies_000002.vtp"), pd1 = read_vtp(root_ / "r_bodies_000001.vtp");
  vtkDataArray* v2 = cell_array(pd2, "velocity", 3);
  vtkDataArray* v1 = cell_array(pd1, "velocity", 3);
  ASSERT_TRUE(v1 && v2);
  EXPECT_EQ(v2->GetComponent(1, 0), 99.0);
  EXPECT_EQ(v1->GetComponent(1, 0), 11.0);
}

TEST_F(VtkIo, ResumeNumbersAfterTheHighestKeptFrameOfAnyKind) {
  Registry reg;
  build_spring_scene(reg);
  {
    VtkWriter first(root_);
    reg.time = 0.0;
    first.write_frame(reg);                                                      // frame 0: all kinds
    reg.time = 1.0;
    first.write_frame(reg, {.bodies = true, .contacts = false, .springs = false});  // frame 1: bodies
    reg.time = 2.0;
    first.write_frame(reg, {.bodies = false, .contacts = true, .springs = false});  // frame 2: contacts
  }
  VtkWriter w(root_);
  w.resume(1.5);  // keeps bodies 0, 1; contacts 0; springs 0: highest kept frame 1
  EXPECT_EQ(w.frames(), 2);
  EXPECT_EQ(read_pvd(root_ / "bodies.pvd").size(), 2u);
  EXPECT_EQ(read_pvd(root_ / "contacts.pvd").size(), 1u);
  EXPECT_EQ(read_pvd(root_ / "springs.pvd").size(), 1u);
  w.resume(0.5);  // the rewritten files read back: only frame 0 left
  EXPECT_EQ(w.frames(), 1);
  EXPECT_EQ(read_pvd(root_ / "bodies.pvd").size(), 1u);
  w.resume(-1.0);  // before every frame: empty (but valid) collections, numbering from 0
  EXPECT_EQ(w.frames(), 0);
  EXPECT_TRUE(read_pvd(root_ / "bodies.pvd").empty());
  w.write_frame(reg);
  const auto e = read_pvd(root_ / "springs.pvd");
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].file, "springs_000000.vtp");
}

TEST_F(VtkIo, ResumeOnAnEmptyDirectoryStartsAtFrameZero) {
  VtkWriter w(root_ / "fresh");
  w.resume(5.0);  // no .pvd: nothing to resume, and no file created
  EXPECT_EQ(w.frames(), 0);
  EXPECT_TRUE(fs::is_empty(root_ / "fresh"));
  Registry reg;
  const MaterialId rock = add_material(reg, "rock", 2000.0);
  add_polygon_body(reg, rectangle(1.0, 1.0), rock, {0.0, 0.0});
  w.write_frame(reg);
  EXPECT_TRUE(fs::exists(root_ / "fresh" / "bodies_000000.vtp"));
  EXPECT_EQ(read_pvd(root_ / "fresh" / "bodies.pvd").size(), 1u);
  EXPECT_THROW(w.resume(std::numeric_limits<double>::quiet_NaN()), Error);
}

TEST_F(VtkIo, ResumeRejectsAMalformedCollectionNamingIt) {
  Registry reg;
  build_spring_scene(reg);
  {
    VtkWriter first(root_);
    for (int f = 0; f < 3; ++f) {
      reg.time = f;
      first.write_frame(reg);
    }
  }
  const std::string head = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  const std::string tail = "</Collection>\n</VTKFile>\n";
  const std::string bad[] = {
      "this is not XML",
      head + "<DataSet timestep=\"0\" file=\"springs_000000.vtp\"/>\n",  // truncated
      head + "<DataSet timestep=\"zero\" file=\"springs_000000.vtp\"/>\n" + tail,
      head + "<DataSet timestep=\"0\"/>\n" + tail,
      head + "<DataSet timestep=\"0\" file=\"bodies_000000.vtp\"/>\n" + tail,  // another kind
      head + "<DataSet timestep=\"0\" file=\"springs_-00001.vtp\"/>\n" + tail,
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\"><Collection/></VTKFile>\n",
  };
  for (const std::string& text : bad) {
    write_vtk_file(root_ / "springs.pvd", text);
    VtkWriter w(root_);
    ::testing::internal::CaptureStderr();
    try {
      w.resume(0.5);
      ADD_FAILURE() << "no exception for: " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("springs.pvd"), std::string::npos) << e.what();
    }
    // VTK's parser messages go into the exception, not onto the terminal
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << text;
    EXPECT_EQ(w.frames(), 0);
    // parsed before any rewrite: bodies.pvd still lists its 3 frames
    EXPECT_EQ(read_pvd(root_ / "bodies.pvd").size(), 3u);
  }
  // a collection written by another tool, with other attributes, a comment and entities, is fine
  write_vtk_file(root_ / "springs.pvd", "<?xml version=\"1.0\"?>\n<!-- by hand -->\n"
                                    "<VTKFile version=\"1.0\" type='Collection'>\n <Collection>\n"
                                    "  <!-- a comment -->\n"
                                    "  <DataSet part=\"0\" file=\"springs_00000&#55;.vtp\" timestep=\"1e-1\"></DataSet>\n"
                                    " </Collection>\n</VTKFile>\n");
  VtkWriter w(root_);
  w.resume(0.5);  // bodies 0; springs 7 (t = 0.1): the highest is 7
  EXPECT_EQ(w.frames(), 8);
  const auto e = read_pvd(root_ / "springs.pvd");
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].time, 0.1);
  EXPECT_EQ(e[0].file, "springs_000007.vtp");
}
