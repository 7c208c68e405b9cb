// nscd/io/datbox_reader.cpp — LMGC90 DATBOX folder → Registry (datbox.hpp): BODIES.DAT,
// BULK_BEHAV.DAT, TACT_BEHAV.DAT, DOF.INI. DRV_DOF.DAT and Vloc_Rloc.INI: datbox_drives.cpp.
//
// Columns as LMGC90's readers take them (mod_RBDY2.f90 read_bodies, mod_a_BDARY_*.f90,
// mod_bulk_behav.f90, mod_tact_behav.f90 read_xxx_tact_behav, mod_RBDY2.f90 read_in_dof);
// LMGC90 fishes for its keywords and skips what it does not know, nscd refuses it instead.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <set>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/contactors/pt2dx.hpp"
#include "nscd/contactors/round_shapes.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/datbox.hpp"
#include "nscd/io/datbox_format.hpp"
#include "nscd/io/datbox_internal.hpp"
#include "nscd/laws/contact_laws.hpp"
#include "nscd/laws/material_pairs.hpp"

namespace nscd::datbox {
namespace {

std::string trim(std::string_view s) {
  const auto a = s.find_first_not_of(' ');
  if (a == std::string_view::npos) return {};
  return std::string(s.substr(a, s.find_last_not_of(' ') - a + 1));
}

bool skippable(const std::string& l) {
  return l.find_first_not_of(' ') == std::string::npos || l[0] == '!' || l[0] == '#';
}

/// The next line that is not blank or a comment; false at the end.
bool next_content(Lines& in) {
  while (in.next())
    if (!skippable(in.line())) return true;
  return false;
}

/// The next content line, which must be the keyword line "$<key>".
void expect_key(Lines& in, const char* key) {
  if (!next_content(in)) throw Error(in.where() + ": the file ends where '$" + key + "' was expected (truncated?)");
  if (in.line()[0] != '$' || in.key() != key)
    in.fail("expected '$" + std::string(key) + "', found '" + trim(in.line()) + "'");
}

/// The next line, whatever it is (a block's data line); fails at the end.
void expect_line(Lines& in, const char* what) {
  if (!in.next()) throw Error(in.where() + ": the file ends where " + std::string(what) + " was expected (truncated?)");
}

// ---- BULK_BEHAV.DAT ----------------------------------------------------------------------

void read_bulk(Lines& in, Vec2& gravity, std::map<std::string, BulkBehav>& behavs) {
  while (next_content(in)) {
    if (in.line()[0] != '$')
      in.fail("unexpected line '" + trim(in.line()) + "' (a '$gravy' or '$behav' block was expected)");
    const std::string key = in.key();
    if (key == "gravy") {
      expect_line(in, "the gravity line");
      gravity = {in.value(kGravityGrid, 0, "grv1="), in.value(kGravityGrid, 1, "grv2=")};
    } else if (key == "behav") {
      expect_line(in, "a bulk behaviour line");
      BulkBehav b;
      b.name = trim(in.column(1, 5));
      b.law = trim(in.column(8, 30));
      b.line = in.number();
      if (b.name.empty()) in.fail("a bulk behaviour without a name (columns 2-6)");
      if (behavs.count(b.name)) in.fail("bulk behaviour '" + b.name + "' defined twice");
      if (b.law == "RIGID") {
        b.density = in.value(kBehavGrid, 0, "Umas=");
      } else {  // another law's parameters follow on lines of their own: up to the next '$'
        while (in.next())
          if (!in.line().empty() && in.line()[0] == '$') {
            in.back();
            break;
          }
      }
      behavs.emplace(b.name, b);
    } else {
      in.fail("unknown block '$" + key + "' (BULK_BEHAV.DAT has '$gravy' and '$behav')");
    }
  }
}

// ---- BODIES.DAT -------------------------------------------------------------------------


void read_tact(Lines& in, BodyRec& b) {
  TactRec t;
  t.kind = in.key();
  t.line = in.number();
  if (t.kind != "DISKx" && t.kind != "JONCx" && t.kind != "xKSID" && t.kind != "POLYG" && t.kind != "PT2Dx")
    in.fail("contactor '" + trim(in.column(1, 5)) +
            "' is not supported (nscd reads DISKx, JONCx, xKSID, POLYG, PT2Dx)");
  if (in.column(15, 5) != "color") in.fail("expected 'color' in columns 16-20");
  t.colour = trim(in.column(22, 5));
  if (t.colour.empty()) in.fail("a contactor without a colour (columns 23-27)");
  if (t.kind == "DISKx" || t.kind == "xKSID") {
    t.a = in.value(kBodyGrid, 0, "byrd=");
  } else if (t.kind == "JONCx") {
    t.a = in.value(kBodyGrid, 0, "axe1=");
    t.b = in.value(kBodyGrid, 1, "axe2=");
  } else if (t.kind == "PT2Dx") {
    t.a = in.value(kBodyGrid, 0, "coo1=");
    t.b = in.value(kBodyGrid, 1, "coo2=");
  } else {
    if (in.column(29, 10) != "nb_vertex=") in.fail("expected 'nb_vertex=' in columns 30-39");
    const long long n = in.integer_at(39, 7, "nb_vertex");
    if (n < 3 || n > static_cast<long long>(kMaxPolygVertices))
      in.fail("nb_vertex must lie in [3, 4096], got " + std::to_string(n));
    for (long long k = 0; k < n; ++k) {
      expect_line(in, "a POLYG vertex line");
      t.vertices.push_back({in.value(kBodyGrid, 0, "coo1="), in.value(kBodyGrid, 1, "coo2=")});
    }
  }
  b.tacts.push_back(std::move(t));
}

BodyRec read_body(Lines& in) {
  BodyRec b;
  expect_line(in, "the body line");
  const std::string type = in.key();
  if (type == "RBDY3") in.fail("body type RBDY3 (a 3D rigid body) is not supported: nscd is 2D (RBDY2 only)");
  if (type == "MAILx")
    in.fail("body type MAILx (a deformable mesh) is not supported: nscd has rigid bodies (RBDY2 only)");
  if (type != "RBDY2") in.fail("body type '" + trim(in.column(1, 5)) + "' is not supported (RBDY2 only)");
  b.line = in.number();
  expect_key(in, "blmty");
  expect_line(in, "the PLAIN line");
  if (in.key() != "PLAIN") in.fail("bulk element '" + trim(in.column(1, 5)) + "' is not supported (PLAIN only)");
  if (in.column(15, 5) != "behav") in.fail("expected 'behav' in columns 16-20");
  b.behav = trim(in.column(22, 5));
  b.behav_line = in.number();
  b.avrd = in.value(kBodyGrid, 0, "avrd=");
  // a blank gyrd reads as 0 in Fortran (old files have none): LMGC90 then computes both
  b.gyrd = in.column(kBodyGrid + kFieldStride, 14).find_first_not_of(' ') == std::string_view::npos
               ? 0.0
               : in.value(kBodyGrid, 1, "gyrd=");
  if (b.avrd < 0.0 || b.gyrd < 0.0) in.fail("avrd and gyrd must be >= 0");
  expect_key(in, "nodty");
  expect_line(in, "the node line");
  if (in.key() == "NO6xx") in.fail("node NO6xx (a 3D rigid body) is not supported: nscd is 2D (NO3xx only)");
  if (in.key() != "NO3xx") in.fail("node '" + trim(in.column(1, 5)) + "' is not supported (NO3xx only)");
  for (int k = 0; k < 3; ++k) b.coo[k] = in.value(kBodyGrid, k, k == 0 ? "coo1=" : k == 1 ? "coo2=" : "coo3=");
  expect_key(in, "tacty");
  while (true) {
    expect_line(in, "a contactor or '$$$$$$'");
    if (in.line().rfind("$$$$$$", 0) == 0) break;
    if (skippable(in.line())) continue;
    read_tact(in, b);
  }
  return b;
}

std::vector<BodyRec> read_bodies(Lines& in) {
  std::vector<BodyRec> bodies;
  while (next_content(in)) {
    if (in.line()[0] != '$' || in.key() != "bdyty") in.fail("expected '$bdyty', found '" + trim(in.line()) + "'");
    bodies.push_back(read_body(in));
  }
  return bodies;
}

// ---- TACT_BEHAV.DAT ---------------------------------------------------------------------

void read_law(Lines& in, std::map<std::string, LawRec>& laws) {
  expect_line(in, "a contact law line");
  LawRec r;
  r.name = trim(in.column(1, 5));
  r.law = trim(in.column(8, 30));
  r.line = in.number();
  if (r.name.empty()) in.fail("a contact law without a name (columns 2-6)");
  if (laws.count(r.name)) in.fail("contact law '" + r.name + "' defined twice");
  if (const ContactLawRow* row = find_contact_law_row(r.law)) {
    r.spec.kind = row->kind;
    if (row->restitution) {  // rstn= and rstt= on the law's line, fric= on the next
      r.spec.e_n = in.value(kBehavGrid, 0, "rstn=");
      r.spec.e_t = in.value(kBehavGrid, 1, "rstt=");
      expect_line(in, (r.law + "'s 'fric=' line").c_str());
    }
    r.spec.mu = in.value(kBehavGrid, 0, "fric=");
    r.known = true;
  } else {  // parameters of another law: up to the next '$'
    while (in.next())
      if (!in.line().empty() && in.line()[0] == '$') {
        in.back();
        break;
      }
  }
  if (r.known) {
    try {
      validate(r.spec);
    } catch (const Error& e) {
      in.fail(e.what());
    }
  }
  laws.emplace(r.name, r);
}

SeeRec read_see(Lines& in) {
  expect_line(in, "the see table's header line");
  if (trim(in.column(1, 5)) != "cdbdy")
    in.fail("expected the header ' cdbdy  cdtac  cdcol  behav  anbdy  antac  ancol       alert'");
  expect_line(in, "a see table line");
  SeeRec s;
  s.line = in.number();
  const char* names[] = {"cdbdy", "cdtac", "cdcol", "behav", "anbdy", "antac", "ancol"};
  std::string* fields[] = {&s.cdbdy, &s.cdtac, &s.cdcol, &s.behav, &s.anbdy, &s.antac, &s.ancol};
  for (int k = 0; k < 7; ++k) {
    *fields[k] = trim(in.column(1 + 7 * static_cast<std::size_t>(k), 5));
    if (fields[k]->empty())
      in.fail(std::string(names[k]) + " missing (columns " + std::to_string(2 + 7 * k) + "-" +
              std::to_string(6 + 7 * k) + ")");
  }
  s.alert = in.real_at(54, "alert");
  if (s.alert < 0.0) in.fail("alert must be >= 0");
  if (in.next()) {  // the optional '+' line: a second alert distance (LMGC90's global_alert)
    if (!in.line().empty() && in.line()[0] == '+') s.halo = in.real_at(54, "halo alert");
    else in.back();
  }
  return s;
}

void read_tact_behav(Lines& in, std::map<std::string, LawRec>& laws, std::vector<SeeRec>& see) {
  while (next_content(in)) {
    if (in.line()[0] != '$')
      in.fail("unexpected line '" + trim(in.line()) + "' (a '$behav' or '$seety' block was expected)");
    const std::string key = in.key();
    if (key == "behav") read_law(in, laws);
    else if (key == "seety") see.push_back(read_see(in));
    else in.fail("unknown block '$" + key + "' (TACT_BEHAV.DAT has '$behav' and '$seety')");
  }
}

// ---- DOF.INI ----------------------------------------------------------------------------

/// "$steps N time= T": the step and the time.
void read_steps_line(Lines& in, std::int64_t& step, double& time) {
  const auto t = in.tokens();
  if (t.size() != 4 || t[2] != "time=") in.fail("expected '$steps <n> time= <t>'");
  step = in.integer_at(6, in.line().find("time=") - 6, "steps");
  if (!parse_fortran_real(t[3], time)) in.fail("time: '" + t[3] + "' is not a finite number");
}

void read_dof(Lines& in, std::vector<BodyRec>& bodies, std::int64_t& step, double& time) {
  std::vector<bool> seen(bodies.size(), false);
  while (next_content(in)) {
    if (in.line()[0] != '$') in.fail("unexpected line '" + trim(in.line()) + "'");
    if (in.key() == "steps") {
      read_steps_line(in, step, time);
      continue;
    }
    if (in.key() != "bdyty") in.fail("expected '$bdyty', found '" + trim(in.line()) + "'");
    expect_line(in, "the body line");
    if (in.key() != "RBDY2") in.fail("body type '" + trim(in.column(1, 5)) + "' is not supported (RBDY2 only)");
    const auto t = in.tokens();
    if (t.size() != 2) in.fail("expected 'RBDY2 <number>'");
    const long long n = in.integer_at(6, in.line().size(), "body number");
    if (n < 1 || n > static_cast<long long>(bodies.size()))
      in.fail("body " + std::to_string(n) + " is not in BODIES.DAT (" + std::to_string(bodies.size()) + " bodies)");
    if (seen[n - 1]) in.fail("body " + std::to_string(n) + " given twice");
    seen[n - 1] = true;
    BodyRec& b = bodies[n - 1];
    expect_key(in, "nodty");
    expect_line(in, "the node's X line");
    if (in.key() != "NO3xx") in.fail("node '" + trim(in.column(1, 5)) + "' is not supported (NO3xx only)");
    for (int k = 0; k < 3; ++k) b.X[k] = in.value(kBodyGrid, k, k == 0 ? "X(1)=" : k == 1 ? "X(2)=" : "X(3)=");
    expect_line(in, "the node's V line");
    for (int k = 0; k < 3; ++k) b.V[k] = in.value(kBodyGrid, k, k == 0 ? "V(1)=" : k == 1 ? "V(2)=" : "V(3)=");
    expect_line(in, "'$$$$$$'");
    if (in.line().rfind("$$$$$$", 0) != 0) in.fail("expected '$$$$$$' after the node");
  }
}

}  // namespace
}  // namespace nscd::datbox

namespace nscd::datbox {
namespace {

/// A body given a nominal mass (an xKSID alone, avrd 0) must have its three dofs imposed, so
/// that its mass is never used, as in LMGC90 where it is 0.
void check_nominal_masses(const Parsed& p, const std::filesystem::path& file, Datbox& d) {
  for (std::size_t i = 0; i < p.bodies.size(); ++i) {
    if (!p.bodies[i].nominal_mass) continue;
    const BodyId b(static_cast<std::uint32_t>(i));
    for (Dof dof : {Dof::X, Dof::Y, Dof::Rot})
      if (drive_of(d.reg, b, dof) != Drive::Fixed && drive_of(d.reg, b, dof) != Drive::Velocity)
        fail_at(file, p.bodies[i].behav_line,
                "avrd or gyrd is 0 and the contactors give no mass (an xKSID alone): "
                "nscd takes it only when DRV_DOF.DAT imposes the velocity of its three dofs");
    d.notes.push_back(
        "RBDY2 " + std::to_string(i + 1) +
        ": avrd 0 (an xKSID alone), every dof driven: given the mass of a disk of its radius, never used");
  }
}

}  // namespace
}  // namespace nscd::datbox

namespace nscd {

Datbox read_datbox(const std::filesystem::path& dir) {
  using namespace datbox;
  Lines bulk_in(dir / "BULK_BEHAV.DAT", true), bodies_in(dir / "BODIES.DAT", true),
      tact_in(dir / "TACT_BEHAV.DAT", true);
  Lines dof_in(dir / "DOF.INI", false);
  Parsed p;
  read_bulk(bulk_in, p.gravity, p.behavs);
  p.bodies = read_bodies(bodies_in);
  read_tact_behav(tact_in, p.laws, p.see);
  Datbox d;
  if (dof_in.exists()) read_dof(dof_in, p.bodies, d.step, d.reg.time);
  d.reg.step = d.step;
  build_registry(p, bodies_in.file(), tact_in.file(), d);
  read_drives(dir, d);
  check_nominal_masses(p, bodies_in.file(), d);
  read_contacts(dir, p, d);
  return d;
}

}  // namespace nscd
