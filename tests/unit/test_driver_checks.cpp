// tests/unit/test_driver_checks.cpp — the checks the drivers share (shared/driver_checks.hpp):
// output folders never mixed with an earlier run, options a run cannot honour, impossible
// results named (issue #9).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "error_assertions.hpp"
#include "nscd/shared/driver_checks.hpp"
#include "nscd/shared/samples.hpp"

namespace {

using namespace nscd;
using nscd::testing_support::Contains;
using nscd::testing_support::error_message;
namespace fs = std::filesystem;

TEST(DriverChecks, OutputFolderHoldingARunIsRefusedUnlessOverwritten) {
  const fs::path dir = fs::temp_directory_path() / ("nscd_driver_checks_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  EXPECT_EQ(scenes::claim_output_folder(dir / "new", {"summary.txt"}, false, true), "");  // created
  EXPECT_TRUE(fs::is_directory(dir / "new"));
  std::ofstream(dir / "new" / "log.txt") << "log";  // a log alone is not a run
  std::ofstream(dir / "new" / "pid") << "123";
  EXPECT_EQ(scenes::claim_output_folder(dir / "new", {"summary.txt"}, false, true), "");
  std::ofstream(dir / "new" / "summary.txt") << "old";
  fs::create_directories(dir / "new" / "vtk");
  std::ofstream(dir / "new" / "input.nscd") << "kept";
  const std::string m = error_message([&] { scenes::claim_output_folder(dir / "new", {"summary.txt", "vtk"}, false, true); });
  EXPECT_TRUE(Contains(m, "is not empty (it holds input.nscd, summary.txt, vtk)"));
  EXPECT_TRUE(Contains(m, "--overwrite"));
  EXPECT_TRUE(Contains(m, "--resume"));
  const std::string note =
      scenes::claim_output_folder(dir / "new", {"summary.txt", "vtk", "input.nscd"}, true, true, dir / "new" / "input.nscd");
  EXPECT_TRUE(Contains(note, "input.nscd"));
  EXPECT_FALSE(fs::exists(dir / "new" / "summary.txt"));
  EXPECT_FALSE(fs::exists(dir / "new" / "vtk"));
  EXPECT_TRUE(fs::exists(dir / "new" / "input.nscd"));  // the input is never deleted
  EXPECT_TRUE(fs::exists(dir / "new" / "log.txt"));
  std::ofstream(dir / "file") << "x";
  EXPECT_TRUE(Contains(error_message([&] { scenes::claim_output_folder(dir / "file", {}, true, false); }), "is not a folder"));
  fs::remove_all(dir);
}

TEST(DriverChecks, OptionsThatCannotBeHonouredAreNamed) {
  EXPECT_NO_THROW(scenes::refuse_options({"dt"}, {"box-width"}, "--scene lmgc90"));
  try {
    scenes::refuse_options({"dt", "box-width"}, {"pitch-factor", "box-width"}, "--scene lmgc90");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "--box-width cannot go with --scene lmgc90");
  }
}

TEST(DriverChecks, ImpossibleStatesAreNamed) {
  scenes::Scene s = scenes::paper_sample_loose();
  EXPECT_EQ(scenes::implausible(s.reg, s.grains, s.box_width, 0.0), "");
  const std::size_t g = s.grains[3].index();
  s.reg.bodies.x[g] = -0.25;
  EXPECT_TRUE(Contains(scenes::implausible(s.reg, s.grains, s.box_width, 0.0), "grain 'grain 3' at (-0.25, "));
  EXPECT_TRUE(Contains(scenes::implausible(s.reg, s.grains, s.box_width, 0.0), "is outside the box"));
  s.reg.bodies.x[g] = 0.5;
  s.reg.bodies.y[g] = -0.4999999;
  EXPECT_TRUE(Contains(scenes::implausible(s.reg, s.grains, s.box_width, 0.0), "at (0.5, -0.4999999) m is below the floor"));
  s.reg.bodies.vy[g] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(Contains(scenes::implausible(s.reg, s.grains, s.box_width, 0.0), "non-finite"));
}

}  // namespace
