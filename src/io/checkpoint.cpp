// nscd/io/checkpoint.cpp — see checkpoint.hpp.
#include "nscd/io/checkpoint.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/contactors/pt2dx.hpp"
#include "nscd/interactions/ptpt2.hpp"
#include "nscd/core/error.hpp"

namespace nscd {
namespace {

constexpr const char* kMagic = "nscd-checkpoint";
// Version 3 adds each POLYG's is_big flag and each PTPT2 link's length and normal at its last
// detection, so that a reload gives every table bit for bit (and a link squeezed to zero
// length can be reloaded). Version 2 files are still read: their links take the length and
// normal of the saved configuration, their polygons is_big = 0 (both are recomputed by the
// next step's detection).
constexpr int kVersion = 3;
constexpr int kOldestVersion = 2;

// ---- writing ----------------------------------------------------------------------------
struct Out {
  std::ostream& os;
  Out& operator<<(double v) { os << ' ' << std::hexfloat << v << std::defaultfloat; return *this; }
  Out& operator<<(std::int64_t v) { os << ' ' << v; return *this; }
  Out& operator<<(std::uint64_t v) { os << ' ' << v; return *this; }
  Out& operator<<(int v) { os << ' ' << v; return *this; }
  Out& operator<<(std::uint32_t v) { os << ' ' << v; return *this; }
  Out& operator<<(const std::string& s) { os << ' ' << std::quoted(s); return *this; }
  Out& tag(const char* t) { os << '\n' << t; return *this; }
};

// ---- reading ----------------------------------------------------------------------------
// An error already naming the file (the others, raised by the registry's own checks while the
// scene is rebuilt, are prefixed with the file name by load_checkpoint).
struct FileError : Error {
  using Error::Error;
};

struct In {
  std::istream& is;
  const std::filesystem::path& file;
  const std::string& content;  ///< the whole file, to tell the line of an error

  [[noreturn]] void fail(const std::string& what) const {
    is.clear();
    const std::streamoff pos = is.tellg();
    const std::size_t end = pos < 0 ? content.size() : std::min(content.size(), static_cast<std::size_t>(pos));
    const auto line = 1 + std::count(content.begin(), content.begin() + static_cast<std::ptrdiff_t>(end), '\n');
    throw FileError("reading checkpoint '" + file.string() + "', line " + std::to_string(line) + ": " + what);
  }
  void expect(const char* t) {
    std::string w;
    if (!(is >> w) || w != t) fail(std::string("expected '") + t + "', found '" + w + "'");
  }
  double real() {
    std::string w;
    if (!(is >> w)) fail("unexpected end of file");
    char* end = nullptr;
    const double v = std::strtod(w.c_str(), &end);
    if (end == w.c_str() || *end != '\0') fail("bad number '" + w + "'");
    return v;
  }
  template <class T>
  T integer() {
    T v{};
    if (!(is >> v)) fail("expected an integer");
    return v;
  }
  /// An integer in [lo, hi], `what` naming it in the error.
  long long integer_in(long long lo, long long hi, const char* what) {
    const auto v = integer<long long>();
    if (v < lo || v > hi)
      fail(std::string(what) + " " + std::to_string(v) + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return v;
  }
  std::string text() {
    std::string s;
    if (!(is >> std::quoted(s))) fail("expected a quoted string");
    return s;
  }
};

void write_time_function(Out& o, const TimeFunction& f, const std::string& who) {
  if (f.kind() == TimeFunction::Kind::Lambda)
    throw Error("cannot checkpoint " + who + ": its boundary condition is a user lambda; re-impose it after loading");
  o << static_cast<int>(f.kind()) << f.A() << f.B() << f.frequency() << f.phase() << f.ramp_duration() << f.start();
}

TimeFunction read_time_function(In& in) {
  const int kind = in.integer<int>();
  const double a = in.real(), b = in.real(), f = in.real(), phi = in.real(), ramp = in.real(), t0 = in.real();
  if (kind == static_cast<int>(TimeFunction::Kind::Constant)) return TimeFunction::constant(a);
  if (kind == static_cast<int>(TimeFunction::Kind::Cosine)) return TimeFunction::cosine(a, b, f, phi, ramp, t0);
  in.fail("unknown time-function kind " + std::to_string(kind));
}

}  // namespace

void save_checkpoint(const std::filesystem::path& file, const Registry& reg,
                     const ContactHistory& warm_start,
                     const std::map<std::string, std::string>& extra) {
  std::ostringstream buf;
  Out o{buf};
  buf << kMagic << ' ' << kVersion;
  o.tag("time") << reg.time << reg.step;
  o.tag("params") << reg.params.dt << reg.params.theta << reg.params.gravity.x << reg.params.gravity.y
                  << reg.params.alert;
  o.tag("materials") << static_cast<std::uint64_t>(reg.materials.size());
  for (std::size_t i = 0; i < reg.materials.size(); ++i) o.tag("m") << reg.materials.name[i] << reg.materials.density[i];
  const ContactLawTable& lt = reg.contact_laws;
  o.tag("laws") << static_cast<std::uint64_t>(lt.laws.size()) << static_cast<int>(lt.default_law);
  for (const LawSpec& l : lt.laws) o.tag("l") << static_cast<int>(l.kind) << l.mu << l.e_n << l.e_t;
  o.tag("pairs") << static_cast<std::uint64_t>(lt.n_materials);
  for (std::int32_t k : lt.pair_law) o << static_cast<int>(k);
  const BodyTable& b = reg.bodies;
  o.tag("bodies") << static_cast<std::uint64_t>(b.size());
  for (std::size_t i = 0; i < b.size(); ++i)
    o.tag("b") << b.name[i] << static_cast<std::uint32_t>(b.material[i].value) << b.mass[i] << b.inertia[i] << b.x0[i]
               << b.y0[i] << b.angle0[i] << b.x[i] << b.y[i] << b.angle[i] << b.vx[i] << b.vy[i] << b.spin[i];
  o.tag("drives") << static_cast<std::uint64_t>(b.drives.size());
  for (const DofDrive& d : b.drives) {
    o.tag("d") << d.body.value << static_cast<int>(d.dof) << static_cast<int>(d.drive);
    const std::string& name = d.body.index() < b.size() ? b.name[d.body.index()] : std::string();
    write_time_function(o, d.value, "body " + std::to_string(d.body.value) + (name.empty() ? "" : " '" + name + "'"));
  }
  const PolygTable& p = reg.polyg;
  o.tag("polyg") << static_cast<std::uint64_t>(p.size());
  for (std::size_t k = 0; k < p.size(); ++k) {
    o.tag("p") << p.body[k].value << static_cast<int>(p.is_big[k]) << p.vertex_count[k];
    for (std::uint32_t v = 0; v < p.vertex_count[k]; ++v) o << p.vertex[p.first_vertex[k] + v].x << p.vertex[p.first_vertex[k] + v].y;
  }
  o.tag("points") << static_cast<std::uint64_t>(reg.points.size());
  for (std::size_t k = 0; k < reg.points.size(); ++k)
    o.tag("pt") << reg.points.body[k].value << reg.points.point[k].x << reg.points.point[k].y;
  const Ptpt2Table& lk = reg.links;
  o.tag("links") << static_cast<std::uint64_t>(lk.size());
  for (std::size_t k = 0; k < lk.size(); ++k)
    o.tag("lk") << lk.candidate[k].value << lk.antagonist[k].value << lk.law[k].k << lk.law[k].nu << lk.law[k].L0
                << lk.law[k].eps0 << lk.rn[k] << lk.length[k] << lk.normal[k].x << lk.normal[k].y;
  o.tag("warm") << static_cast<std::uint64_t>(warm_start.size());
  for (const auto& w : warm_start) o.tag("w") << w.pair << w.feature << w.rn << w.rt;
  o.tag("extra") << static_cast<std::uint64_t>(extra.size());
  for (const auto& [key, value] : extra) o.tag("x") << key << value;
  buf << "\nend\n";

  // Write "<file>.tmp" completely, then rename it over the file: the previous checkpoint stays
  // intact until the new one is whole. A failed write removes its partial .tmp.
  const std::filesystem::path tmp = file.string() + ".tmp";
  std::error_code ec;
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw Error("cannot write checkpoint '" + tmp.string() + "'");
    const std::string s = buf.str();
    f.write(s.data(), static_cast<std::streamsize>(s.size()));
    f.close();
    if (!f) {
      std::filesystem::remove(tmp, ec);
      throw Error("error while writing checkpoint '" + tmp.string() + "' (disk full?)");
    }
  }
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    const std::string why = ec.message();
    std::filesystem::remove(tmp, ec);
    throw Error("cannot rename '" + tmp.string() + "' to '" + file.string() + "': " + why);
  }
}

namespace {

// Reads everything after the version; throws FileError (naming the file) on a malformed file
// and lets the registry functions throw their own Error on inconsistent data.
void read_checkpoint(In& in, int version, Checkpoint& cp) {
  Registry& reg = cp.reg;
  in.expect("time");
  reg.time = in.real();
  reg.step = in.integer<std::int64_t>();
  in.expect("params");
  reg.params.dt = in.real();
  reg.params.theta = in.real();
  reg.params.gravity.x = in.real();
  reg.params.gravity.y = in.real();
  reg.params.alert = in.real();
  in.expect("materials");
  const auto nm = in.integer<std::size_t>();
  for (std::size_t i = 0; i < nm; ++i) {
    in.expect("m");
    const std::string name = in.text();
    add_material(reg, name, in.real());
  }
  in.expect("laws");
  const auto nl = in.integer<std::size_t>();
  const auto n_laws = static_cast<long long>(std::min<std::size_t>(nl, 1u << 30));
  const int def = static_cast<int>(in.integer_in(-1, n_laws - 1, "default law index"));
  for (std::size_t i = 0; i < nl; ++i) {
    in.expect("l");
    LawSpec l;
    // a contact law: VOIGT_ROD is a spring law, never in this table
    l.kind = static_cast<LawKind>(in.integer_in(0, static_cast<int>(LawKind::RST_CLB), "contact law kind"));
    l.mu = in.real();
    l.e_n = in.real();
    l.e_t = in.real();
    validate(l);
    reg.contact_laws.laws.push_back(l);
  }
  reg.contact_laws.default_law = def;
  in.expect("pairs");
  if (in.integer<std::size_t>() != nm) in.fail("contact-law table size does not match the materials");
  for (auto& k : reg.contact_laws.pair_law) k = static_cast<std::int32_t>(in.integer_in(-1, n_laws - 1, "pair law index"));
  in.expect("bodies");
  const auto nb = in.integer<std::size_t>();
  for (std::size_t i = 0; i < nb; ++i) {
    in.expect("b");
    RigidBodySpec s;
    s.name = in.text();
    s.material = MaterialId(in.integer<std::uint32_t>());
    s.mass = in.real();
    s.inertia = in.real();
    const double x0 = in.real(), y0 = in.real(), a0 = in.real();
    s.position = {in.real(), in.real()};
    s.angle = in.real();
    s.velocity = {in.real(), in.real()};
    s.spin = in.real();
    add_body(reg, s);
    reg.bodies.x0[i] = x0;
    reg.bodies.y0[i] = y0;
    reg.bodies.angle0[i] = a0;
  }
  in.expect("drives");
  const auto nd = in.integer<std::size_t>();
  for (std::size_t i = 0; i < nd; ++i) {
    in.expect("d");
    const BodyId body(in.integer<std::uint32_t>());
    const auto dof = static_cast<Dof>(in.integer_in(0, static_cast<int>(Dof::Rot), "degree of freedom"));
    const auto drive = static_cast<Drive>(in.integer_in(0, static_cast<int>(Drive::Force), "drive"));
    TimeFunction fn = read_time_function(in);
    if (drive == Drive::Fixed) fix_dof(reg, body, dof);
    else if (drive == Drive::Velocity) impose_velocity(reg, body, dof, fn);
    else if (drive == Drive::Force) impose_force(reg, body, dof, fn);
  }
  in.expect("polyg");
  const auto np = in.integer<std::size_t>();
  for (std::size_t k = 0; k < np; ++k) {
    in.expect("p");
    const BodyId body(in.integer<std::uint32_t>());
    const int is_big = version >= 3 ? static_cast<int>(in.integer_in(0, 1, "is_big flag")) : 0;
    // bounded before anything is allocated
    const auto nv = static_cast<std::size_t>(in.integer_in(3, static_cast<long long>(kMaxPolygVertices), "vertex count"));
    Polygon v(nv);
    for (auto& p : v) p = {in.real(), in.real()};
    attach_polyg(reg, body, v);
    reg.polyg.is_big.back() = static_cast<std::uint8_t>(is_big);
  }
  in.expect("points");
  const auto npt = in.integer<std::size_t>();
  for (std::size_t k = 0; k < npt; ++k) {
    in.expect("pt");
    const BodyId body(in.integer<std::uint32_t>());
    const double px = in.real(), py = in.real();
    attach_point(reg, body, {px, py});
  }
  in.expect("links");
  const auto nlk = in.integer<std::size_t>();
  for (std::size_t k = 0; k < nlk; ++k) {
    in.expect("lk");
    const PointId cd(in.integer<std::uint32_t>()), an(in.integer<std::uint32_t>());
    VoigtRod law;
    law.k = in.real();
    law.nu = in.real();
    law.L0 = in.real();
    law.eps0 = in.real();
    const double rn = in.real();
    if (version < 3) {
      // the link's frame from the saved configuration (fails if its points coincide there)
      add_spring(reg, cd, an, law);
      reg.links.rn.back() = rn;
      continue;
    }
    const double length = in.real();
    const Vec2 normal{in.real(), in.real()};
    // The link as it was, frame included: add_spring would refuse a link squeezed to zero
    // length, and recompute the frame at q_f instead of the last detection's q_m.
    const std::size_t n_points = reg.points.size();
    if (!cd.valid() || cd.index() >= n_points || !an.valid() || an.index() >= n_points)
      in.fail("PTPT2 link " + std::to_string(k) + ": unknown PT2Dx point id");
    if (!(law.k >= 0.0) || !(law.nu >= 0.0) || !(law.L0 > 0.0) || !std::isfinite(law.k) || !std::isfinite(law.nu) ||
        !std::isfinite(law.L0) || !std::isfinite(law.eps0) || !std::isfinite(rn))
      in.fail("PTPT2 link " + std::to_string(k) + ": VOIGT_ROD needs finite k >= 0, nu >= 0, L0 > 0, eps0 and force");
    if (!(length >= 0.0) || !std::isfinite(length) || !(std::abs(norm(normal) - 1.0) < 1e-9))
      in.fail("PTPT2 link " + std::to_string(k) + ": length must be finite and >= 0, the normal a unit vector");
    Ptpt2Table& l = reg.links;
    l.candidate.push_back(cd);
    l.antagonist.push_back(an);
    l.law.push_back(law);
    l.length.push_back(length);
    l.normal.push_back(normal);
    l.rn.push_back(rn);
  }
  in.expect("warm");
  const auto nw = in.integer<std::size_t>();
  for (std::size_t i = 0; i < nw; ++i) {
    in.expect("w");
    ContactMemory w;
    w.pair = in.integer<std::uint64_t>();
    w.feature = in.integer<std::uint32_t>();
    w.rn = in.real();
    w.rt = in.real();
    cp.warm_start.push_back(w);
  }
  in.expect("extra");
  const auto nx = in.integer<std::size_t>();
  for (std::size_t i = 0; i < nx; ++i) {
    in.expect("x");
    std::string key = in.text();
    cp.extra[key] = in.text();
  }
  in.expect("end");
}

}  // namespace

Checkpoint load_checkpoint(const std::filesystem::path& file) {
  std::string text;
  {
    std::ifstream is(file, std::ios::binary);
    if (!is) throw Error("cannot open checkpoint '" + file.string() + "'");
    std::ostringstream all;
    all << is.rdbuf();
    if (is.bad()) throw Error("cannot read checkpoint '" + file.string() + "'");
    text = std::move(all).str();
  }
  std::istringstream f(text);
  In in{f, file, text};
  std::string magic;
  int version = 0;
  if (!(f >> magic) || magic != kMagic) in.fail("not an nscd checkpoint");
  if (!(f >> version)) in.fail("no version number after '" + std::string(kMagic) + "'");
  if (version < kOldestVersion || version > kVersion)
    in.fail("version " + std::to_string(version) + " is not supported (expected " + std::to_string(kOldestVersion) +
            " to " + std::to_string(kVersion) + ")");
  Checkpoint cp;
  try {
    read_checkpoint(in, version, cp);
  } catch (const FileError&) {
    throw;
  } catch (const Error& e) {
    // a body, polygon, point or link the registry refuses: name the file too
    in.fail(e.what());
  }
  return cp;
}

}  // namespace nscd
