// nscd/contactors/diskx_kind.cpp — the DISKx row (contactor_row.hpp): a disk of radius r centred
// at an offset in its body's frame. Its table is round_tables.hpp, its attach and mass
// round_shapes.hpp, its narrow phases interactions/round_pairs.hpp.
#include "nscd/contactors/contactor_row.hpp"
#include "nscd/contactors/round_shapes.hpp"
#include "nscd/contactors/round_views.hpp"

namespace nscd {
namespace {

constexpr int kSides = 32;  // VTK draws a disk as a 32-gon
constexpr std::string_view kParams[] = {"offset x", "offset y", "radius"};

std::size_t count(const Registry& reg) { return reg.diskx.size(); }
BodyId body(const Registry& reg, std::uint32_t i) { return reg.diskx.body[i]; }

// A disk is big (a wall, out of the grid) when its radius passes the big size.
void world(const Registry& reg, const Configuration& q, KindViews& views, KindBoxes& boxes) {
  const DiskxTable& dk = reg.diskx;
  std::vector<DiskView>& v = views.reset<DiskView>();
  v.resize(dk.size());
  for (std::size_t k = 0; k < dk.size(); ++k) {
    const std::size_t b = dk.body[k].index();
    v[k] = {world_point(q.x[b], q.y[b], q.angle[b], dk.offset[k]), dk.radius[k]};
    boxes.push_circle(v[k].centre, dk.radius[k], boxes.is_big_size(dk.radius[k]));
  }
}

void draw(const Registry& reg, std::uint32_t d, KindOutline& out) {
  for (int k = 0; k < kSides; ++k) {
    const double a = 2.0 * kPi * k / kSides;
    out.put(reg.diskx.offset[d] + reg.diskx.radius[d] * Vec2{std::cos(a), std::sin(a)});
  }
  out.end_cell();
}

void save(const Registry& reg, std::uint32_t i, double* n) {
  n[0] = reg.diskx.offset[i].x, n[1] = reg.diskx.offset[i].y, n[2] = reg.diskx.radius[i];
}
void load(Registry& reg, BodyId b, const double* n) { attach_diskx(reg, b, {n[0], n[1]}, n[2]); }

}  // namespace

extern const ContactorKindRow kDiskxRow;
const ContactorKindRow kDiskxRow{.name = "DISKx", .tag = "dk", .params = kParams, .count = count, .body = body,
                                 .world = world, .draw = draw, .save = save, .load = load};

}  // namespace nscd
