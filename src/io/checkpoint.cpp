// nscd/io/checkpoint.cpp — see checkpoint.hpp: the writer (the reader is checkpoint_read.cpp).
#include "nscd/io/checkpoint.hpp"

#include "nscd/io/atomic_file.hpp"
#include "nscd/io/checkpoint_format.hpp"

#include <cmath>
#include <iomanip>
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
using checkpoint_format::kVersion;

// The writer of the records: every value after a space, reals in hexfloat (exact, read back bit
// for bit); the first non-finite value is noted (`bad`), so that save_checkpoint can refuse it.
struct Out {
  std::ostream& os;
  std::string bad;   ///< the first non-finite value met: where it is (empty: none)
  std::string tag_;  ///< the record being written, and its index
  std::size_t index_ = 0;
  Out& operator<<(double v) {
    if (!std::isfinite(v) && bad.empty())
      bad = "'" + tag_ + "' record " + std::to_string(index_) + " holds " + exact(v);
    os << ' ' << std::hexfloat << v << std::defaultfloat;
    return *this;
  }
  Out& operator<<(std::int64_t v) { os << ' ' << v; return *this; }
  Out& operator<<(std::uint64_t v) { os << ' ' << v; return *this; }
  Out& operator<<(int v) { os << ' ' << v; return *this; }
  Out& operator<<(std::uint32_t v) { os << ' ' << v; return *this; }
  Out& operator<<(const std::string& s) { os << ' ' << std::quoted(s); return *this; }
  Out& tag(const char* t) {
    index_ = tag_ == t ? index_ + 1 : 0;
    tag_ = t;
    os << '\n' << t;
    return *this;
  }
};

void write_time_function(Out& o, const TimeFunction& f, const std::string& who) {
  if (f.kind() == TimeFunction::Kind::Lambda)
    throw Error("cannot checkpoint " + who + ": its boundary condition is a user lambda; re-impose it after loading");
  o << static_cast<int>(f.kind()) << f.A() << f.B() << f.frequency() << f.phase() << f.ramp_duration() << f.start();
}

// The materials, the contact laws and the law of each pair of materials.
void write_laws(Out& o, const Registry& reg) {
  o.tag("materials") << static_cast<std::uint64_t>(reg.materials.size());
  for (std::size_t i = 0; i < reg.materials.size(); ++i)
    o.tag("m") << reg.materials.name[i] << reg.materials.density[i];
  const ContactLawTable& lt = reg.contact_laws;
  o.tag("laws") << static_cast<std::uint64_t>(lt.laws.size()) << static_cast<int>(lt.default_law);
  for (const LawSpec& l : lt.laws) o.tag("l") << static_cast<int>(l.kind) << l.mu << l.e_n << l.e_t;
  o.tag("pairs") << static_cast<std::uint64_t>(lt.n_materials);
  for (std::int32_t k : lt.pair_law) o << static_cast<int>(k);
}

// The bodies and their fixed, driven and loaded degrees of freedom.
void write_bodies(Out& o, const Registry& reg) {
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
}

// One record per contactor of a kind: its tag, its body, its row's numbers.
void write_kind(Out& o, const Registry& reg, const ContactorKindRow& row) {
  if (row.save == nullptr)
    throw Error("cannot checkpoint contactor kind " + std::string(row.name) + ": its row has no save");
  const std::string tag(row.tag);
  std::vector<double> numbers(row.params.size());
  for (std::uint32_t i = 0, n = static_cast<std::uint32_t>(row.count(reg)); i < n; ++i) {
    row.save(reg, i, numbers.data());
    o.tag(tag.c_str()) << row.body(reg, i).value;
    for (double v : numbers) o << v;
  }
}

// The contactors: POLYGs, the round ones (version 4 on), the added kinds (version 5), the PT2Dx
// points and the PTPT2 links.
void write_contactors(Out& o, const Registry& reg, bool round) {
  const PolygTable& p = reg.polyg;
  o.tag("polyg") << static_cast<std::uint64_t>(p.size());
  for (std::size_t k = 0; k < p.size(); ++k) {
    o.tag("p") << p.body[k].value << static_cast<int>(p.is_big[k]) << p.vertex_count[k];
    for (std::uint32_t v = 0; v < p.vertex_count[k]; ++v)
      o << p.vertex[p.first_vertex[k] + v].x << p.vertex[p.first_vertex[k] + v].y;
  }
  if (round) {  // counts first, then each kind's records (its row's numbers)
    o.tag("round") << static_cast<std::uint64_t>(reg.diskx.size()) << static_cast<std::uint64_t>(reg.joncx.size())
                   << static_cast<std::uint64_t>(reg.xksid.size());
    for (ContactorKind k : {ContactorKind::DISKx, ContactorKind::JONCx, ContactorKind::xKSID})
      write_kind(o, reg, *kind_row(reg, static_cast<std::uint8_t>(k)));
  }
  if (!reg.added.row.empty()) {  // version 5: the added kinds, by name, in the order they were added
    o.tag("kinds") << static_cast<std::uint64_t>(reg.added.size());
    for (const ContactorKindRow* row : reg.added.row) {
      o.tag("kind") << std::string(row->name) << static_cast<std::uint64_t>(row->count(reg));
      write_kind(o, reg, *row);
    }
  }
  o.tag("points") << static_cast<std::uint64_t>(reg.points.size());
  for (std::size_t k = 0; k < reg.points.size(); ++k)
    o.tag("pt") << reg.points.body[k].value << reg.points.point[k].x << reg.points.point[k].y;
  const Ptpt2Table& lk = reg.links;
  o.tag("links") << static_cast<std::uint64_t>(lk.size());
  for (std::size_t k = 0; k < lk.size(); ++k)
    o.tag("lk") << lk.candidate[k].value << lk.antagonist[k].value << lk.law[k].k << lk.law[k].nu << lk.law[k].L0
                << lk.law[k].eps0 << lk.rn[k] << lk.length[k] << lk.normal[k].x << lk.normal[k].y;
}

}  // namespace

void save_checkpoint(const std::filesystem::path& file, const Registry& reg,
                     const ContactHistory& warm_start,
                     const std::map<std::string, std::string>& extra) {
  std::ostringstream buf;
  Out o{buf, {}, {}, 0};
  const bool added = !reg.added.row.empty();
  const bool round = added || !reg.diskx.empty() || !reg.joncx.empty() || !reg.xksid.empty();
  buf << kMagic << ' ' << (added ? kVersion : round ? 4 : 3);
  o.tag("time") << reg.time << reg.step;
  o.tag("params") << reg.params.dt << reg.params.theta << reg.params.gravity.x << reg.params.gravity.y
                  << reg.params.alert;
  write_laws(o, reg);
  write_bodies(o, reg);
  write_contactors(o, reg, round);
  o.tag("warm") << static_cast<std::uint64_t>(warm_start.size());
  for (const auto& w : warm_start) o.tag("w") << w.pair << w.feature << w.rn << w.rt;
  o.tag("extra") << static_cast<std::uint64_t>(extra.size());
  for (const auto& [key, value] : extra) o.tag("x") << key << value;
  buf << "\nend\n";
  // Never write a file that load_checkpoint would refuse: a non-finite value (a NaN force from
  // a user's function, a diverged run) is named here; any other value out of the reader's
  // range (checkpoint.hpp) is found by reading the text back before it is written.
  if (!o.bad.empty())
    throw Error("save_checkpoint '" + file.string() + "': refusing to write a non-finite state: " + o.bad);
  try {
    load_checkpoint_text(buf.str(), file.string(), reg.added.row);
  } catch (const Error& e) {
    throw Error("save_checkpoint '" + file.string() +
                "': refusing to write a state the reader would refuse: " + e.what());
  }

  // Written whole or not at all (atomic_write): the previous checkpoint stays intact until the
  // new one is complete; a failed write removes its partial .tmp.
  atomic_write(file, buf.str());
}

}  // namespace nscd
