// nscd/io/datbox_writer.cpp — Registry → a DATBOX folder LMGC90 reads (datbox.hpp).
//
// Layouts as pylmgc90's writers give them (pylmgc90/pre/IO/bodies2File.py, bulkBehav2File.py,
// tactBehav2File.py, drvDof2File.py, dofIni2File.py, vlocrlocIni2File.py) and LMGC90's FORMAT
// statements (mod_a_BDARY_*.f90: 1X,A5,2X,I5,2X,A5,2X,A5,2X,A5,D14.7; mod_tact_behav.f90's see
// line 1X,A5,(2X,A5)×6,6X,D14.7; mod_DKDKx.f90's contact line).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

#include "nscd/contactors/contactor_row.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/atomic_file.hpp"
#include "nscd/io/datbox_format.hpp"
#include "nscd/io/datbox_internal.hpp"
#include "nscd/laws/contact_laws.hpp"
#include "nscd/laws/material_pairs.hpp"

namespace nscd::datbox {
namespace {

std::string e14l(double v) {  // the lower-case exponent pylmgc90 writes outside BODIES.DAT
  std::string s = e14(v);
  for (char& c : s)
    if (c == 'E') c = 'e';
  return s;
}

std::string fmt(const char* f, auto... a) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a...);
  return buf;
}

/// behav and colour of each material: "behav:colour" split, else generated names.
struct Names {
  std::vector<std::string> behav, colour;
};

Names material_names(const Registry& reg) {
  Names n;
  for (std::size_t m = 0; m < reg.materials.size(); ++m) {
    const std::string& s = reg.materials.name[m];
    const auto colon = s.find(':');
    const bool split = colon != std::string::npos && colon >= 1 && colon <= 5 && s.size() - colon - 1 <= 5 &&
                       s.find(' ') == std::string::npos && s.find(':', colon + 1) == std::string::npos;
    n.behav.push_back(split ? s.substr(0, colon) : fmt("M%04zu", m + 1));
    n.colour.push_back(split && s.size() > colon + 1 ? s.substr(colon + 1) : fmt("C%04zu", m + 1));
  }
  return n;
}

void write_bodies(std::ostream& o, const Registry& reg, const Names& names,
                  const std::vector<std::vector<ContactorId>>& tacts) {
  const BodyTable& b = reg.bodies;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const std::size_t m = b.material[i].index();
    if (!b.material[i].valid() || m >= reg.materials.size())
      throw Error("write_datbox: body " + std::to_string(i + 1) + " has no material");
    const double rho = reg.materials.density[m];
    const double avrd = std::sqrt(b.mass[i] / (rho * std::numbers::pi)), gyrd = std::sqrt(b.inertia[i] / b.mass[i]);
    const std::string colour = name5(names.colour[m], "colour");
    o << "$bdyty\n" << fmt(" RBDY2%7zu\n", i + 1) << "$blmty\n";
    o << " PLAIN      1  behav  " << name5(names.behav[m], "bulk behaviour") << "  avrd=" << e14(avrd)
      << "  gyrd=" << e14(gyrd) << "\n";
    o << "$nodty\n"
      << " NO3xx      1                coo1=" << e14(b.x0[i]) << "  coo2=" << e14(b.y0[i])
      << "  coo3=" << e14(b.angle0[i]) << "  \n";
    o << "$tacty                                                                  \n";
    for (std::size_t k = 0; k < tacts[i].size(); ++k) {
      const ContactorId c = tacts[i][k];
      const std::uint32_t r = contactor_index(c);
      const ContactorKind kind = contactor_kind(c);
      o << " " << name_of(kind) << fmt("  %5zu", k + 1) << "  color  " << colour;
      switch (kind) {
        case ContactorKind::DISKx:
          if (reg.diskx.offset[r].x != 0.0 || reg.diskx.offset[r].y != 0.0)
            throw Error("write_datbox: an off-centre DISKx (LMGC90's DISKb) is not written");
          o << "  byrd=" << e14(reg.diskx.radius[r]) << "\n";
          break;
        case ContactorKind::xKSID:
          if (reg.xksid.offset[r].x != 0.0 || reg.xksid.offset[r].y != 0.0)
            throw Error("write_datbox: an off-centre xKSID is not written");
          o << "  byrd=" << e14(reg.xksid.radius[r]) << "\n";
          break;
        case ContactorKind::JONCx:
          if (reg.joncx.offset[r].x != 0.0 || reg.joncx.offset[r].y != 0.0 || reg.joncx.axis[r].x != 1.0 ||
              reg.joncx.axis[r].y != 0.0)
            throw Error(
                "write_datbox: a JONCx off the body's centre or x axis is not written (LMGC90's JONCx lies on them)");
          o << "  axe1=" << e14(reg.joncx.half_length[r]) << "  axe2=" << e14(reg.joncx.half_thickness[r]) << "\n";
          break;
        case ContactorKind::PT2Dx:
          o << "  coo1=" << e14(reg.points.point[r].x) << "  coo2=" << e14(reg.points.point[r].y) << "\n";
          break;
        case ContactorKind::POLYG: {
          const std::uint32_t first = reg.polyg.first_vertex[r], n = reg.polyg.vertex_count[r];
          o << fmt("  nb_vertex=%7u\n", n);
          for (std::uint32_t v = first; v < first + n; ++v)
            o << std::string(27, ' ') << "  coo1=" << e14(reg.polyg.vertex[v].x)
              << "  coo2=" << e14(reg.polyg.vertex[v].y) << "\n";
          break;
        }
      }
    }
    o << "$$$$$$\n";
  }
}

void write_bulk(std::ostream& o, const Registry& reg, const Names& names) {
  o << "\n! File BEHAVIOUR (written by nscd)\n\n$gravy  \n";
  o << "                   grv1=" << e14l(reg.params.gravity.x) << "  grv2=" << e14l(reg.params.gravity.y)
    << "  grv3=" << e14l(0.0) << "\n";
  std::map<std::string, double> density;
  for (std::size_t m = 0; m < reg.materials.size(); ++m) {
    const auto [it, fresh] = density.emplace(names.behav[m], reg.materials.density[m]);
    if (!fresh && it->second != reg.materials.density[m])
      throw Error("write_datbox: bulk behaviour '" + names.behav[m] + "' would have two densities");
    if (!fresh) continue;
    o << "$behav  lawty\n " << name5(names.behav[m], "bulk behaviour") << "  " << fmt("%-30s", "RIGID")
      << "  Umas=" << e14l(reg.materials.density[m]) << "\n";
  }
  o << "      \n";
}

std::string law_name(const DatboxExtras& x, const Registry& reg, std::size_t k) {
  if (x.law_name && x.law_name->size() == reg.contact_laws.laws.size()) return (*x.law_name)[k];
  const ContactLawRow* row = contact_law_row(reg.contact_laws.laws[k].kind);
  if (!row) throw Error("write_datbox: VOIGT_ROD as a contact law is not written");
  return fmt("%s%02zu", std::string(row->datbox_tag).c_str(), k + 1);
}

void write_tact(std::ostream& o, const Registry& reg, const Names& names, const DatboxExtras& x) {
  const auto& t = reg.contact_laws;
  // the law of each pair of colours, from the law of each pair of materials
  std::map<std::pair<std::string, std::string>, std::int32_t> by_colours;
  for (std::size_t a = 0; a < reg.materials.size(); ++a)
    for (std::size_t b = a; b < reg.materials.size(); ++b) {
      const std::int32_t k =
          contact_law_index(reg, MaterialId(static_cast<std::uint32_t>(a)), MaterialId(static_cast<std::uint32_t>(b)));
      if (k < 0) continue;
      const auto key = std::minmax(names.colour[a], names.colour[b]);
      const auto [it, fresh] = by_colours.emplace(key, k);
      if (!fresh && !(t.laws[it->second].kind == t.laws[k].kind && t.laws[it->second].mu == t.laws[k].mu &&
                      t.laws[it->second].e_n == t.laws[k].e_n && t.laws[it->second].e_t == t.laws[k].e_t))
        throw Error("write_datbox: colours (" + key.first + ", " + key.second + ") would need two laws");
    }
  std::set<std::int32_t> used;
  for (const auto& e : by_colours) used.insert(e.second);
  o << "\n";
  for (std::int32_t k : used) {
    const LawSpec& l = t.laws[k];
    if (l.kind == LawKind::VOIGT_ROD) throw Error("write_datbox: VOIGT_ROD as a contact law is not written");
    const std::string head = " " + name5(law_name(x, reg, k), "contact law") + "  " +
                             fmt("%-30s", std::string(name_of(l.kind)).c_str()) + "  ";
    if (contact_law_row(l.kind)->restitution)
      o << "$behav \n"
        << head << "rstn=" << e14l(l.e_n) << "  rstt=" << e14l(l.e_t) << "\n"
        << std::string(40, ' ') << "fric=" << e14l(l.mu) << "\n      \n";
    else o << "$behav \n" << head << "fric=" << e14l(l.mu) << "\n      \n";
  }
  // one see entry per LMGC90 interaction the colours' contactors can have
  std::map<std::string, std::set<ContactorKind>> kinds;
  const auto by_body = contactors_by_body(reg);
  for (std::size_t b = 0; b < by_body.size(); ++b)
    for (ContactorId c : by_body[b]) kinds[names.colour[reg.bodies.material[b].index()]].insert(contactor_kind(c));
  const ContactorKind order[] = {ContactorKind::DISKx, ContactorKind::POLYG, ContactorKind::JONCx,
                                 ContactorKind::xKSID};
  for (const auto& [key, k] : by_colours)
    for (int flip = 0; flip < (key.first == key.second ? 1 : 2); ++flip) {
      const std::string& cdcol = flip ? key.second : key.first;
      const std::string& ancol = flip ? key.first : key.second;
      for (ContactorKind cd : order)
        for (ContactorKind an : order) {
          if (interaction_name(cd, an).empty() || !kinds[cdcol].count(cd) || !kinds[ancol].count(an)) continue;
          o << "$seety\n cdbdy  cdtac  cdcol  behav  anbdy  antac  ancol       alert\n";
          o << " RBDY2  " << name_of(cd) << "  " << name5(cdcol, "colour") << "  "
            << name5(law_name(x, reg, k), "contact law") << "  RBDY2  " << name_of(an) << "  " << name5(ancol, "colour")
            << "      " << e14l(reg.params.alert) << "\n      \n";
        }
    }
}

}  // namespace
}  // namespace nscd::datbox

namespace nscd::datbox {
namespace {

/// The DatboxDrive of a driven dof: the extras' own, or one made from its TimeFunction.
DatboxDrive drive_of(const DofDrive& dd, const DatboxExtras& x, const Registry& reg) {
  if (x.drives) {
    const auto it = x.drives->find({dd.body.index(), static_cast<std::uint8_t>(dd.dof)});
    if (it != x.drives->end()) return it->second;
  }
  DatboxDrive d;  // Fixed: vlocy 0, RAMPI 1
  if (dd.drive == Drive::Fixed) return d;
  const TimeFunction& f = dd.value;
  const std::string who = "body " + reg.bodies.name[dd.body.index()];
  switch (f.kind()) {
    case TimeFunction::Kind::Constant:
      d.ct = f.A();
      return d;
    case TimeFunction::Kind::Cosine:
      if (f.start() != 0.0)
        throw Error("write_datbox: " + who + ": a cosine drive that starts at t0 > 0 has no DRV_DOF form");
      d.ct = f.A();
      d.amp = f.B();
      d.omega = 2.0 * std::numbers::pi * f.frequency();
      d.phi = -f.phase();
      if (f.ramp_duration() > 0.0) {
        d.rampi = 0.0;
        d.ramp = 1.0 / f.ramp_duration();
      }
      return d;
    case TimeFunction::Kind::Lambda:
      break;
  }
  throw Error("write_datbox: " + who +
              ": its drive is a user lambda; a DATBOX needs a DRV_DOF formula or an evolution file");
}

void write_drives(std::ostream& o, const std::filesystem::path& dir, const Registry& reg, const DatboxExtras& x) {
  std::vector<const DofDrive*> drives;
  for (const DofDrive& d : reg.bodies.drives)
    if (d.drive != Drive::Free) drives.push_back(&d);
  std::stable_sort(drives.begin(), drives.end(), [](const DofDrive* a, const DofDrive* b) {
    return a->body.index() != b->body.index() ? a->body.index() < b->body.index() : a->dof < b->dof;
  });
  o << "! DOF\n";
  for (std::size_t i = 0; i < drives.size(); ++i) {
    const std::uint32_t b = drives[i]->body.index();
    if (i == 0 || drives[i - 1]->body.index() != b)
      o << "$bdyty\n" << fmt(" RBDY2%7u\n", b + 1) << "$nodty\n NO3xx      1\n"
        << "$dofty  numbr [CT......+......AMP..*..cos.(..OMEGA.*.time.+.PHI..)]...*...[RAMPI.....+.....RAMP.*.time]\n";
    const DatboxDrive d = drive_of(*drives[i], x, reg);
    const char* kind = drives[i]->drive == Drive::Force ? "force" : "vlocy";
    const int dof = static_cast<int>(drives[i]->dof) + 1;
    if (d.evolution) {
      o << fmt(" %5s  %5d evolution %s\n", kind, dof, d.file.c_str());
      std::ostringstream e;
      for (std::size_t k = 0; k < d.t.size(); ++k) e << e14(d.t[k]) << " " << e14(d.value[k]) << "\n";
      atomic_write(dir / d.file, e.str());
    } else {
      o << fmt(" %5s  %5d", kind, dof);
      for (double v : {d.ct, d.amp, d.omega, d.phi, d.rampi, d.ramp}) o << " " << e14l(v);
      o << "\n";
    }
    if (i + 1 == drives.size() || drives[i + 1]->body.index() != b) o << "$$$$$$\n\n";
  }
  o << "      \n";
}

std::string steps_line(const Registry& reg, std::int64_t step) {
  std::string t = e14(reg.time);
  for (char& c : t)
    if (c == 'E') c = 'D';
  return fmt("$steps%7lld                time=", static_cast<long long>(step)) + t + "\n";
}

void write_dof(std::ostream& o, const Registry& reg, std::int64_t step) {
  const BodyTable& b = reg.bodies;
  o << "\n! DOF\n\n"
    << steps_line(reg, step) << "\n!-----------------------------------------------------------------------\n";
  for (std::size_t i = 0; i < b.size(); ++i) {
    o << "$bdyty\n" << fmt(" RBDY2  %7zu\n", i + 1) << "$nodty\n";
    o << " NO3xx      1                X(1)=" << e14l(b.x[i] - b.x0[i]) << "  X(2)=" << e14l(b.y[i] - b.y0[i])
      << "  X(3)=" << e14l(b.angle[i] - b.angle0[i]) << "\n";
    o << std::string(29, ' ') << "V(1)=" << e14l(b.vx[i]) << "  V(2)=" << e14l(b.vy[i]) << "  V(3)=" << e14l(b.spin[i])
      << "\n";
    o << "$$$$$$\n      \n";
  }
  o << "!-----------------------------------------------------------------------\n      \n";
}

void write_contacts(std::ostream& o, const Registry& reg, const std::vector<DatboxContact>& cs,
                    const std::set<std::string>& gap_laws, std::int64_t step) {
  o << "\n! Vloc_Rloc\n\n"
    << steps_line(reg, step) << "\n!-----------------------------------------------------------------------\n";
  const auto by_body = contactors_by_body(reg);
  std::map<std::uint32_t, std::pair<int, int>> number;  // ContactorId → (body, rank), 1-based
  for (std::size_t b = 0; b < by_body.size(); ++b)
    for (std::size_t k = 0; k < by_body[b].size(); ++k)
      number[by_body[b][k].value] = {static_cast<int>(b + 1), static_cast<int>(k + 1)};
  std::map<std::string, int> count;
  for (const DatboxContact& c : cs) {
    const auto cd = number.at(c.cd.value), an = number.at(c.an.value);
    const std::string cdk(name_of(contactor_kind(c.cd))), ank(name_of(contactor_kind(c.an)));
    const std::string behav = name5(c.behav, "contact law"), status = name5(c.status, "status");
    o << fmt("$icdan  %5s%9d\n", c.type.c_str(), ++count[c.type]);
    if (c.type == "PLPLx") {
      o << " cdbdy  numbr  cdtac  numbr  vertx  numbr  behav  anbdy  numbr  antac  numbr  segmt  numbr\n";
      o << fmt(" RBDY2  %5d  %5s  %5d  CDVER  %5d  %5s  RBDY2  %5d  %5s  %5d  ANSEG  %5d  %5s %5d\n", cd.first,
               cdk.c_str(), cd.second, c.cd_vertex, behav.c_str(), an.first, ank.c_str(), an.second, c.an_segment,
               status.c_str(), 0);
    } else if (c.type == "PLJCx") {
      o << " cdbdy  numbr  cdtac  numbr  vertx  numbr  behav  anbdy  numbr  antac  numbr                sttus iadj \n";
      o << fmt(" RBDY2  %5d  %5s  %5d  CDVER  %5d  %5s  RBDY2  %5d  %5s  %5d  %5s\n", cd.first, cdk.c_str(), cd.second,
               c.cd_vertex, behav.c_str(), an.first, ank.c_str(), an.second, status.c_str());
    } else if (c.type == "DKPLx") {
      o << " cdbdy  numbr  cdtac  numbr  behav  anbdy  numbr  antac  numbr  vertx  numbr                sttus iadj \n";
      o << fmt(" RBDY2  %5d  %5s  %5d  %5s  RBDY2  %5d  %5s  %5d  CDVER  %5d%16s%5s %5d\n", cd.first, cdk.c_str(),
               cd.second, behav.c_str(), an.first, ank.c_str(), an.second, c.an_segment, "", status.c_str(), 0);
    } else {
      o << " cdbdy  numbr  cdtac  numbr  behav  anbdy  numbr  antac  numbr  sttus   iadj\n";
      o << fmt(" RBDY2  %5d  %5s  %5d  %5s  RBDY2  %5d  %5s  %5d  %5s  %5d\n", cd.first, cdk.c_str(), cd.second,
               behav.c_str(), an.first, ank.c_str(), an.second, status.c_str(), 0);
    }
    const std::string pad(27, ' ');
    o << pad << "  rlt/H" << e14(c.rlt) << "  rln/H" << e14(c.rln) << "\n";
    o << pad << "  vlt =" << e14(c.vlt) << "  vln =" << e14(c.vln) << "\n";
    o << pad << "  gapTT" << e14(c.gap) << "\n";
    o << pad << "  n(1)=" << e14(c.normal.x) << "  n(2)=" << e14(c.normal.y) << "\n";
    o << pad << "  coo1=" << e14(c.point.x) << "  coo2=" << e14(c.point.y) << "\n";
    // LMGC90 reads one more line for a law with an internal variable, or it reads the next record
    if (gap_laws.count(behav) != 0) o << "#taille_ele\n" << " " << e14(c.internal) << "\n";
    o << "\n";
  }
  o << "      \n";
}

}  // namespace
}  // namespace nscd::datbox

namespace nscd {

std::vector<DatboxContact> datbox_contacts(const Registry& reg) {
  const ContactTable& t = reg.contacts;
  std::vector<DatboxContact> out;
  const char* status[] = {"noctc", "stick", "slifw", "slibw"};
  for (std::size_t i = 0; i < t.size(); ++i) {
    DatboxContact c;
    c.cd = t.candidate[i];
    c.an = t.antagonist[i];
    c.normal = t.normal[i];
    c.type = datbox::interaction_name(contactor_kind(c.cd), contactor_kind(c.an));
    if (c.type.empty()) {  // LMGC90 has the pair the other way round: the same forces, n reversed
      std::swap(c.cd, c.an);
      c.normal = {-c.normal.x, -c.normal.y};
      c.type = datbox::interaction_name(contactor_kind(c.cd), contactor_kind(c.an));
    }
    if (c.type.empty()) continue;
    if (c.type == "PLPLx" || c.type == "PLJCx") c.cd_vertex = 1;  // nscd's feature ids are not LMGC90's numbers
    if (c.type == "PLPLx" || c.type == "DKPLx") c.an_segment = 1;
    c.rln = t.rn[i];
    c.rlt = t.rt[i];
    c.gap = t.gap[i];
    c.point = t.point[i];
    c.status = status[static_cast<int>(t.status[i]) & 3];
    out.push_back(c);  // behav: write_datbox names the law of the contact's materials
  }
  return out;
}

void write_datbox(const std::filesystem::path& dir, const Registry& reg, const DatboxExtras& x) {
  using namespace datbox;
  if (!reg.links.empty()) throw Error("write_datbox: PTPT2 spring links are not written to a DATBOX");
  for (const ContactorKindRow* row : reg.added.row)
    throw Error("write_datbox: the scene's own contactor kind " + std::string(row->name) + " has no DATBOX form");
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error("write_datbox: cannot create '" + dir.string() + "': " + ec.message());
  const Names names = material_names(reg);
  const auto tacts = contactors_by_body(reg);
  std::ostringstream bodies, bulk, tact, drv, dof, vloc;
  write_bodies(bodies, reg, names, tacts);
  write_bulk(bulk, reg, names);
  write_tact(tact, reg, names, x);
  write_drives(drv, dir, reg, x);
  write_dof(dof, reg, x.step);
  std::vector<DatboxContact> contacts = x.contacts ? *x.contacts : datbox_contacts(reg);
  for (DatboxContact& c : contacts) {  // a contact without its law's name: the law of its materials
    if (!c.behav.empty()) continue;
    const auto body = [&](ContactorId id) {
      return kind_row(reg, contactor_kind_bits(id))->body(reg, contactor_index(id));
    };
    const std::int32_t k =
        contact_law_index(reg, reg.bodies.material[body(c.cd).index()], reg.bodies.material[body(c.an).index()]);
    c.behav = k >= 0 ? law_name(x, reg, static_cast<std::size_t>(k)) : "-----";
  }
  std::set<std::string> gap_laws;
  for (std::size_t k = 0; k < reg.contact_laws.laws.size(); ++k)
    if (reg.contact_laws.laws[k].kind == LawKind::GAP_SGR_CLB)
      gap_laws.insert(name5(law_name(x, reg, k), "contact law"));
  write_contacts(vloc, reg, contacts, gap_laws, x.step);
  atomic_write(dir / "BODIES.DAT", bodies.str());
  atomic_write(dir / "BULK_BEHAV.DAT", bulk.str());
  atomic_write(dir / "TACT_BEHAV.DAT", tact.str());
  atomic_write(dir / "DRV_DOF.DAT", drv.str());
  atomic_write(dir / "DOF.INI", dof.str());
  atomic_write(dir / "Vloc_Rloc.INI", vloc.str());
}

}  // namespace nscd
