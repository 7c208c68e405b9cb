// nscd/io/checkpoint.cpp — see checkpoint.hpp.
#include "nscd/io/checkpoint.hpp"

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
constexpr int kVersion = 2;

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
struct In {
  std::istream& is;
  const std::filesystem::path& file;

  [[noreturn]] void fail(const std::string& what) const {
    throw Error("reading checkpoint '" + file.string() + "': " + what);
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
                     const std::vector<MoreauJean::WarmStartEntry>& warm_start,
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
    write_time_function(o, d.value, "body " + std::to_string(d.body.value));
  }
  const PolygTable& p = reg.polyg;
  o.tag("polyg") << static_cast<std::uint64_t>(p.size());
  for (std::size_t k = 0; k < p.size(); ++k) {
    o.tag("p") << p.body[k].value << p.vertex_count[k];
    for (std::uint32_t v = 0; v < p.vertex_count[k]; ++v) o << p.vertex[p.first_vertex[k] + v].x << p.vertex[p.first_vertex[k] + v].y;
  }
  o.tag("points") << static_cast<std::uint64_t>(reg.points.size());
  for (std::size_t k = 0; k < reg.points.size(); ++k)
    o.tag("pt") << reg.points.body[k].value << reg.points.point[k].x << reg.points.point[k].y;
  const Ptpt2Table& lk = reg.links;
  o.tag("links") << static_cast<std::uint64_t>(lk.size());
  for (std::size_t k = 0; k < lk.size(); ++k)
    o.tag("lk") << lk.candidate[k].value << lk.antagonist[k].value << lk.law[k].k << lk.law[k].nu << lk.law[k].L0
                << lk.law[k].eps0 << lk.rn[k];
  o.tag("warm") << static_cast<std::uint64_t>(warm_start.size());
  for (const auto& w : warm_start) o.tag("w") << w.pair << w.feature << w.rn << w.rt;
  o.tag("extra") << static_cast<std::uint64_t>(extra.size());
  for (const auto& [key, value] : extra) o.tag("x") << key << value;
  buf << "\nend\n";

  const std::filesystem::path tmp = file.string() + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw Error("cannot write checkpoint '" + tmp.string() + "'");
    const std::string s = buf.str();
    f.write(s.data(), static_cast<std::streamsize>(s.size()));
    f.flush();
    if (!f) throw Error("error while writing checkpoint '" + tmp.string() + "' (disk full?)");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) throw Error("cannot rename '" + tmp.string() + "' to '" + file.string() + "': " + ec.message());
}

Checkpoint load_checkpoint(const std::filesystem::path& file) {
  std::ifstream f(file);
  if (!f) throw Error("cannot open checkpoint '" + file.string() + "'");
  In in{f, file};
  std::string magic;
  int version = 0;
  if (!(f >> magic >> version) || magic != kMagic) in.fail("not an nscd checkpoint");
  if (version != kVersion) in.fail("version " + std::to_string(version) + " is not supported (expected " + std::to_string(kVersion) + ")");
  Checkpoint cp;
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
  const int def = in.integer<int>();
  for (std::size_t i = 0; i < nl; ++i) {
    in.expect("l");
    LawSpec l;
    l.kind = static_cast<LawKind>(in.integer<int>());
    l.mu = in.real();
    l.e_n = in.real();
    l.e_t = in.real();
    validate(l);
    reg.contact_laws.laws.push_back(l);
  }
  reg.contact_laws.default_law = def;
  in.expect("pairs");
  if (in.integer<std::size_t>() != nm) in.fail("contact-law table size does not match the materials");
  for (auto& k : reg.contact_laws.pair_law) k = in.integer<int>();
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
    const auto dof = static_cast<Dof>(in.integer<int>());
    const auto drive = static_cast<Drive>(in.integer<int>());
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
    const auto nv = in.integer<std::uint32_t>();
    Polygon v(nv);
    for (auto& p : v) p = {in.real(), in.real()};
    attach_polyg(reg, body, v);
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
    add_spring(reg, cd, an, law);
    reg.links.rn.back() = rn;
  }
  in.expect("warm");
  const auto nw = in.integer<std::size_t>();
  for (std::size_t i = 0; i < nw; ++i) {
    in.expect("w");
    MoreauJean::WarmStartEntry w;
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
  return cp;
}

}  // namespace nscd
