// tests/unit/test_datbox.cpp — the LMGC90 DATBOX reader and writer (issue #39) on the small
// hand-written folders of tests/data/datbox/ (disks_box: 8 DISKx in a JONCx box with a PT2Dx,
// an evolution-file force, a cosine spin and a Vloc_Rloc.INI; polygons_box: 6 POLYG in the same
// box): what is read, the round trip DATBOX → nscd → DATBOX to the last digit written, a few
// hundred steps that settle, and bad inputs refused with the file and the line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "error_assertions.hpp"
#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/contactors/round_shapes.hpp"
#include "nscd/core/error.hpp"
#include "nscd/laws/material_pairs.hpp"
#include "nscd/io/datbox.hpp"
#include "nscd/shared/datbox_warm_start.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "temp_path.hpp"

namespace {

using namespace nscd;
namespace fs = std::filesystem;
using testing_support::Contains;
using testing_support::unique_temp_path;

const fs::path kData = fs::path(NSCD_TEST_DATA_DIR) / "datbox";

std::string read_datbox_file(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

void write_datbox_file(const fs::path& p, const std::string& s) {
  std::ofstream f(p, std::ios::binary);
  f << s;
}

/// A copy of a data folder in a fresh temporary folder.
fs::path copy_of(const std::string& name) {
  const fs::path dir = unique_temp_path("datbox") / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const auto& e : fs::directory_iterator(kData / name)) fs::copy_file(e.path(), dir / e.path().filename());
  return dir;
}

void write_back(const Datbox& d, const fs::path& dir) {
  DatboxExtras x;
  x.law_name = &d.law_name;
  x.drives = &d.drives;
  x.contacts = &d.contacts;
  x.step = d.step;
  write_datbox(dir, d.reg, x);
}

TEST(Datbox, ReadsDisksInABox) {
  const Datbox d = read_datbox(kData / "disks_box");
  const Registry& r = d.reg;
  ASSERT_EQ(r.bodies.size(), 11u);
  EXPECT_EQ(r.diskx.size(), 8u);
  EXPECT_EQ(r.joncx.size(), 3u);
  EXPECT_EQ(r.points.size(), 1u);
  EXPECT_EQ(r.polyg.size(), 0u);
  // materials per (behav, colour); LMGC90's mass Umas π avrd², inertia mass gyrd²
  ASSERT_EQ(r.materials.size(), 2u);
  EXPECT_EQ(r.materials.name[0], "TDURx:WALLx");
  EXPECT_EQ(r.materials.name[1], "PLEXx:BLEUx");
  EXPECT_DOUBLE_EQ(r.bodies.mass[3], 1200.0 * std::numbers::pi * 0.08 * 0.08);
  EXPECT_DOUBLE_EQ(r.bodies.inertia[3], r.bodies.mass[3] * 5.6568542e-02 * 5.6568542e-02);  // gyrd as written
  EXPECT_DOUBLE_EQ(r.diskx.radius[0], 0.08);
  // DOF.INI: the side walls turned by X(3), a disk's velocities
  EXPECT_DOUBLE_EQ(r.bodies.angle[1], 1.5707963);
  EXPECT_DOUBLE_EQ(r.bodies.angle0[1], 0.0);
  EXPECT_DOUBLE_EQ(r.bodies.vy[4], -0.1);
  EXPECT_DOUBLE_EQ(r.bodies.spin[4], 0.5);
  // laws and the see table: two used laws, the alert, gravity
  ASSERT_EQ(d.law_name.size(), 2u);
  EXPECT_EQ(r.params.alert, 1e-2);
  EXPECT_EQ(r.params.gravity.y, -9.81);
  const std::int32_t grains = contact_law_index(r, MaterialId(1), MaterialId(1)), wall = contact_law_index(r, MaterialId(0), MaterialId(1));
  ASSERT_GE(grains, 0);
  ASSERT_GE(wall, 0);
  EXPECT_EQ(r.contact_laws.laws[grains].kind, LawKind::IQS_CLB);
  EXPECT_EQ(r.contact_laws.laws[grains].mu, 0.3);
  EXPECT_EQ(r.contact_laws.laws[wall].kind, LawKind::GAP_SGR_CLB);
  EXPECT_EQ(contact_law_index(r, MaterialId(0), MaterialId(0)), -1);  // walls never meet walls
  // what was read but not used is said: the unused RST_CLB and the ELAS material
  std::string notes;
  for (const auto& n : d.notes) notes += n + "\n";
  EXPECT_TRUE(Contains(notes, "rstc0"));
  EXPECT_TRUE(Contains(notes, "steel"));
  // drives: the walls fixed, an evolution force, a cosine spin ramped in
  EXPECT_EQ(drive_of(r, BodyId(0), Dof::Rot), Drive::Fixed);
  EXPECT_EQ(drive_of(r, BodyId(7), Dof::X), Drive::Force);
  EXPECT_EQ(drive_of(r, BodyId(8), Dof::Rot), Drive::Velocity);
  const DatboxDrive& push = d.drives.at({7u, std::uint8_t(0)});
  EXPECT_TRUE(push.evolution);
  EXPECT_DOUBLE_EQ(push(0.005), 0.25);
  EXPECT_DOUBLE_EQ(push(5.0), 0.0);
  const DatboxDrive& spin = d.drives.at({8u, std::uint8_t(2)});
  EXPECT_DOUBLE_EQ(spin(0.05), (0.0 + std::cos(6.2831853 * 0.05 + 0.5)) * 0.5);
  // Vloc_Rloc.INI
  ASSERT_EQ(d.contacts.size(), 1u);
  EXPECT_EQ(d.contacts[0].type, "DKJCx");
  EXPECT_EQ(d.contacts[0].rln, 9.8);
}

TEST(Datbox, RoundTripIsExactToTheLastDigitWritten) {
  for (const std::string name : {"disks_box", "polygons_box"}) {
    SCOPED_TRACE(name);
    const fs::path b = unique_temp_path("datbox_b") / name, c = unique_temp_path("datbox_c") / name;
    fs::remove_all(b);
    fs::remove_all(c);
    const Datbox da = read_datbox(kData / name);
    write_back(da, b);
    const Datbox db = read_datbox(b);
    write_back(db, c);
    for (const char* f : {"BODIES.DAT", "BULK_BEHAV.DAT", "TACT_BEHAV.DAT", "DRV_DOF.DAT", "DOF.INI", "Vloc_Rloc.INI"})
      EXPECT_EQ(read_datbox_file(b / f), read_datbox_file(c / f)) << f;
    // the hand-written files are in the writer's layout: they come back the same, but for what
    // is not used (the unused law and material of disks_box)
    for (const char* f : {"BODIES.DAT", "DRV_DOF.DAT", "DOF.INI", "Vloc_Rloc.INI"})
      if (fs::exists(kData / name / f)) {
        EXPECT_EQ(read_datbox_file(kData / name / f), read_datbox_file(b / f)) << f;
      }
    if (name == "polygons_box") {
      for (const char* f : {"BULK_BEHAV.DAT", "TACT_BEHAV.DAT"}) EXPECT_EQ(read_datbox_file(kData / name / f), read_datbox_file(b / f)) << f;
    } else {
      EXPECT_EQ(read_datbox_file(kData / name / "push.dat"), read_datbox_file(b / "push.dat"));
    }
    // and the scenes are the same, bit for bit
    ASSERT_EQ(da.reg.bodies.size(), db.reg.bodies.size());
    for (std::size_t i = 0; i < da.reg.bodies.size(); ++i) {
      EXPECT_EQ(da.reg.bodies.x[i], db.reg.bodies.x[i]);
      EXPECT_EQ(da.reg.bodies.angle[i], db.reg.bodies.angle[i]);
      EXPECT_EQ(da.reg.bodies.vx[i], db.reg.bodies.vx[i]);
      EXPECT_EQ(da.reg.bodies.mass[i], db.reg.bodies.mass[i]);
    }
    EXPECT_EQ(da.reg.polyg.vertex.size(), db.reg.polyg.vertex.size());
    fs::remove_all(b.parent_path());
    fs::remove_all(c.parent_path());
  }
}

// Every DATBOX folder of tests/data (the hand-written ones and those pylmgc90 made) read, written,
// read again and written again: the two writes are the same files and the two scenes the same bits.
TEST(Datbox, EveryFolderOfTheTestDataSurvivesTheRoundTrip) {
  int folders = 0;
  for (const auto& entry : fs::directory_iterator(kData)) {
    if (!entry.is_directory()) continue;
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    ++folders;
    const fs::path b = unique_temp_path("datbox_rb") / name, c = unique_temp_path("datbox_rc") / name;
    fs::remove_all(b);
    fs::remove_all(c);
    const Datbox da = read_datbox(entry.path());
    write_back(da, b);
    const Datbox db = read_datbox(b);
    write_back(db, c);
    for (const char* f : {"BODIES.DAT", "BULK_BEHAV.DAT", "TACT_BEHAV.DAT", "DRV_DOF.DAT", "DOF.INI", "Vloc_Rloc.INI"})
      if (fs::exists(b / f)) {
        EXPECT_EQ(read_datbox_file(b / f), read_datbox_file(c / f)) << f;
      }
    ASSERT_EQ(da.reg.bodies.size(), db.reg.bodies.size());
    const auto& p = da.reg.bodies;
    const auto& q = db.reg.bodies;
    for (std::size_t i = 0; i < p.size(); ++i) {
      EXPECT_EQ(p.x[i], q.x[i]);
      EXPECT_EQ(p.y[i], q.y[i]);
      EXPECT_EQ(p.angle[i], q.angle[i]);
      EXPECT_EQ(p.vx[i], q.vx[i]);
      EXPECT_EQ(p.vy[i], q.vy[i]);
      EXPECT_EQ(p.spin[i], q.spin[i]);
      EXPECT_EQ(p.is_driven[i], q.is_driven[i]);
    }
    EXPECT_EQ(p.drives.size(), q.drives.size());
    ASSERT_EQ(da.reg.contact_laws.laws.size(), db.reg.contact_laws.laws.size());
    for (std::size_t k = 0; k < da.reg.contact_laws.laws.size(); ++k) {
      EXPECT_EQ(da.reg.contact_laws.laws[k].kind, db.reg.contact_laws.laws[k].kind);
      EXPECT_EQ(da.reg.contact_laws.laws[k].mu, db.reg.contact_laws.laws[k].mu);
      EXPECT_EQ(da.reg.contact_laws.laws[k].e_n, db.reg.contact_laws.laws[k].e_n);
    }
    EXPECT_EQ(da.reg.polyg.vertex.size(), db.reg.polyg.vertex.size());
    fs::remove_all(b.parent_path());
    fs::remove_all(c.parent_path());
  }
  EXPECT_GE(folders, 6);
}

TEST(Datbox, WritesASceneNscdBuilt) {
  Registry reg;
  const MaterialId grain = add_material(reg, "grain", 2600.0), wall = add_material(reg, "wall", 1000.0);
  set_contact_law(reg, grain, grain, {LawKind::IQS_CLB, 0.4});
  set_contact_law(reg, grain, wall, {LawKind::RST_CLB, 0.3, 0.5, 0.0});
  const BodyId floor = add_jonc_body(reg, 1.0, 0.05, wall, {0.5, -0.05}, 0.1);
  fix_body(reg, floor);
  add_disk_body(reg, 0.05, grain, {0.3, 0.2});
  add_polygon_body(reg, rectangle(0.1, 0.06), grain, {0.6, 0.2}, 0.3);
  impose_velocity(reg, BodyId(2), Dof::Rot, TimeFunction::cosine(0.0, 1.0, 2.0, 0.25, 0.5));
  const fs::path dir = unique_temp_path("datbox_nscd");
  fs::remove_all(dir);
  write_datbox(dir, reg);
  const Datbox d = read_datbox(dir);
  ASSERT_EQ(d.reg.bodies.size(), 3u);
  EXPECT_EQ(d.reg.materials.name[0], "M0002:C0002");  // generated names: "wall" is not behav:colour
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(d.reg.bodies.x[i], reg.bodies.x[i], 1e-7);
    EXPECT_NEAR(d.reg.bodies.angle[i], reg.bodies.angle[i], 1e-7);
    EXPECT_NEAR(d.reg.bodies.mass[i], reg.bodies.mass[i], 1e-7 * reg.bodies.mass[i]);
    EXPECT_NEAR(d.reg.bodies.inertia[i], reg.bodies.inertia[i], 1e-7 * reg.bodies.inertia[i]);
  }
  EXPECT_EQ(drive_of(d.reg, BodyId(0), Dof::Y), Drive::Fixed);
  // the cosine drive in LMGC90's form: ramp 0.5 s is RAMPI 0, RAMP 2
  const DatboxDrive& w = d.drives.at({2u, std::uint8_t(2)});
  EXPECT_DOUBLE_EQ(w.rampi, 0.0);
  EXPECT_DOUBLE_EQ(w.ramp, 2.0);
  EXPECT_NEAR(w(0.3), reg.bodies.drives.back().value(0.3), 1e-6);
  const std::int32_t k = contact_law_index(d.reg, MaterialId(0), MaterialId(1));
  ASSERT_GE(k, 0);
  EXPECT_EQ(d.reg.contact_laws.laws[k].kind, LawKind::RST_CLB);
  EXPECT_EQ(d.reg.contact_laws.laws[k].e_n, 0.5);
  fs::remove_all(dir);
}

TEST(Datbox, ReadsWhatLmgc90Reads) {
  // avrd 0 and gyrd blank (old files): both from the contactor; labels not read; '#' comments
  const fs::path dir = copy_of("disks_box");
  std::string bodies = read_datbox_file(dir / "BODIES.DAT");
  bodies.replace(bodies.find("avrd= 8.0000000E-02  gyrd= 5.6568542E-02"), 40, "avrd= 0.0000000D+00");
  bodies.replace(bodies.find("axe1= 6.0000000E-01  axe2="), 26, "ax1 = 6.0000000D-01  ax2 =");
  write_datbox_file(dir / "BODIES.DAT", bodies);
  write_datbox_file(dir / "TACT_BEHAV.DAT", "#\n# a comment\n" + read_datbox_file(dir / "TACT_BEHAV.DAT"));
  const Datbox d = read_datbox(dir);
  EXPECT_DOUBLE_EQ(d.reg.bodies.mass[3], 1200.0 * std::numbers::pi * 0.08 * 0.08);
  EXPECT_DOUBLE_EQ(d.reg.bodies.inertia[3], d.reg.bodies.mass[3] * 0.08 * 0.08 / 2.0);
  EXPECT_EQ(d.reg.joncx.half_length[0], 0.6);
  fs::remove_all(unique_temp_path("datbox"));
}

/// Steps a DATBOX scene; every grain (a body not driven) stays in the box [0, 1] × [0, 1.2].
void settles(const std::string& name, int steps, double dt, double* ke_out) {
  Datbox d = read_datbox(kData / name);
  d.reg.params.dt = dt;
  if (name == "disks_box") free_dof(d.reg, BodyId(8), Dof::Rot);  // its imposed spin would keep its neighbours rolling
  MoreauJean mj(d.reg);
  std::size_t matched = 0;
  mj.set_warm_start_memory(scenes::datbox_warm_start(d.reg, d.contacts, &matched));
  EXPECT_EQ(matched, d.contacts.size());
  for (int s = 0; s < steps; ++s) mj.step();
  const BodyTable& b = d.reg.bodies;
  for (std::size_t i = 3; i < b.size(); ++i) {
    EXPECT_GT(b.x[i], 0.0) << "body " << i + 1;
    EXPECT_LT(b.x[i], 1.0) << "body " << i + 1;
    EXPECT_GT(b.y[i], 0.0) << "body " << i + 1;
    EXPECT_LT(b.y[i], 1.2) << "body " << i + 1;
  }
  EXPECT_GT(mj.report().contacts, 5u);
  if (name == "disks_box") {  // no disk through the floor (its top at y = 0); most rest on it
    int on_floor = 0;
    for (std::size_t i = 3; i < b.size(); ++i) {
      EXPECT_GT(b.y[i], d.reg.diskx.radius[i - 3] - 1e-3) << "body " << i + 1;
      on_floor += b.y[i] < d.reg.diskx.radius[i - 3] + 1e-3 ? 1 : 0;
    }
    EXPECT_GE(on_floor, 4);
  }
  *ke_out = kinetic_energy(d.reg);
}

TEST(Datbox, DisksSettleInTheBox) {
  double ke = 0.0;
  settles("disks_box", 2500, 2e-3, &ke);  // 5 s: the disks roll apart (no rolling resistance) before they rest
  EXPECT_LT(ke, 1e-6);
}

TEST(Datbox, PolygonsSettleInTheBox) {
  double ke = 0.0;
  settles("polygons_box", 400, 2e-3, &ke);
  EXPECT_LT(ke, 1e-3);
}

/// Replaces the first `from` in `file` of a copy of `name` by `to`; returns the error message.
std::string refusal(const std::string& name, const std::string& file, const std::string& from, const std::string& to) {
  const fs::path dir = copy_of(name);
  std::string text = read_datbox_file(dir / file);
  const auto at = text.find(from);
  if (at == std::string::npos) return "(test error: '" + from + "' not in " + file + ")";
  text.replace(at, from.size(), to);
  write_datbox_file(dir / file, text);
  try {
    read_datbox(dir);
  } catch (const Error& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(Datbox, RefusesBadInputNamingFileAndLine) {
  {
    const fs::path dir = copy_of("disks_box");
    fs::remove(dir / "BODIES.DAT");
    std::string why;
    try {
      read_datbox(dir);
    } catch (const Error& e) {
      why = e.what();
    }
    EXPECT_TRUE(Contains(why, "BODIES.DAT")) << why;
    EXPECT_TRUE(Contains(why, "missing")) << why;
  }
  std::string why = refusal("disks_box", "BODIES.DAT", " DISKx      1  color  BLEUx  byrd= 8.0000000E-02", " DISKb      1  color  BLEUx  byrd= 8.0000000E-02");
  EXPECT_TRUE(Contains(why, "BODIES.DAT', line 35: contactor 'DISKb' is not supported")) << why;
  why = refusal("disks_box", "BODIES.DAT", " RBDY2      5\n", " RBDY3      5\n");
  EXPECT_TRUE(Contains(why, "line 38: body type RBDY3 (a 3D rigid body)")) << why;
  why = refusal("disks_box", "BODIES.DAT", " RBDY2      5\n", " MAILx      5\n");
  EXPECT_TRUE(Contains(why, "line 38: body type MAILx (a deformable mesh)")) << why;
  why = refusal("disks_box", "BODIES.DAT", "byrd= 8.0000000E-02", "byrd= 8.00000x0E-02");
  EXPECT_TRUE(Contains(why, "BODIES.DAT', line 35: byrd: ' 8.00000x0E-02' is not a finite number")) << why;
  why = refusal("polygons_box", "BODIES.DAT", "$$$$$$\n$bdyty\n RBDY2      5", "");  // body 4 runs into body 5's
  EXPECT_TRUE(Contains(why, "BODIES.DAT', line")) << why;
  {  // a file cut inside a POLYG
    const fs::path dir = copy_of("polygons_box");
    const std::string text = read_datbox_file(dir / "BODIES.DAT");
    std::size_t cut = text.find(" POLYG      1");
    for (int k = 0; k < 3; ++k) cut = text.find('\n', cut) + 1;  // the POLYG line and two of its five vertices
    write_datbox_file(dir / "BODIES.DAT", text.substr(0, cut));
    std::string w;
    try {
      read_datbox(dir);
    } catch (const Error& e) {
      w = e.what();
    }
    EXPECT_TRUE(Contains(w, "BODIES.DAT', line 37: the file ends where a POLYG vertex line was expected (truncated?)")) << w;
  }
  why = refusal("disks_box", "TACT_BEHAV.DAT", "RBDY2  DISKx  BLEUx  gapc0  RBDY2  JONCx", "RBDY2  DISKx  BLEUx  rstc0  RBDY2  JONCx");
  EXPECT_EQ(why, "(accepted)");  // RST_CLB is read
  why = refusal("disks_box", "TACT_BEHAV.DAT", "GAP_SGR_CLB     ", "ELASTIC_WIRE    ");
  EXPECT_TRUE(Contains(why, "TACT_BEHAV.DAT', line 18: contact law 'gapc0' is ELASTIC_WIRE (line 6)")) << why;
  why = refusal("disks_box", "TACT_BEHAV.DAT", "RBDY2  JONCx  WALLx", "MAILx  ALpxx  WALLx");
  EXPECT_TRUE(Contains(why, "line 18: body type 'MAILx' in the see table is not supported")) << why;
  why = refusal("disks_box", "DOF.INI", "V(2)=-1.0000000e-01", "V(2)=-1.0000000e-0!");
  EXPECT_TRUE(Contains(why, "DOF.INI', line")) << why;
  why = refusal("disks_box", "DRV_DOF.DAT", "evolution push.dat", "evolution nothing.dat");
  EXPECT_TRUE(Contains(why, "DRV_DOF.DAT', line")) << why;
  EXPECT_TRUE(Contains(why, "'nothing.dat' cannot be read")) << why;
  why = refusal("disks_box", "Vloc_Rloc.INI", "DKJCx", "CLJCx");
  EXPECT_TRUE(Contains(why, "Vloc_Rloc.INI', line 7: interaction 'CLJCx' is not supported")) << why;
  fs::remove_all(unique_temp_path("datbox"));
}

}  // namespace
