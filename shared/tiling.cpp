// nscd/shared/tiling.cpp — see tiling.hpp.
#include "nscd/shared/tiling.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "nscd/registry/registry.hpp"

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

// The free bodies of a sample, each with its single polygon, and the highest grain top.
struct TileGrains {
  std::vector<std::size_t> grain, polyg_of;
  double top = 0.0;
};

TileGrains tile_grains(const Registry& sample) {
  TileGrains g;
  g.polyg_of.assign(sample.bodies.size(), SIZE_MAX);
  for (std::size_t p = 0; p < sample.polyg.size(); ++p) {
    const std::size_t b = sample.polyg.body[p].index();
    if (g.polyg_of[b] != SIZE_MAX && !sample.bodies.is_driven[b])
      throw Error("tile_scene: body '" + sample.bodies.name[b] + "' has more than one POLYG");
    g.polyg_of[b] = p;
  }
  for (std::size_t b = 0; b < sample.bodies.size(); ++b) {
    if (sample.bodies.is_driven[b] || g.polyg_of[b] == SIZE_MAX) continue;
    g.grain.push_back(b);
    g.top = std::max(g.top, sample.bodies.y[b] + sample.polyg.radius[g.polyg_of[b]]);
  }
  if (g.grain.empty()) throw Error("tile_scene: the sample has no free body to copy");
  return g;
}

// Where the copies go: copy k of sample body b at x_of(k, b) in the new box.
struct TileLayout {
  const Registry& sample;
  Seams seams;
  double width, pitch, left;  // the sample's inner width, copy to copy, its left inner face
  bool mirrored(std::size_t k) const { return seams == Seams::Mirrored && k % 2 == 1; }
  double x_of(std::size_t k, std::size_t b) const {
    const double x = sample.bodies.x[b] - left;
    return pitch * static_cast<double>(k) + (mirrored(k) ? width - x : x);
  }
};

// Every copy of every grain: (copy, sample body), in copy order, then re-ordered if asked.
std::vector<std::pair<std::size_t, std::size_t>> tile_body_order(const TileGrains& g, const TileLayout& at,
                                                                 std::size_t copies, TileOrder body_order) {
  const Registry& sample = at.sample;
  std::vector<std::pair<std::size_t, std::size_t>> order;
  order.reserve(g.grain.size() * copies);
  for (std::size_t k = 0; k < copies; ++k)
    for (const std::size_t b : g.grain) order.emplace_back(k, b);
  if (body_order == TileOrder::Rows) {
    double band = 0.0;  // the largest grain diameter
    for (const std::size_t b : g.grain) band = std::max(band, 2.0 * sample.polyg.radius[g.polyg_of[b]]);
    std::stable_sort(order.begin(), order.end(), [&](const auto& u, const auto& v) {
      const double ru = std::floor(sample.bodies.y[u.second] / band), rv = std::floor(sample.bodies.y[v.second] / band);
      if (ru != rv) return ru < rv;
      return at.x_of(u.first, u.second) < at.x_of(v.first, v.second);
    });
  }
  return order;
}

// Copy k of sample body b, with its single polygon p, its velocities and its material.
BodyId add_tile_copy(Scene& s, const TileLayout& at, std::size_t p, std::size_t k, std::size_t b) {
  const Registry& sample = at.sample;
  const auto first = sample.polyg.vertex.begin() + sample.polyg.first_vertex[p];
  Polygon shape(first, first + sample.polyg.vertex_count[p]);
  double angle = sample.bodies.angle[b], sign = 1.0;
  if (at.mirrored(k)) {
    // x -> W - x: world vertex X + R(a) v becomes M X + R(-a) M v, M = diag(-1, 1); the
    // reflected vertex list is clockwise, so it is reversed to stay counter-clockwise.
    for (Vec2& v : shape) v.x = -v.x;
    std::reverse(shape.begin(), shape.end());
    angle = -angle;
    sign = -1.0;
  }
  const BodyId id = add_polygon_body(s.reg, shape, sample.bodies.material[b], {at.x_of(k, b), sample.bodies.y[b]},
                                     angle, sample.bodies.name[b] + " copy " + std::to_string(k));
  const std::size_t i = id.index();
  s.reg.bodies.vx[i] = sign * sample.bodies.vx[b];
  s.reg.bodies.vy[i] = sample.bodies.vy[b];
  s.reg.bodies.spin[i] = sign * sample.bodies.spin[b];
  return id;
}

// Between copies k and k+1: a fixed column of 1 cm squares, its faces where the sample's walls were.
void add_seam_walls(Scene& s, const TileLayout& at, std::size_t copies) {
  const double side = kSeamWallThickness;
  std::vector<Polygon> column;
  for (double y = 0.5 * side; y - 0.5 * side < s.box_height; y += side)
    column.push_back(transformed(rectangle(side, side), {0.0, y}));
  for (std::size_t k = 0; k + 1 < copies; ++k) {
    const BodyId b = add_polygon_body(s.reg, column, s.wall_material,
                                      {at.pitch * static_cast<double>(k) + at.width + 0.5 * side, 0.0}, 0.0,
                                      "seam wall " + std::to_string(k));
    fix_body(s.reg, b);
  }
}

}  // namespace

double sample_box_width(const Registry& sample) {
  const double left = extreme_x(sample, body_named(sample, "left wall"), false);
  const double right = extreme_x(sample, body_named(sample, "right wall"), true);
  if (!(right > left)) throw Error("tile_scene: the sample's right wall is not right of its left wall");
  return right - left;
}

Scene tile_scene(const Registry& sample, std::size_t copies, Seams seams, TileOrder body_order) {
  if (copies == 0) throw Error("tile_scene: needs at least one copy");
  const double width = sample_box_width(sample);
  const std::size_t wall = body_named(sample, "left wall");
  const TileGrains g = tile_grains(sample);

  Scene s;
  s.reg.params = sample.params;
  for (std::size_t m = 0; m < sample.materials.size(); ++m)
    add_material(s.reg, sample.materials.name[m], sample.materials.density[m]);
  s.reg.contact_laws = sample.contact_laws;  // same materials in the same order: same table
  s.grain_material = sample.bodies.material[g.grain.front()];
  s.wall_material = sample.bodies.material[wall];
  const double pitch = width + (seams == Seams::Walls ? kSeamWallThickness : 0.0);  // copy to copy
  s.box_width = pitch * static_cast<double>(copies - 1) + width;
  s.box_height = g.top + 0.01;
  const double thickness = extreme_x(sample, wall, false) - extreme_x(sample, wall, true);
  s.walls = add_box(s.reg, s.wall_material, s.box_width, s.box_height, thickness > 0.0 ? thickness : kWallThickness);
  s.grains.reserve(g.grain.size() * copies);
  const TileLayout at{sample, seams, width, pitch, extreme_x(sample, wall, false)};
  for (const auto& [k, b] : tile_body_order(g, at, copies, body_order))
    s.grains.push_back(add_tile_copy(s, at, g.polyg_of[b], k, b));
  if (seams == Seams::Walls) add_seam_walls(s, at, copies);
  return s;
}

}  // namespace nscd::scenes
