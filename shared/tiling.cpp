// nscd/shared/tiling.cpp — see tiling.hpp.
#include "nscd/shared/tiling.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "nscd/core/names.hpp"

namespace nscd::scenes {
namespace {

// World x of a body's polygon vertices: the smallest (inner face of a right wall) or the largest
// (inner face of a left wall).
double extreme_x(const Registry& reg, std::size_t body, bool smallest) {
  double best = smallest ? INFINITY : -INFINITY;
  const double c = std::cos(reg.bodies.angle[body]), s = std::sin(reg.bodies.angle[body]);
  for (std::size_t p = 0; p < reg.polyg.size(); ++p) {
    if (reg.polyg.body[p].index() != body) continue;
    for (std::uint32_t k = 0; k < reg.polyg.vertex_count[p]; ++k) {
      const Vec2 v = reg.polyg.vertex[reg.polyg.first_vertex[p] + k];
      const double x = reg.bodies.x[body] + c * v.x - s * v.y;
      best = smallest ? std::min(best, x) : std::max(best, x);
    }
  }
  return best;
}

std::size_t body_named(const Registry& reg, const std::string& name) {
  for (std::size_t b = 0; b < reg.bodies.size(); ++b)
    if (reg.bodies.name[b] == name) return b;
  throw Error("tile_scene: the sample has no body named '" + name + "' (a box built by add_box is expected)");
}

}  // namespace

double sample_box_width(const Registry& sample) {
  const double left = extreme_x(sample, body_named(sample, "left wall"), false);
  const double right = extreme_x(sample, body_named(sample, "right wall"), true);
  if (!(right > left)) throw Error("tile_scene: the sample's right wall is not right of its left wall");
  return right - left;
}

Scene tile_scene(const Registry& sample, std::size_t copies) {
  if (copies == 0) throw Error("tile_scene: needs at least one copy");
  const double width = sample_box_width(sample);
  const std::size_t wall = body_named(sample, "left wall");
  // the free bodies and their single polygon
  std::vector<std::size_t> grain, polyg_of(sample.bodies.size(), SIZE_MAX);
  for (std::size_t p = 0; p < sample.polyg.size(); ++p) {
    const std::size_t b = sample.polyg.body[p].index();
    if (polyg_of[b] != SIZE_MAX && !sample.bodies.is_driven[b])
      throw Error("tile_scene: body '" + sample.bodies.name[b] + "' has more than one POLYG");
    polyg_of[b] = p;
  }
  double top = 0.0;
  for (std::size_t b = 0; b < sample.bodies.size(); ++b) {
    if (sample.bodies.is_driven[b] || polyg_of[b] == SIZE_MAX) continue;
    grain.push_back(b);
    top = std::max(top, sample.bodies.y[b] + sample.polyg.radius[polyg_of[b]]);
  }
  if (grain.empty()) throw Error("tile_scene: the sample has no free body to copy");

  Scene s;
  s.reg.params = sample.params;
  for (std::size_t m = 0; m < sample.materials.size(); ++m)
    add_material(s.reg, sample.materials.name[m], sample.materials.density[m]);
  s.reg.contact_laws = sample.contact_laws;  // same materials in the same order: same table
  s.grain_material = sample.bodies.material[grain.front()];
  s.wall_material = sample.bodies.material[wall];
  s.box_width = width * static_cast<double>(copies);
  s.box_height = top + 0.01;
  const double thickness = extreme_x(sample, wall, false) - extreme_x(sample, wall, true);
  s.walls = add_box(s.reg, s.wall_material, s.box_width, s.box_height, thickness > 0.0 ? thickness : kWallThickness);
  s.grains.reserve(grain.size() * copies);
  for (std::size_t k = 0; k < copies; ++k) {
    const double shift = width * static_cast<double>(k);
    for (const std::size_t b : grain) {
      const std::size_t p = polyg_of[b];
      const Polygon shape(sample.polyg.vertex.begin() + sample.polyg.first_vertex[p],
                          sample.polyg.vertex.begin() + sample.polyg.first_vertex[p] + sample.polyg.vertex_count[p]);
      const BodyId id = add_polygon_body(s.reg, shape, sample.bodies.material[b],
                                         {sample.bodies.x[b] + shift, sample.bodies.y[b]}, sample.bodies.angle[b],
                                         sample.bodies.name[b] + " copy " + std::to_string(k));
      const std::size_t i = id.index();
      s.reg.bodies.vx[i] = sample.bodies.vx[b];
      s.reg.bodies.vy[i] = sample.bodies.vy[b];
      s.reg.bodies.spin[i] = sample.bodies.spin[b];
      s.grains.push_back(id);
    }
  }
  return s;
}

}  // namespace nscd::scenes
