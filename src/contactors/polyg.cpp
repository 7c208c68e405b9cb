// nscd/contactors/polyg.cpp — see polyg.hpp.
#include "nscd/contactors/polyg.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/core/error.hpp"

namespace nscd {
namespace {

std::string fmt(Vec2 p) {
  std::ostringstream s;
  s.precision(6);
  s << '(' << p.x << ", " << p.y << ')';
  return s.str();
}

// Relative tolerance under which a turn or a length counts as zero.
constexpr double kRelTol = 1e-10;

// A POLYG's vertex count must fit the contact feature ids.
void check_vertex_count(std::size_t n, const std::string& who) {
  if (n > kMaxPolygVertices)
    throw Error("POLYG of " + who + ": at most " + std::to_string(kMaxPolygVertices) + " vertices, got " +
                std::to_string(n));
}

}  // namespace

void validate_polygon(std::span<const Vec2> v, const std::string& context) {
  const std::string who = "POLYG of " + context + ": ";
  const std::size_t n = v.size();
  if (n < 3) throw Error(who + "needs at least 3 vertices, got " + std::to_string(n));
  double scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(v[i].x) || !std::isfinite(v[i].y))
      throw Error(who + "vertex " + std::to_string(i) + " is not finite");
    scale = std::max({scale, std::abs(v[i].x - v[0].x), std::abs(v[i].y - v[0].y)});
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    if (norm(v[j] - v[i]) <= kRelTol * scale)
      throw Error(who + "vertex " + std::to_string(j) + " repeats vertex " + std::to_string(i) + " at " + fmt(v[i]));
  }
  // Shoelace sum relative to the first vertex: with absolute coordinates a small polygon far
  // from the origin loses its area to cancellation (a 0.1 mm grain at 10 km read as zero area).
  double twice_area = 0.0;
  for (std::size_t i = 0; i < n; ++i) twice_area += cross(v[i] - v[0], v[(i + 1) % n] - v[0]);
  if (std::abs(twice_area) <= kRelTol * scale * scale)
    throw Error(who + "area is zero (all vertices collinear)");
  if (twice_area < 0.0)
    throw Error(who + "vertices are clockwise; give them counter-clockwise (area " + std::to_string(0.5 * twice_area) +
                ")");
  double turning = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = v[(i + n - 1) % n], b = v[i], c = v[(i + 1) % n];
    const Vec2 e1 = b - a, e2 = c - b;
    const double s = cross(e1, e2);
    if (std::abs(s) <= kRelTol * norm(e1) * norm(e2))
      throw Error(who + "vertices " + std::to_string((i + n - 1) % n) + ", " + std::to_string(i) + ", " +
                  std::to_string((i + 1) % n) + " are collinear (degenerate vertex " + std::to_string(i) + " at " +
                  fmt(b) + ")");
    if (s < 0.0) throw Error(who + "not convex: reflex angle at vertex " + std::to_string(i) + " " + fmt(b));
    turning += std::atan2(s, dot(e1, e2));
  }
  if (std::abs(turning - 2.0 * kPi) > 1e-6)
    throw Error(who + "edges wind around more than once (self-intersecting); total turning " + std::to_string(turning) +
                " rad");
}

Polygon regular_polygon(int n, double d, double orientation) {
  if (n < 3) throw Error("regular_polygon: needs n >= 3, got " + std::to_string(n));
  if (!(d > 0.0) || !std::isfinite(d)) throw Error("regular_polygon: diameter must be finite and > 0");
  Polygon p(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double a = orientation + 2.0 * kPi * k / n;
    p[static_cast<std::size_t>(k)] = {0.5 * d * std::cos(a), 0.5 * d * std::sin(a)};
  }
  return p;
}

Polygon rectangle(double w, double h) {
  if (!(w > 0.0) || !(h > 0.0) || !std::isfinite(w) || !std::isfinite(h))
    throw Error("rectangle: width and height must be finite and > 0");
  return {{-0.5 * w, -0.5 * h}, {0.5 * w, -0.5 * h}, {0.5 * w, 0.5 * h}, {-0.5 * w, 0.5 * h}};
}

Polygon transformed(std::span<const Vec2> v, Vec2 offset, double angle) {
  const Rot2 r = Rot2::of(angle);
  Polygon out;
  out.reserve(v.size());
  for (Vec2 p : v) out.push_back(offset + r.apply(p));
  return out;
}

MassProperties mass_properties(std::span<const Vec2> v) {
  if (v.size() < 3) throw Error("mass_properties: needs at least 3 vertices, got " + std::to_string(v.size()));
  // Shoelace sums relative to the first vertex, to limit cancellation far from the origin.
  const Vec2 o = v[0];
  double a2 = 0.0, j = 0.0;
  Vec2 c{};
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 p = v[i] - o, q = v[(i + 1) % v.size()] - o;
    const double w = cross(p, q);
    a2 += w;
    c += w * (p + q);
    j += w * (dot(p, p) + dot(p, q) + dot(q, q));
  }
  MassProperties m;
  m.area = 0.5 * a2;
  const Vec2 cl = (1.0 / (3.0 * a2)) * c;
  m.centroid = o + cl;
  m.polar_moment = j / 12.0 - m.area * dot(cl, cl);
  return m;
}

PolygId attach_polyg(Registry& reg, BodyId body, std::span<const Vec2> v) {
  if (!body.valid() || body.index() >= reg.bodies.size()) throw Error("attach_polyg: unknown body id");
  const std::string& bn = reg.bodies.name[body.index()];
  const std::string who = "body " + std::to_string(body.index()) + (bn.empty() ? "" : " '" + bn + "'");
  check_vertex_count(v.size(), who);
  validate_polygon(v, who);
  auto& t = reg.polyg;
  t.body.push_back(body);
  t.first_vertex.push_back(static_cast<std::uint32_t>(t.vertex.size()));
  t.vertex_count.push_back(static_cast<std::uint32_t>(v.size()));
  double r = 0.0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const Vec2 e = v[(k + 1) % v.size()] - v[k];
    t.vertex.push_back(v[k]);
    t.edge_normal.push_back(normalized(Vec2{e.y, -e.x}));  // outward for a counter-clockwise polygon
    r = std::max(r, norm(v[k]));
  }
  t.radius.push_back(r);
  const MassProperties mp = mass_properties(v);
  t.area.push_back(mp.area);
  t.centre.push_back(mp.centroid);
  t.is_big.push_back(0);
  return PolygId(static_cast<std::uint32_t>(t.size() - 1));
}

BodyId add_polygon_body(Registry& reg, std::span<const Polygon> shapes, MaterialId material, Vec2 position,
                        double angle, const std::string& name) {
  const std::string who = "body " + std::to_string(reg.bodies.size()) + (name.empty() ? "" : " '" + name + "'");
  if (shapes.empty()) throw Error(who + ": needs at least one polygon");
  if (!material.valid() || material.index() >= reg.materials.size()) throw Error(who + ": unknown material id");
  double area = 0.0;
  Vec2 first_moment{};
  for (const auto& s : shapes) {
    // everything attach_polyg checks is checked here, before the body exists, so that a bad
    // shape leaves the registry unchanged
    check_vertex_count(s.size(), who);
    validate_polygon(s, who);
    const MassProperties m = mass_properties(s);
    area += m.area;
    first_moment += m.area * m.centroid;
  }
  const Vec2 com = (1.0 / area) * first_moment;
  double polar = 0.0;  // parallel-axis theorem, shapes assumed not to overlap
  for (const auto& s : shapes) {
    const MassProperties m = mass_properties(s);
    polar += m.polar_moment + m.area * dot(m.centroid - com, m.centroid - com);
  }
  const double rho = reg.materials.density[material.index()];
  RigidBodySpec spec;
  spec.name = name;
  spec.material = material;
  spec.position = position + Rot2::of(angle).apply(com);
  spec.angle = angle;
  spec.mass = rho * area;
  spec.inertia = rho * polar;
  const BodyId b = add_body(reg, spec);
  for (const auto& s : shapes) {
    Polygon local;
    local.reserve(s.size());
    for (Vec2 p : s) local.push_back(p - com);
    attach_polyg(reg, b, local);
  }
  return b;
}

BodyId add_polygon_body(Registry& reg, const Polygon& shape, MaterialId material, Vec2 position, double angle,
                        const std::string& name) {
  return add_polygon_body(reg, std::span<const Polygon>(&shape, 1), material, position, angle, name);
}

void set_material_density(Registry& reg, MaterialId material, double density) {
  if (!material.valid() || material.index() >= reg.materials.size())
    throw Error("set_material_density: unknown material id");
  if (!(density > 0.0) || !std::isfinite(density))
    throw Error("material '" + reg.materials.name[material.index()] + "': density must be finite and > 0, got " +
                std::to_string(density));
  const double ratio = density / reg.materials.density[material.index()];
  reg.materials.density[material.index()] = density;
  for (std::size_t i = 0; i < reg.bodies.size(); ++i)
    if (reg.bodies.material[i] == material) {
      const BodyId b(static_cast<std::uint32_t>(i));
      set_mass(reg, b, reg.bodies.mass[i] * ratio, reg.bodies.inertia[i] * ratio);
    }
}

Vec2 world_vertex(const Registry& reg, PolygId p, std::uint32_t k) {
  const auto& t = reg.polyg;
  const std::size_t b = t.body[p.index()].index();
  const Rot2 r = Rot2::of(reg.bodies.angle[b]);
  return Vec2{reg.bodies.x[b], reg.bodies.y[b]} + r.apply(t.vertex[t.first_vertex[p.index()] + k]);
}

Polygon world_polygon(const Registry& reg, PolygId p) {
  Polygon out(reg.polyg.vertex_count[p.index()]);
  for (std::uint32_t k = 0; k < out.size(); ++k) out[k] = world_vertex(reg, p, k);
  return out;
}

// The POLYG row (contactor_row.hpp): the name, the bodies and the drawing. The detection of two
// polygons (interactions/plplx.cpp) and their checkpoint section (vertex lists of any length)
// are their own paths, the hot ones of a polygon scene.
namespace {
std::size_t polyg_count(const Registry& reg) { return reg.polyg.size(); }
BodyId polyg_body(const Registry& reg, std::uint32_t i) { return reg.polyg.body[i]; }
void polyg_draw(const Registry& reg, std::uint32_t p, KindOutline& out) {
  const PolygTable& t = reg.polyg;
  for (std::uint32_t k = t.first_vertex[p], e = k + t.vertex_count[p]; k < e; ++k) out.put(t.vertex[k]);
  out.end_cell();
}
}  // namespace

extern const ContactorKindRow kPolygRow;
const ContactorKindRow kPolygRow{
    .name = "POLYG", .tag = "p", .count = polyg_count, .body = polyg_body, .draw = polyg_draw};

}  // namespace nscd
