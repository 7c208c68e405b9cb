// nscd/io/datbox_drives.cpp — DRV_DOF.DAT (imposed velocities and forces, evolution files) and
// Vloc_Rloc.INI (contact impulses) of a DATBOX (datbox.hpp).
//
// A driven dof's value is LMGC90's (mod_a_DOF.f90, comp_a_driven_dof_at_t):
//   [CT + AMP cos(OMEGA t + PHI)] · min(1, RAMPI + RAMP t),
// or an evolution file's table, interpolated linearly (held at its end values outside it).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/datbox_format.hpp"
#include "nscd/io/datbox_internal.hpp"
#include "nscd/io/text_reader.hpp"

namespace nscd {

double DatboxDrive::operator()(double time) const {
  if (!evolution) return (ct + amp * std::cos(omega * time + phi)) * std::min(1.0, rampi + ramp * time);
  if (t.empty()) return 0.0;
  if (time <= t.front()) return value.front();
  if (time >= t.back()) return value.back();
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), time) - t.begin());
  const double s = (time - t[k - 1]) / (t[k] - t[k - 1]);
  return value[k - 1] + s * (value[k] - value[k - 1]);
}

}  // namespace nscd

namespace nscd::datbox {
namespace {

std::string trimmed(std::string_view s) {
  const auto a = s.find_first_not_of(' ');
  if (a == std::string_view::npos) return {};
  return std::string(s.substr(a, s.find_last_not_of(' ') - a + 1));
}

bool blank_or_comment(const std::string& l) {
  return l.find_first_not_of(' ') == std::string::npos || l[0] == '!' || l[0] == '#';
}

void read_evolution(const std::filesystem::path& dir, DatboxDrive& d, const Lines& at) {
  if (d.file.empty() || d.file.find('/') != std::string::npos || d.file.find("..") != std::string::npos)
    at.fail("evolution file name '" + d.file + "' must be a plain file name in the DATBOX folder");
  Lines in(dir / d.file, false);
  if (!in.exists()) at.fail("evolution file '" + d.file + "' cannot be read (missing?)");
  while (in.next()) {
    if (blank_or_comment(in.line())) continue;
    const auto tok = in.tokens();
    double t = 0.0, v = 0.0;
    if (tok.size() != 2 || !parse_fortran_real(tok[0], t) || !parse_fortran_real(tok[1], v))
      in.fail("expected two numbers 't f(t)'");
    if (!d.t.empty() && !(t > d.t.back())) in.fail("times must increase");
    d.t.push_back(t);
    d.value.push_back(v);
  }
  if (d.t.empty()) throw Error("DATBOX file '" + in.file().string() + "': no 't f(t)' line");
}

/// One ' vlocy  N …' or ' force  N …' line of body `b`.
void read_drive_line(const std::filesystem::path& dir, Lines& in, BodyId b, Datbox& d) {
  const std::string kind = in.key();
  if (kind != "vlocy" && kind != "force")
    in.fail("unknown driven dof '" + trimmed(in.column(1, 5)) + "' (vlocy or force)");
  const long long dof = in.integer_at(6, 7, "dof number");
  if (dof < 1 || dof > 3) in.fail("dof number must be 1, 2 or 3 (NO3xx), got " + std::to_string(dof));
  DatboxDrive drv;
  if (trimmed(in.column(13, 11)) == "evolution") {
    drv.evolution = true;
    drv.file = trimmed(in.column(24, std::string::npos));
    read_evolution(dir, drv, in);
  } else {
    double* c[] = {&drv.ct, &drv.amp, &drv.omega, &drv.phi, &drv.rampi, &drv.ramp};
    const char* names[] = {"CT", "AMP", "OMEGA", "PHI", "RAMPI", "RAMP"};
    for (int k = 0; k < 6; ++k) *c[k] = in.real_at(14 + 15 * static_cast<std::size_t>(k), names[k]);
  }
  const Dof which = static_cast<Dof>(dof - 1);
  const bool constant = !drv.evolution && drv.amp == 0.0 && drv.rampi >= 1.0 && drv.ramp >= 0.0;
  if (kind == "vlocy" && constant && drv.ct == 0.0) {
    fix_dof(d.reg, b, which);  // LMGC90's way to fix a dof: vlocy 0
    return;
  }
  const TimeFunction f = constant ? TimeFunction::constant(drv.ct) : TimeFunction::lambda(drv);
  if (kind == "vlocy") impose_velocity(d.reg, b, which, f);
  else impose_force(d.reg, b, which, f);
  d.drives[{b.index(), static_cast<std::uint8_t>(which)}] = std::move(drv);
}

void expect(Lines& in, const char* what) {
  if (!in.next()) throw Error(in.where() + ": the file ends where " + std::string(what) + " was expected (truncated?)");
}

}  // namespace

void read_drives(const std::filesystem::path& dir, Datbox& d) {
  Lines in(dir / "DRV_DOF.DAT", false);
  if (!in.exists()) return;
  while (in.next()) {
    if (blank_or_comment(in.line())) continue;
    if (in.line()[0] != '$' || in.key() != "bdyty") in.fail("expected '$bdyty', found '" + trimmed(in.line()) + "'");
    expect(in, "the body line");
    if (in.key() != "RBDY2") in.fail("body type '" + trimmed(in.column(1, 5)) + "' is not supported (RBDY2 only)");
    const long long n = in.integer_at(6, std::string::npos, "body number");
    if (n < 1 || n > static_cast<long long>(d.reg.bodies.size()))
      in.fail("body " + std::to_string(n) + " is not in BODIES.DAT (" + std::to_string(d.reg.bodies.size()) +
              " bodies)");
    const BodyId b(static_cast<std::uint32_t>(n - 1));
    expect(in, "'$nodty'");
    if (in.line()[0] != '$' || in.key() != "nodty") in.fail("expected '$nodty'");
    expect(in, "the node line");
    if (in.key() != "NO3xx") in.fail("node '" + trimmed(in.column(1, 5)) + "' is not supported (NO3xx only)");
    expect(in, "'$dofty'");
    if (in.line()[0] != '$' || in.key() != "dofty") in.fail("expected '$dofty'");
    while (true) {
      expect(in, "a driven dof or '$$$$$$'");
      if (in.line().rfind("$$$$$$", 0) == 0) break;
      read_drive_line(dir, in, b, d);
    }
  }
}

namespace {

/// The contactor `tact` (1-based) of body `body` (1-based), of kind `kind`.
ContactorId resolve(const Lines& in, const Parsed& p, const std::string& bdy, const std::string& body,
                    const std::string& kind, const std::string& tact) {
  if (bdy != "RBDY2") in.fail("body type '" + bdy + "' is not supported (RBDY2 only)");
  long long b = 0, t = 0;
  try {
    b = parse_integer(body, "body number", 1, static_cast<long long>(p.tact_ids.size()));
    t = parse_integer(tact, "contactor number", 1, static_cast<long long>(p.tact_ids[b - 1].size()));
  } catch (const Error& e) {
    in.fail(e.what());
  }
  const ContactorId c = p.tact_ids[b - 1][t - 1];
  if (name_of(contactor_kind(c)) != kind)
    in.fail("contactor " + tact + " of RBDY2 " + body + " is a " + std::string(name_of(contactor_kind(c))) +
            ", not a " + kind);
  return c;
}

void read_contact_numbers(Lines& in, const Parsed& p, DatboxContact& c) {
  std::vector<std::string> t = in.tokens();
  for (const char* marker : {"CDVER", "ANSEG"}) {  // "CDVER n", "ANSEG n": the polygons' vertex and segment
    const auto it = std::find(t.begin(), t.end(), marker);
    if (it == t.end()) continue;
    if (it + 1 == t.end()) in.fail(std::string(marker) + " without its number");
    int& target = (std::string(marker) == "CDVER" && c.type != "DKPLx") ? c.cd_vertex : c.an_segment;
    try {
      target = static_cast<int>(parse_integer(*(it + 1), marker, 0, 1'000'000));
    } catch (const Error& e) {
      in.fail(e.what());
    }
    t.erase(it, it + 2);
  }
  if (t.size() < 10 || t.size() > 11) in.fail("expected 'cdbdy n cdtac n behav anbdy n antac n status [iadj]'");
  const std::string cd_kind = c.type.substr(0, 2) == "DK" ? "DISKx" : "POLYG";
  const std::string an2 = c.type.substr(2, 2);
  const std::string an_kind = an2 == "DK" ? "DISKx" : an2 == "JC" ? "JONCx" : an2 == "KD" ? "xKSID" : "POLYG";
  c.cd = resolve(in, p, t[0], t[1], cd_kind, t[3]);
  if (t[2] != cd_kind) in.fail(c.type + " needs a " + cd_kind + " candidate, got " + t[2]);
  c.behav = t[4];
  if (t[7] != an_kind) in.fail(c.type + " needs a " + an_kind + " antagonist, got " + t[7]);
  c.an = resolve(in, p, t[5], t[6], an_kind, t[8]);
  c.status = t[9];
}

/// GAP_SGR_CLB's internal variable: LMGC90 writes a '#' comment naming it, then the value
/// (1X,D14.7), and reads the first line that is not a comment.
double read_internal(Lines& in) {
  do expect(in, "the internal variable line of a GAP_SGR_CLB contact");
  while (in.line().starts_with("#") || in.line().starts_with("!"));
  double v = 0.0;
  const std::string field = in.line().substr(0, std::min<std::size_t>(15, in.line().size()));
  if (!parse_fortran_real(trimmed(field), v) || !std::isfinite(v))
    in.fail("expected the GAP_SGR_CLB internal variable (1X,D14.7), got '" + trimmed(in.line()) + "'");
  return v;
}

void read_contact(Lines& in, const Parsed& p, Datbox& d) {
  DatboxContact c;
  c.type = trimmed(in.column(8, 5));
  if (c.type != "DKDKx" && c.type != "DKJCx" && c.type != "DKKDx" && c.type != "DKPLx" && c.type != "PLJCx" &&
      c.type != "PLPLx")
    in.fail("interaction '" + c.type + "' is not supported (DKDKx, DKJCx, DKKDx, DKPLx, PLJCx, PLPLx)");
  expect(in, "the header line");
  if (in.line().find("cdbdy") == std::string::npos) in.fail("expected the header line ' cdbdy  numbr  …'");
  expect(in, "the contact line");
  read_contact_numbers(in, p, c);
  expect(in, "the rl line");
  c.rlt = in.value(kBodyGrid, 0, "rlt/H");
  c.rln = in.value(kBodyGrid, 1, "rln/H");
  expect(in, "the vl line");
  c.vlt = in.value(kBodyGrid, 0, "vlt =");
  c.vln = in.value(kBodyGrid, 1, "vln =");
  expect(in, "the gap line");
  c.gap = in.value(kBodyGrid, 0, "gapTT");
  expect(in, "the normal line");
  c.normal = {in.value(kBodyGrid, 0, "n(1)="), in.value(kBodyGrid, 1, "n(2)=")};
  expect(in, "the point line");
  c.point = {in.value(kBodyGrid, 0, "coo1="), in.value(kBodyGrid, 1, "coo2=")};
  const auto law = p.laws.find(c.behav);
  if (law != p.laws.end() && law->second.law == "GAP_SGR_CLB") c.internal = read_internal(in);
  d.contacts.push_back(std::move(c));
}

}  // namespace

void read_contacts(const std::filesystem::path& dir, const Parsed& p, Datbox& d) {
  Lines in(dir / "Vloc_Rloc.INI", false);
  if (!in.exists()) return;
  while (in.next()) {
    if (blank_or_comment(in.line())) continue;
    if (in.line()[0] != '$') in.fail("unexpected line '" + trimmed(in.line()) + "' (internal variables are not read)");
    if (in.key() == "steps") continue;
    if (in.key() != "icdan") in.fail("expected '$icdan', found '" + trimmed(in.line()) + "'");
    read_contact(in, p, d);
  }
}

}  // namespace nscd::datbox
