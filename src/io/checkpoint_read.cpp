// nscd/io/checkpoint_read.cpp — see checkpoint.hpp: the reader (the writer is checkpoint.cpp).
#include "nscd/io/checkpoint.hpp"

#include "nscd/io/checkpoint_format.hpp"

#include <array>
#include <cmath>
#include <cstdlib>
#include <initializer_list>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/contactors/pt2dx.hpp"
#include "nscd/contactors/round_shapes.hpp"
#include "nscd/interactions/ptpt2.hpp"
#include "nscd/contactors/contactor_row.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/text_reader.hpp"

namespace nscd {
namespace {

using checkpoint_format::kMagic;
using checkpoint_format::kOldestVersion;
using checkpoint_format::kVersion;

// Counts bound what a count line may announce (the records are read one by one, nothing is
// allocated from a count; the bound only keeps the numbers sane).
constexpr long long kMaxCount = 1ll << 40;

// ---- reading ----------------------------------------------------------------------------
// Every record is one line: a tag, then its fields (the writer puts each on its own line).
// A record is read whole: each field strictly (parse_real / parse_integer: the whole token,
// finite, in range), and nothing may follow its last field.
class Rec {
 public:
  Rec(const LineReader& in, std::string rest, const char* tag) : in_(in), ls_(std::move(rest)), tag_(tag) {}
  [[noreturn]] void fail(const std::string& what) const { in_.fail(what); }
  std::string token(const char* what) {
    std::string w;
    if (!(ls_ >> w)) fail(std::string("'") + tag_ + "' record: expected " + what + ", found the end of the line");
    return w;
  }
  double real(const char* what, double limit = kMaxMagnitude) {
    const std::string w = token(what);
    try {
      return parse_real(w, std::string(tag_) + " record, " + what, -limit, limit);
    } catch (const Error& e) {
      fail(e.what());
    }
  }
  /// A real in [lo, hi] (masses, inertias: bounded away from 0 so that 1/m stays finite).
  double real_in(const char* what, double lo, double hi) {
    const std::string w = token(what);
    try {
      return parse_real(w, std::string(tag_) + " record, " + what, lo, hi);
    } catch (const Error& e) {
      fail(e.what());
    }
  }
  long long integer(const char* what, long long lo, long long hi) {
    const std::string w = token(what);
    try {
      return parse_integer(w, std::string(tag_) + " record, " + what, lo, hi);
    } catch (const Error& e) {
      fail(e.what());
    }
  }
  std::uint32_t index(const char* what) {
    return static_cast<std::uint32_t>(integer(what, 0, 0xFFFFFFFFll));
  }  // 0xFFFFFFFF: none
  std::size_t count(const char* what) { return static_cast<std::size_t>(integer(what, 0, kMaxCount)); }
  std::string text(const char* what) {
    ls_ >> std::ws;
    if (ls_.peek() != '"') fail(std::string("'") + tag_ + "' record: expected " + what + " (a quoted string)");
    std::string s;
    if (!(ls_ >> std::quoted(s))) fail(std::string("'") + tag_ + "' record: unterminated string");
    return s;
  }
  /// Nothing may follow the last field (a wrong count or a line joined with the next).
  void end() {
    std::string w;
    if (ls_ >> w) fail(std::string("'") + tag_ + "' record: unexpected '" + w.substr(0, 40) + "' after its last field");
  }

 private:
  const LineReader& in_;
  std::istringstream ls_;
  const char* tag_;
};

struct In {
  LineReader& lines;
  [[noreturn]] void fail(const std::string& what) const { lines.fail(what); }
  /// The next line, which must start with `tag`.
  Rec record(const char* tag) {
    std::string line;
    if (!lines.next(line)) {
      throw Error(lines.where() + ": expected '" + tag + "', found the end of the file");
    }
    std::istringstream ls(line);
    std::string w;
    ls >> w;
    if (w != tag) fail(std::string("expected '") + tag + "', found '" + w.substr(0, 40) + "'");
    std::string rest;
    std::getline(ls, rest, '\0');
    return Rec(lines, rest, tag);
  }
};

TimeFunction read_time_function(Rec& r) {
  const auto kind = r.integer("time-function kind", std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
  const double a = r.real("A"), b = r.real("B"), f = r.real("frequency"), phi = r.real("phase"), ramp = r.real("ramp"),
               t0 = r.real("start");
  if (kind == static_cast<int>(TimeFunction::Kind::Constant)) return TimeFunction::constant(a);
  if (kind == static_cast<int>(TimeFunction::Kind::Cosine)) return TimeFunction::cosine(a, b, f, phi, ramp, t0);
  r.fail("unknown time-function kind " + std::to_string(kind));
}

// A count record ("materials", "bodies", …): its tag and one count.
std::size_t read_count(In& in, const char* tag, const char* what) {
  Rec r = in.record(tag);
  const std::size_t n = r.count(what);
  r.end();
  return n;
}

void read_time_and_params(In& in, Registry& reg) {
  {
    Rec r = in.record("time");
    reg.time = r.real("time", kMaxTime);
    reg.step = r.integer("step", 0, std::numeric_limits<std::int64_t>::max() / 2);
    r.end();
  }
  Rec r = in.record("params");
  reg.params.dt = r.real("dt");
  reg.params.theta = r.real("theta");
  reg.params.gravity.x = r.real("gravity x");
  reg.params.gravity.y = r.real("gravity y");
  reg.params.alert = r.real("alert");
  r.end();
  validate(reg.params);
}

// Returns the number of materials (the size of the law table's pairs).
std::size_t read_materials(In& in, Registry& reg) {
  const std::size_t nm = read_count(in, "materials", "material count");
  for (std::size_t i = 0; i < nm; ++i) {
    Rec r = in.record("m");
    const std::string name = r.text("material name");
    const double density = r.real("density");
    r.end();
    add_material(reg, name, density);
  }
  return nm;
}

// The contact laws, the default law and the law of each pair of the nm materials.
void read_contact_laws(In& in, Registry& reg, std::size_t nm) {
  std::size_t nl = 0;
  int def = -1;
  {
    Rec r = in.record("laws");
    nl = r.count("law count");
    def = static_cast<int>(r.integer("default law index", -1, static_cast<long long>(nl) - 1));
    r.end();
  }
  for (std::size_t i = 0; i < nl; ++i) {
    Rec r = in.record("l");
    LawSpec l;
    // a contact law: VOIGT_ROD is a spring law, never in this table
    l.kind = static_cast<LawKind>(r.integer("contact law kind", 0, static_cast<int>(kLastContactLaw)));
    l.mu = r.real("mu");
    l.e_n = r.real("e_n");
    l.e_t = r.real("e_t");
    r.end();
    validate(l);
    reg.contact_laws.laws.push_back(l);
  }
  reg.contact_laws.default_law = def;
  Rec r = in.record("pairs");
  if (r.count("material count") != nm) r.fail("contact-law table size does not match the materials");
  for (auto& k : reg.contact_laws.pair_law)
    k = static_cast<std::int32_t>(r.integer("pair law index", -1, static_cast<long long>(nl) - 1));
  r.end();
}

void read_bodies(In& in, Registry& reg) {
  const std::size_t nb = read_count(in, "bodies", "body count");
  for (std::size_t i = 0; i < nb; ++i) {
    Rec r = in.record("b");
    RigidBodySpec s;
    s.name = r.text("body name");
    s.material = MaterialId(r.index("material id"));
    s.mass = r.real_in("mass", kMinMass, kMaxMagnitude);
    s.inertia = r.real_in("inertia", kMinMass, kMaxMagnitude);
    const double x0 = r.real("x0", kMaxLength), y0 = r.real("y0", kMaxLength), a0 = r.real("angle0", kMaxAngle);
    s.position.x = r.real("x", kMaxLength);
    s.position.y = r.real("y", kMaxLength);
    s.angle = r.real("angle", kMaxAngle);
    s.velocity.x = r.real("vx", kMaxSpeed);
    s.velocity.y = r.real("vy", kMaxSpeed);
    s.spin = r.real("spin", kMaxSpin);
    r.end();
    add_body(reg, s);
    reg.bodies.x0[i] = x0;
    reg.bodies.y0[i] = y0;
    reg.bodies.angle0[i] = a0;
  }
}

// The bodies' fixed, driven and loaded degrees of freedom.
void read_drives(In& in, Registry& reg) {
  const std::size_t nd = read_count(in, "drives", "drive count");
  for (std::size_t i = 0; i < nd; ++i) {
    Rec r = in.record("d");
    const BodyId body(r.index("body id"));
    const auto dof = static_cast<Dof>(r.integer("degree of freedom", 0, static_cast<int>(Dof::Rot)));
    const auto drive = static_cast<Drive>(r.integer("drive", 0, static_cast<int>(Drive::Force)));
    TimeFunction fn = read_time_function(r);
    r.end();
    if (drive == Drive::Fixed) fix_dof(reg, body, dof);
    else if (drive == Drive::Velocity) impose_velocity(reg, body, dof, fn);
    else if (drive == Drive::Force) impose_force(reg, body, dof, fn);
  }
}

// Returns the number of POLYGs.
std::size_t read_polygons(In& in, Registry& reg, int version) {
  const std::size_t np = read_count(in, "polyg", "POLYG count");
  for (std::size_t k = 0; k < np; ++k) {
    Rec r = in.record("p");
    const BodyId body(r.index("body id"));
    const int is_big = version >= 3 ? static_cast<int>(r.integer("is_big flag", 0, 1)) : 0;
    // bounded before anything is allocated
    const auto nv = static_cast<std::size_t>(r.integer("vertex count", 3, static_cast<long long>(kMaxPolygVertices)));
    Polygon v(nv);
    for (auto& p : v) {
      p.x = r.real("vertex x", kMaxLength);
      p.y = r.real("vertex y", kMaxLength);
    }
    r.end();
    attach_polyg(reg, body, v);
    reg.polyg.is_big.back() = static_cast<std::uint8_t>(is_big);
  }
  return np;
}

// Contactor counts per kind (ContactorKind order, then the added kinds), for the warm-start keys.
using KindCounts = std::array<std::size_t, kKindSlots>;

// `n` records of a kind: its tag, a body, its row's numbers; each attached by the row's load.
void read_kind(In& in, Registry& reg, const ContactorKindRow& row, std::size_t n) {
  const std::string tag(row.tag);
  std::vector<double> numbers(row.params.size());
  for (std::size_t k = 0; k < n; ++k) {
    Rec r = in.record(tag.c_str());
    const BodyId body(r.index("body id"));
    for (std::size_t i = 0; i < numbers.size(); ++i)
      numbers[i] = r.real(std::string(row.params[i]).c_str(), kMaxLength);
    r.end();
    row.load(reg, body, numbers.data());
  }
}

// The "round" section (version 4): DISKx, JONCx and xKSID; their counts go to counts[1..3].
void read_round_contactors(In& in, Registry& reg, KindCounts& counts) {
  {
    Rec r = in.record("round");
    counts[1] = r.count("DISKx count");
    counts[2] = r.count("JONCx count");
    counts[3] = r.count("xKSID count");
    r.end();
  }
  for (std::uint8_t k = 1; k <= 3; ++k) read_kind(in, reg, *kind_row(reg, k), counts[k]);
}

// The "kinds" section (version 5): the added kinds, which the loader was given, in order.
void read_added_kinds(In& in, Registry& reg, KindCounts& counts) {
  std::size_t n = 0;
  {
    Rec r = in.record("kinds");
    n = r.count("added kind count");
    r.end();
  }
  for (std::size_t a = 0; a < n; ++a) {
    Rec r = in.record("kind");
    const std::string name = r.text("kind name");
    const std::size_t count = r.count("contactor count");
    r.end();
    if (a >= reg.added.size() || reg.added.row[a]->name != name)
      r.fail("added contactor kind " + std::to_string(a) + " is '" + name.substr(0, 40) +
             "': pass its row to load_checkpoint (the scene's added kinds, in the order they were added)");
    read_kind(in, reg, *reg.added.row[a], count);
    counts[kFirstAddedKind + a] = count;
  }
}

void read_points(In& in, Registry& reg) {
  const std::size_t npt = read_count(in, "points", "point count");
  for (std::size_t k = 0; k < npt; ++k) {
    Rec r = in.record("pt");
    const BodyId body(r.index("body id"));
    const double px = r.real("x", kMaxLength), py = r.real("y", kMaxLength);
    r.end();
    attach_point(reg, body, {px, py});
  }
}

// One "lk" record, the k-th PTPT2 link.
void read_link(In& in, Registry& reg, int version, std::size_t k) {
  Rec r = in.record("lk");
  const PointId cd(r.index("candidate point id")), an(r.index("antagonist point id"));
  VoigtRod law;
  law.k = r.real("k");
  law.nu = r.real("nu");
  law.L0 = r.real("L0", kMaxLength);
  law.eps0 = r.real("eps0");
  const double rn = r.real("force", kMaxForce);
  if (version < 3) {
    r.end();
    // the link's frame from the saved configuration (fails if its points coincide there)
    add_spring(reg, cd, an, law);
    reg.links.rn.back() = rn;
    return;
  }
  const double length = r.real("length", kMaxLength);
  const Vec2 normal{r.real("normal x"), r.real("normal y")};
  r.end();
  // The link as it was, frame included: add_spring would refuse a link squeezed to zero
  // length, and recompute the frame at q_f instead of the last detection's q_m.
  const std::size_t n_points = reg.points.size();
  if (!cd.valid() || cd.index() >= n_points || !an.valid() || an.index() >= n_points)
    r.fail("PTPT2 link " + std::to_string(k) + ": unknown PT2Dx point id");
  if (!(law.k >= 0.0) || !(law.nu >= 0.0) || !(law.L0 > 0.0))
    r.fail("PTPT2 link " + std::to_string(k) + ": VOIGT_ROD needs k >= 0, nu >= 0, L0 > 0");
  if (!(length >= 0.0) || !(std::abs(norm(normal) - 1.0) < 1e-9))
    r.fail("PTPT2 link " + std::to_string(k) + ": length must be >= 0, the normal a unit vector");
  Ptpt2Table& l = reg.links;
  l.candidate.push_back(cd);
  l.antagonist.push_back(an);
  l.law.push_back(law);
  l.length.push_back(length);
  l.normal.push_back(normal);
  l.rn.push_back(rn);
}

// One "w" record, the i-th warm-start entry: a pair of existing contactors (counts: contactors
// per kind), after the previous entry.
void read_warm_entry(In& in, Checkpoint& cp, const KindCounts& counts, std::size_t i) {
  Rec r = in.record("w");
  ContactMemory w;
  const std::string key = r.token("pair key");
  try {
    w.pair = parse_unsigned(key, "w record, pair key");
  } catch (const Error& e) {
    r.fail(e.what());
  }
  w.feature = static_cast<std::uint32_t>(r.integer("feature", 0, 0xFFFFFFFFll));
  w.rn = r.real("normal force", kMaxForce);
  w.rt = r.real("tangential force", kMaxForce);
  r.end();
  // a pair of existing contactors, in the memory's sorted order (the stepper binary-searches it)
  for (const std::uint64_t id : {std::uint64_t(w.pair >> 32), std::uint64_t(w.pair & 0xFFFFFFFFull)}) {
    const ContactorId c(static_cast<std::uint32_t>(id));
    const std::uint8_t kind = contactor_kind_bits(c);
    if (contactor_index(c) >= counts[kind])  // PT2Dx (kind 4) never touches: count 0
      r.fail("warm-start entry " + std::to_string(i) + ": contactor pair (" + std::to_string(w.pair >> 32) + ", " +
             std::to_string(w.pair & 0xFFFFFFFFull) + ") is out of range (" + std::to_string(counts[0]) + " POLYGs, " +
             std::to_string(counts[1]) + " DISKx, " + std::to_string(counts[2]) + " JONCx, " +
             std::to_string(counts[3]) + " xKSID)");
  }
  if (!cp.warm_start.empty() && !(cp.warm_start.back() < w))
    r.fail("warm-start entry " + std::to_string(i) +
           ": not after the previous one (entries are sorted by pair and feature, each once)");
  cp.warm_start.push_back(w);
}

// The "extra" key-value pairs, each key once, then "end" and nothing after it but blank lines.
void read_extra_and_end(In& in, Checkpoint& cp) {
  const std::size_t nx = read_count(in, "extra", "extra count");
  for (std::size_t i = 0; i < nx; ++i) {
    Rec r = in.record("x");
    std::string key = r.text("key");
    std::string value = r.text("value");
    r.end();
    if (cp.extra.count(key)) r.fail("key '" + key.substr(0, 40) + "' is given twice");
    cp.extra[key] = std::move(value);
  }
  in.record("end").end();
  std::string line;
  while (in.lines.next(line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) in.fail("data after 'end'");
}

// Reads everything after the version line; every error names the file and the line (the
// registry's own refusals, raised while the scene is rebuilt, are prefixed by load_text).
void read_checkpoint(In& in, int version, Checkpoint& cp) {
  Registry& reg = cp.reg;
  read_time_and_params(in, reg);
  const std::size_t nm = read_materials(in, reg);
  read_contact_laws(in, reg, nm);
  read_bodies(in, reg);
  read_drives(in, reg);
  KindCounts counts{};
  counts[0] = read_polygons(in, reg, version);
  if (version >= 4) read_round_contactors(in, reg, counts);
  if (version >= 5) read_added_kinds(in, reg, counts);
  read_points(in, reg);
  const std::size_t nlk = read_count(in, "links", "link count");
  for (std::size_t k = 0; k < nlk; ++k) read_link(in, reg, version, k);
  const std::size_t nw = read_count(in, "warm", "warm-start count");
  for (std::size_t i = 0; i < nw; ++i) read_warm_entry(in, cp, counts, i);
  read_extra_and_end(in, cp);
}

// Reads a checkpoint held in `text` (`file` names it in the errors).
Checkpoint load_text(const std::string& text, const std::filesystem::path& file,
                     std::span<const ContactorKindRow* const> kinds) {
  LineReader lines(text, file, "reading checkpoint");
  In in{lines};
  std::string first;
  if (!lines.next(first)) in.fail("not an nscd checkpoint (empty file)");
  std::istringstream ls(first);
  std::string magic, version_text, more;
  if (!(ls >> magic) || magic != kMagic) in.fail("not an nscd checkpoint");
  if (!(ls >> version_text)) in.fail("no version number after '" + std::string(kMagic) + "'");
  int version = 0;
  try {
    version = static_cast<int>(parse_integer(version_text, "version", -1000000, 1000000));
  } catch (const Error&) {
    in.fail("no version number after '" + std::string(kMagic) + "'");
  }
  if (version < kOldestVersion || version > kVersion)
    in.fail("version " + std::to_string(version) + " is not supported (expected " + std::to_string(kOldestVersion) +
            " to " + std::to_string(kVersion) + ")");
  if (ls >> more) in.fail("unexpected '" + more.substr(0, 40) + "' after the version");
  Checkpoint cp;
  try {
    for (const ContactorKindRow* row : kinds) add_contactor_kind(cp.reg, *row);
    read_checkpoint(in, version, cp);
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.rfind("reading checkpoint '", 0) == 0) throw;
    // a body, polygon, point or link the registry refuses: name the file and the line too
    in.fail(what);
  } catch (const std::exception& e) {
    // nothing a file holds may escape as anything but nscd::Error (std::bad_alloc included)
    in.fail(std::string("cannot be loaded: ") + e.what());
  }
  return cp;
}

}  // namespace

Checkpoint load_checkpoint(const std::filesystem::path& file, std::span<const ContactorKindRow* const> kinds) {
  std::string text;
  {
    std::ifstream is(file, std::ios::binary);
    if (!is) throw Error("cannot open checkpoint '" + file.string() + "'");
    std::ostringstream all;
    all << is.rdbuf();
    if (is.bad()) throw Error("cannot read checkpoint '" + file.string() + "'");
    text = std::move(all).str();
  }
  return load_text(text, file, kinds);
}

Checkpoint load_checkpoint_text(const std::string& text, const std::string& name,
                                std::span<const ContactorKindRow* const> kinds) {
  return load_text(text, name, kinds);
}

}  // namespace nscd
