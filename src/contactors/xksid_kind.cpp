// nscd/contactors/xksid_kind.cpp — the xKSID row (contactor_row.hpp): the disk-shaped hole of a
// ring (a drum), what touches it stays inside. Its table is round_tables.hpp, its attach
// round_shapes.hpp, its narrow phases interactions/round_pairs.hpp.
#include "nscd/contactors/circle_row.hpp"
#include "nscd/contactors/contactor_row.hpp"
#include "nscd/contactors/round_views.hpp"

namespace nscd {
namespace {

// VTK draws a ring as a band of quadrilaterals outside its hole (a filled cell would hide the
// drum's content), from r to (1 + kBand) r.
constexpr int kQuads = 64;
constexpr double kBand = 0.08;
using Row = CircleRow<&Registry::xksid, &attach_xksid>;

// The whole drum: always big, never in the grid.
void world(const Registry& reg, const Configuration& q, KindViews& views, KindBoxes& boxes) {
  const XksidTable& kd = reg.xksid;
  std::vector<RingView>& v = views.reset<RingView>();
  v.resize(kd.size());
  for (std::size_t k = 0; k < kd.size(); ++k) {
    const std::size_t b = kd.body[k].index();
    v[k] = {world_point(q.x[b], q.y[b], q.angle[b], kd.offset[k]), kd.radius[k]};
    boxes.push_circle(v[k].centre, kd.radius[k], true);
  }
}

void draw(const Registry& reg, std::uint32_t r, KindOutline& out) {
  const Vec2 o = reg.xksid.offset[r];
  const double ri = reg.xksid.radius[r], ro = (1.0 + kBand) * ri;
  for (int k = 0; k < kQuads; ++k) {
    const double a0 = 2.0 * kPi * k / kQuads, a1 = 2.0 * kPi * (k + 1) / kQuads;
    out.put(o + ri * Vec2{std::cos(a0), std::sin(a0)});
    out.put(o + ro * Vec2{std::cos(a0), std::sin(a0)});
    out.put(o + ro * Vec2{std::cos(a1), std::sin(a1)});
    out.put(o + ri * Vec2{std::cos(a1), std::sin(a1)});
    out.end_cell();
  }
}

}  // namespace

extern const ContactorKindRow kXksidRow;
constinit const ContactorKindRow kXksidRow = Row::row("xKSID", "kd", world, draw);

}  // namespace nscd
