// tests/unit/vtk_io_fixtures.hpp — what the tests of io/vtk_writer share (test_vtk_io.cpp,
// test_vtk_io_resume.cpp): a fresh directory per test, the .vtp files read back with VTK's own
// reader, the .pvd collections parsed, and a scene with PTPT2 links.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/contactors/pt2dx.hpp"
#include "nscd/interactions/ptpt2.hpp"

namespace nscd::vtk_io_fixtures {

namespace fs = std::filesystem;

// A fresh, unique directory under the system temporary directory, removed afterwards.
class VtkIo : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device rd;
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    root_ = fs::temp_directory_path() /
            ("nscd_vtk_" + std::string(info->name()) + "_" + std::to_string(rd()) + std::to_string(rd()));
    ASSERT_FALSE(fs::exists(root_));
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }
  fs::path root_;
};

inline vtkSmartPointer<vtkPolyData> read_vtp(const fs::path& file) {
  auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
  r->SetFileName(file.string().c_str());
  r->Update();
  EXPECT_EQ(r->GetErrorCode(), 0u) << file;
  return r->GetOutput();
}

// The array `name` of the cell data; fails the test if absent or with the wrong component count.
inline vtkDataArray* cell_array(vtkPolyData* pd, const char* name, int components) {
  vtkDataArray* a = pd->GetCellData()->GetArray(name);
  EXPECT_NE(a, nullptr) << "missing cell array " << name;
  if (a) {
    EXPECT_EQ(a->GetNumberOfComponents(), components) << name;
    EXPECT_EQ(a->GetNumberOfTuples(), pd->GetNumberOfCells()) << name;
  }
  return a;
}

inline Vec2 cell_point(vtkPolyData* pd, vtkIdType cell, vtkIdType k) {
  vtkNew<vtkIdList> ids;
  pd->GetCellPoints(cell, ids);
  double p[3];
  pd->GetPoint(ids->GetId(k), p);
  EXPECT_EQ(p[2], 0.0);
  return {p[0], p[1]};
}

struct PvdEntry {
  double time;
  std::string file;
};
inline std::vector<PvdEntry> read_pvd(const fs::path& file) {
  std::ifstream in(file);
  EXPECT_TRUE(in.good()) << file;
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  EXPECT_NE(text.find("<VTKFile type=\"Collection\""), std::string::npos);
  EXPECT_NE(text.find("</VTKFile>"), std::string::npos);
  std::vector<PvdEntry> out;
  const std::regex ds(R"re(<DataSet timestep="([^"]*)"[^>]* file="([^"]*)"\s*/>)re");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), ds); it != std::sregex_iterator(); ++it)
    out.push_back({std::stod((*it)[1].str()), (*it)[2].str()});
  return out;
}

// Springs scene: a fixed ground (2 × 0.2 at (0, -0.1), top y = 0) and a 0.4 × 0.2 block at
// (0, 0.5) held by two VOIGT_ROD springs from the block's bottom corners straight down to the
// ground, all anchors attached in world coordinates:
//   link 0: candidate block (-0.2, 0.4), antagonist ground (-0.2, 0), k 2e6, nu 3e3, L0 0.3, eps0 0.1
//   link 1: candidate block ( 0.2, 0.4), antagonist ground ( 0.2, 0), k 1e6, nu 500, L0 from the
//           current distance (0.4), eps0 0
// Then the block is moved to (0.1, 0.6) and turned by +π/2, without a new detection: the link
// table still holds the lengths 0.4 of the creation, the writer must use the new configuration.
inline void build_spring_scene(Registry& reg) {
  const MaterialId rock = add_material(reg, "rock", 2000.0);
  const BodyId ground = add_polygon_body(reg, rectangle(2.0, 0.2), rock, {0.0, -0.1}, 0.0, "ground");
  fix_body(reg, ground);
  const BodyId block = add_polygon_body(reg, rectangle(0.4, 0.2), rock, {0.0, 0.5}, 0.0, "block");
  const PointId g0 = attach_point_world(reg, ground, {-0.2, 0.0}), g1 = attach_point_world(reg, ground, {0.2, 0.0});
  const PointId b0 = attach_point_world(reg, block, {-0.2, 0.4}), b1 = attach_point_world(reg, block, {0.2, 0.4});
  add_spring(reg, b0, g0, VoigtRod{.k = 2e6, .nu = 3e3, .L0 = 0.3, .eps0 = 0.1});
  add_spring(reg, b1, g1, VoigtRod{.k = 1e6, .nu = 500.0, .L0 = 0.0, .eps0 = 0.0});
  const std::size_t i = block.index();
  reg.bodies.x[i] = 0.1;
  reg.bodies.y[i] = 0.6;
  reg.bodies.angle[i] = 0.5 * kPi;
  // forces as a solve at rest would leave them, R_N = −k (L − L0 (1 + eps0)) (values below)
  reg.links.rn[0] = -471370.849898476;
  reg.links.rn[1] = -4.0e5;
}

}  // namespace nscd::vtk_io_fixtures
