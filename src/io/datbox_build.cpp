// nscd/io/datbox_build.cpp — a parsed DATBOX → the Registry (datbox.hpp): materials per
// (bulk behaviour, colour), bodies with LMGC90's masses (Umas π avrd², mass · gyrd²), their
// contactors, and the see table as the law of each pair of materials.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/contactor_kind.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/contactors/pt2dx.hpp"
#include "nscd/contactors/round_shapes.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/datbox_internal.hpp"
#include "nscd/io/text_reader.hpp"
#include "nscd/laws/material_pairs.hpp"

namespace nscd::datbox {

void fail_at(const std::filesystem::path& file, std::size_t line, const std::string& what) {
  throw Error("DATBOX file '" + file.string() + "', line " + std::to_string(line) + ": " + what);
}

std::string interaction_name(ContactorKind cd, ContactorKind an) {
  using K = ContactorKind;
  if (cd == K::DISKx && an == K::DISKx) return "DKDKx";
  if (cd == K::DISKx && an == K::JONCx) return "DKJCx";
  if (cd == K::DISKx && an == K::xKSID) return "DKKDx";
  if (cd == K::DISKx && an == K::POLYG) return "DKPLx";
  if (cd == K::POLYG && an == K::POLYG) return "PLPLx";
  if (cd == K::POLYG && an == K::JONCx) return "PLJCx";
  return "";
}

namespace {

/// The material of body b: "behav:colour", created on first use.
MaterialId material_of(const Parsed& p, const BodyRec& b, const std::filesystem::path& file, Registry& reg,
                       std::map<std::string, MaterialId>& ids) {
  std::string colour;
  for (const TactRec& t : b.tacts) {
    if (colour.empty()) colour = t.colour;
    else if (t.colour != colour)
      fail_at(file, t.line,
              "a contactor of colour '" + t.colour + "' on a body whose first contactor has colour '" + colour +
                  "': nscd gives a body one colour (its material)");
  }
  const auto it = p.behavs.find(b.behav);
  if (it == p.behavs.end()) fail_at(file, b.behav_line, "bulk behaviour '" + b.behav + "' is not in BULK_BEHAV.DAT");
  if (it->second.law != "RIGID")
    fail_at(file, b.behav_line,
            "bulk behaviour '" + b.behav + "' has law " + it->second.law + " (BULK_BEHAV.DAT line " +
                std::to_string(it->second.line) + "): an RBDY2 needs RIGID");
  const std::string name = b.behav + ":" + colour;
  const auto m = ids.find(name);
  if (m != ids.end()) return m->second;
  try {
    return ids[name] = add_material(reg, name, it->second.density);
  } catch (const Error& e) {
    fail_at(file, b.behav_line, e.what());
  }
}

ContactorId attach(Registry& reg, BodyId body, const TactRec& t) {
  if (t.kind == "DISKx") return make_contactor(ContactorKind::DISKx, attach_diskx(reg, body, {}, t.a).index());
  if (t.kind == "xKSID") return make_contactor(ContactorKind::xKSID, attach_xksid(reg, body, {}, t.a).index());
  if (t.kind == "JONCx")
    return make_contactor(ContactorKind::JONCx, attach_joncx(reg, body, {}, {1.0, 0.0}, t.a, t.b).index());
  if (t.kind == "PT2Dx") return make_contactor(ContactorKind::PT2Dx, attach_point(reg, body, {t.a, t.b}).index());
  return make_contactor(ContactorKind::POLYG, attach_polyg(reg, body, t.vertices).index());
}

/// LMGC90's radii of a contactor (mod_a_BDARY_*.f90): average radius √(area/π), radius of
/// gyration, and its centre in the node's frame (the POLYG's centroid).
void contactor_radii(const TactRec& t, double& rdg, double& grdg, Vec2& shift) {
  rdg = grdg = 0.0;
  shift = {};
  if (t.kind == "DISKx") {
    rdg = t.a;
    grdg = t.a / std::sqrt(2.0);
  } else if (t.kind == "JONCx") {
    const double a = t.a, b = t.b, area = 4.0 * a * b + std::numbers::pi * b * b;
    rdg = std::sqrt(area / std::numbers::pi);
    grdg = std::sqrt((std::numbers::pi * b * b * (a * a + 0.5 * b * b) + 2.0 * a * b * (a * a + b * b)) / area);
  } else if (t.kind == "POLYG") {
    const MassProperties m = mass_properties(t.vertices);
    rdg = std::sqrt(m.area / std::numbers::pi);
    grdg = std::sqrt(m.polar_moment / m.area);
    shift = m.centroid;
  } else if (t.kind == "PT2Dx") {
    shift = {t.a, t.b};
  }
}

/// What LMGC90's read_bodies does where avrd or gyrd is 0 (mod_RBDY2.f90): both from the
/// contactors — one contactor: its own; several: Σ π rdg² and Σ π rdg² (grdg² + |shift|²). And
/// where the node is at the origin with one POLYG, the vertices were given in the world frame:
/// the node goes to their centroid. Throws (by fail_at) where the mass comes out 0 (an xKSID).
void lmgc90_radii(BodyRec& b, const std::filesystem::path& file) {
  if (b.tacts.size() == 1 && b.tacts[0].kind == "POLYG" && b.coo[0] == 0.0 && b.coo[1] == 0.0 && b.coo[2] == 0.0) {
    const Vec2 c = mass_properties(b.tacts[0].vertices).centroid;
    b.coo[0] = c.x;
    b.coo[1] = c.y;
    for (Vec2& v : b.tacts[0].vertices) v -= c;
  }
  if (b.avrd > 0.0 && b.gyrd > 0.0) return;
  double rdg = 0.0, grdg = 0.0, mT = 0.0, iT = 0.0;
  Vec2 shift;
  for (const TactRec& t : b.tacts) {
    contactor_radii(t, rdg, grdg, shift);
    const double mi = std::numbers::pi * rdg * rdg;
    mT += mi;
    iT += mi * (grdg * grdg + (b.tacts.size() == 1 ? 0.0 : dot(shift, shift)));
  }
  if (!(mT > 0.0) || !(iT > 0.0)) {
    // LMGC90 runs a driven drum (an xKSID alone) with mass 0; read_datbox checks it is driven
    const auto ring =
        std::find_if(b.tacts.begin(), b.tacts.end(), [](const TactRec& t) { return t.kind == "xKSID" && t.a > 0.0; });
    if (ring == b.tacts.end())
      fail_at(file, b.behav_line,
              "avrd or gyrd is 0 and the contactors give no mass (a PT2Dx alone): nscd needs a mass > 0");
    b.nominal_mass = true;
    b.avrd = b.gyrd = ring->a;
    return;
  }
  b.avrd = std::sqrt(mT / std::numbers::pi);
  b.gyrd = std::sqrt(iT / mT);
}

void add_bodies(Parsed& p, const std::filesystem::path& file, Registry& reg) {
  std::map<std::string, MaterialId> ids;
  for (std::size_t i = 0; i < p.bodies.size(); ++i) {
    BodyRec& b = p.bodies[i];
    try {
      if (!b.tacts.empty() || b.avrd == 0.0 || b.gyrd == 0.0) lmgc90_radii(b, file);
    } catch (const Error& e) {
      if (std::string(e.what()).rfind("DATBOX", 0) == 0) throw;
      fail_at(file, b.line, e.what());
    }
    RigidBodySpec s;
    s.name = std::to_string(i + 1);
    s.material = material_of(p, b, file, reg, ids);
    s.mass = reg.materials.density[s.material.index()] * std::numbers::pi * b.avrd * b.avrd;
    s.inertia = s.mass * b.gyrd * b.gyrd;
    s.position = {b.coo[0] + b.X[0], b.coo[1] + b.X[1]};
    s.angle = b.coo[2] + b.X[2];
    s.velocity = {b.V[0], b.V[1]};
    s.spin = b.V[2];
    BodyId id;
    try {
      id = add_body(reg, s);
    } catch (const Error& e) {
      fail_at(file, b.line, e.what());
    }
    reg.bodies.x0[id.index()] = b.coo[0];
    reg.bodies.y0[id.index()] = b.coo[1];
    reg.bodies.angle0[id.index()] = b.coo[2];
    std::vector<ContactorId> tacts;
    for (const TactRec& t : b.tacts) {
      try {
        tacts.push_back(attach(reg, id, t));
      } catch (const Error& e) {
        fail_at(file, t.line, "RBDY2 " + s.name + ": " + e.what());
      }
    }
    p.tact_ids.push_back(std::move(tacts));
  }
}

/// Checks a see entry; returns its contactor kinds.
std::pair<ContactorKind, ContactorKind> check_see(const Parsed& p, const SeeRec& s, const std::filesystem::path& file) {
  for (const std::string* body : {&s.cdbdy, &s.anbdy})
    if (*body != "RBDY2")
      fail_at(file, s.line,
              "body type '" + *body + "' in the see table is not supported (RBDY2 only" +
                  (*body == "MAILx"   ? "; MAILx is a deformable mesh)"
                   : *body == "RBDY3" ? "; RBDY3 is 3D)"
                                      : ")"));
  for (const std::string* tact : {&s.cdtac, &s.antac}) {
    if (*tact == "PT2Dx") fail_at(file, s.line, "PT2Dx interactions (PTPT2 links) are not read from a DATBOX");
    if (*tact != "POLYG" && *tact != "DISKx" && *tact != "JONCx" && *tact != "xKSID")
      fail_at(file, s.line,
              "contactor '" + *tact + "' in the see table is not supported (nscd has DISKx, JONCx, xKSID, POLYG)");
  }
  const ContactorKind cd = parse_contactor_kind(s.cdtac), an = parse_contactor_kind(s.antac);
  if (interaction_name(cd, an).empty())
    fail_at(file, s.line, "LMGC90 has no interaction of candidate " + s.cdtac + " and antagonist " + s.antac);
  const auto law = p.laws.find(s.behav);
  if (law == p.laws.end()) fail_at(file, s.line, "contact law '" + s.behav + "' is not defined in TACT_BEHAV.DAT");
  if (!law->second.known)
    fail_at(file, s.line,
            "contact law '" + s.behav + "' is " + law->second.law + " (line " + std::to_string(law->second.line) +
                "): nscd has IQS_CLB, GAP_SGR_CLB and RST_CLB");
  return {cd, an};
}

void add_laws(const Parsed& p, const std::filesystem::path& file, Datbox& d) {
  Registry& reg = d.reg;
  std::map<std::pair<std::string, std::string>, const SeeRec*> by_colours;
  std::set<std::string> used;
  double alert = -1.0;
  bool alerts_differ = false;
  for (const SeeRec& s : p.see) {
    check_see(p, s, file);
    const auto key = std::minmax(s.cdcol, s.ancol);
    const auto [it, fresh] = by_colours.emplace(key, &s);
    if (!fresh && it->second->behav != s.behav)
      fail_at(file, s.line,
              "colours (" + s.cdcol + ", " + s.ancol + ") get law '" + s.behav + "' here and '" + it->second->behav +
                  "' at line " + std::to_string(it->second->line) + ": nscd picks one law per pair of colours");
    used.insert(s.behav);
    if (alert >= 0.0 && s.alert != alert) alerts_differ = true;
    alert = std::max(alert, s.alert);
    if (s.halo >= 0.0)
      d.notes.push_back("TACT_BEHAV.DAT line " + std::to_string(s.line + 1) +
                        ": the second alert distance ('+' line) is not used");
  }
  if (alert >= 0.0) reg.params.alert = alert;
  if (alerts_differ)
    d.notes.push_back("the see table has different alert distances; nscd has one: the largest, " + exact(alert));
  std::map<std::string, std::int32_t> index;
  for (const auto& [name, law] : p.laws) {
    if (!used.count(name)) {
      d.notes.push_back("contact law '" + name + "' (" + law.law + ", TACT_BEHAV.DAT line " + std::to_string(law.line) +
                        ") is used by no see entry");
      continue;
    }
    index[name] = static_cast<std::int32_t>(reg.contact_laws.laws.size());
    reg.contact_laws.laws.push_back(law.spec);
    d.law_name.push_back(name);
  }
  auto& t = reg.contact_laws;
  const auto colour = [&](std::size_t m) { return reg.materials.name[m].substr(reg.materials.name[m].find(':') + 1); };
  for (std::size_t a = 0; a < reg.materials.size(); ++a)
    for (std::size_t b = 0; b < reg.materials.size(); ++b) {
      const auto it = by_colours.find(std::minmax(colour(a), colour(b)));
      if (it != by_colours.end()) t.pair_law[a * t.n_materials + b] = index.at(it->second->behav);
    }
}

}  // namespace

void build_registry(Parsed& p, const std::filesystem::path& bodies_file, const std::filesystem::path& tact_file,
                    Datbox& d) {
  d.reg.params.gravity = p.gravity;
  std::set<std::string> used;
  for (const BodyRec& b : p.bodies) used.insert(b.behav);
  for (const auto& [name, b] : p.behavs)
    if (!used.count(name))
      d.notes.push_back("bulk behaviour '" + name + "' (" + b.law + ", BULK_BEHAV.DAT line " + std::to_string(b.line) +
                        ") is used by no RBDY2");
  add_bodies(p, bodies_file, d.reg);
  add_laws(p, tact_file, d);
}

std::vector<std::vector<ContactorId>> contactors_by_body(const Registry& reg) {
  std::vector<std::vector<ContactorId>> out(reg.bodies.size());
  auto add = [&](ContactorKind k, const std::vector<BodyId>& body) {
    for (std::size_t i = 0; i < body.size(); ++i)
      out[body[i].index()].push_back(make_contactor(k, static_cast<std::uint32_t>(i)));
  };
  add(ContactorKind::POLYG, reg.polyg.body);
  add(ContactorKind::DISKx, reg.diskx.body);
  add(ContactorKind::JONCx, reg.joncx.body);
  add(ContactorKind::xKSID, reg.xksid.body);
  add(ContactorKind::PT2Dx, reg.points.body);
  return out;
}

}  // namespace nscd::datbox

namespace nscd {

std::pair<int, int> datbox_number(const Registry& reg, ContactorId c) {
  const auto all = datbox::contactors_by_body(reg);
  for (std::size_t b = 0; b < all.size(); ++b)
    for (std::size_t k = 0; k < all[b].size(); ++k)
      if (all[b][k] == c) return {static_cast<int>(b + 1), static_cast<int>(k + 1)};
  throw Error("datbox_number: unknown contactor");
}

}  // namespace nscd
