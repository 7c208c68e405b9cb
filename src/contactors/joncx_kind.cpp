// nscd/contactors/joncx_kind.cpp — the JONCx row (contactor_row.hpp): LMGC90's "jonc", the
// segment offset ± half_length · axis thickened by half_thickness, the usual wall of a disk
// sample. Its table is round_tables.hpp, its attach and mass round_shapes.hpp, its narrow phases
// interactions/round_pairs.hpp.
#include <cmath>

#include "nscd/contactors/contactor_row.hpp"
#include "nscd/contactors/round_shapes.hpp"
#include "nscd/contactors/round_views.hpp"

namespace nscd {
namespace {

constexpr int kEndPoints = 12;  // VTK draws each round end with 12 segments
constexpr std::string_view kParams[] = {"offset x", "offset y", "axis x", "axis y", "half-length", "half-thickness"};

std::size_t count(const Registry& reg) { return reg.joncx.size(); }
BodyId body(const Registry& reg, std::uint32_t i) { return reg.joncx.body[i]; }

// A jonc is big (a wall, out of the grid) when its half-length plus half-thickness passes the big size.
void world(const Registry& reg, const Configuration& q, KindViews& views, KindBoxes& boxes) {
  const JoncxTable& jc = reg.joncx;
  std::vector<JoncView>& v = views.reset<JoncView>();
  v.resize(jc.size());
  for (std::size_t k = 0; k < jc.size(); ++k) {
    const std::size_t b = jc.body[k].index();
    const Vec2 c = world_point(q.x[b], q.y[b], q.angle[b], jc.offset[k]);
    const JoncView j{c, Rot2::of(q.angle[b]).apply(jc.axis[k]), jc.half_length[k], jc.half_thickness[k]};
    v[k] = j;
    const Vec2 e = j.half_length * j.axis;
    const double t = j.half_thickness;
    boxes.push({std::min(c.x - e.x, c.x + e.x) - t, std::min(c.y - e.y, c.y + e.y) - t},
               {std::max(c.x - e.x, c.x + e.x) + t, std::max(c.y - e.y, c.y + e.y) + t},
               boxes.is_big_size(j.half_length + t));
  }
}

// The outline: the +a end's half circle, then the −a end's.
void draw(const Registry& reg, std::uint32_t j, KindOutline& out) {
  const JoncxTable& jc = reg.joncx;
  const Vec2 u = jc.axis[j], m = perp(u);
  for (int end = 0; end < 2; ++end) {
    const double sign = end == 0 ? 1.0 : -1.0;
    const Vec2 c = jc.offset[j] + (sign * jc.half_length[j]) * u;
    for (int k = 0; k <= kEndPoints; ++k) {
      const double a = -0.5 * kPi + kPi * k / kEndPoints;  // from −m to +m around +u
      out.put(c + jc.half_thickness[j] * (sign * std::cos(a) * u + sign * std::sin(a) * m));
    }
  }
  out.end_cell();
}

void save(const Registry& reg, std::uint32_t i, double* n) {
  const JoncxTable& jc = reg.joncx;
  n[0] = jc.offset[i].x, n[1] = jc.offset[i].y, n[2] = jc.axis[i].x, n[3] = jc.axis[i].y;
  n[4] = jc.half_length[i], n[5] = jc.half_thickness[i];
}

// The axis as saved, bit for bit (attach_joncx would normalize it again).
void load(Registry& reg, BodyId b, const double* n) {
  const Vec2 axis{n[2], n[3]};
  if (!(std::abs(norm(axis) - 1.0) < 1e-9)) throw Error("JONCx: the axis must be a unit vector");
  attach_joncx(reg, b, {n[0], n[1]}, axis, n[4], n[5]);
  reg.joncx.axis.back() = axis;
}

}  // namespace

extern const ContactorKindRow kJoncxRow;
const ContactorKindRow kJoncxRow{.name = "JONCx", .tag = "jc", .params = kParams, .count = count, .body = body,
                                 .world = world, .draw = draw, .save = save, .load = load};

}  // namespace nscd
