// nscd/contactors/diskx_kind.cpp — the DISKx row (contactor_row.hpp): a disk of radius r centred
// at an offset in its body's frame. Its table is round_tables.hpp, its attach and mass
// round_shapes.hpp, its narrow phases interactions/round_pairs.hpp.
#include "nscd/contactors/circle_row.hpp"
#include "nscd/contactors/contactor_row.hpp"
#include "nscd/contactors/round_views.hpp"

namespace nscd {
namespace {

constexpr int kSides = 32;  // VTK draws a disk as a 32-gon
using Row = CircleRow<&Registry::diskx, &attach_diskx>;

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

}  // namespace

extern const ContactorKindRow kDiskxRow;
constinit const ContactorKindRow kDiskxRow = Row::row("DISKx", "dk", world, draw);

}  // namespace nscd
