// validation/extremes/scenes.cpp — scene builders of the extremes suite (extremes.hpp).
#include <cmath>
#include <cstdint>
#include <string>

#include "extremes.hpp"
#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"

namespace nscd::extremes {

Registry base_registry(double dt, double mu, double x0, double y0) {
  Registry reg;
  reg.params.dt = dt;
  reg.params.theta = 0.5;
  reg.params.alert = 1.25e-3;
  const MaterialId m = add_material(reg, "stone", 2000.0);
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, mu});
  const BodyId floor = add_polygon_body(reg, rectangle(40.0, 1.0), m, {x0, y0 - 0.5}, 0.0, "floor");
  fix_body(reg, floor);
  return reg;
}

std::vector<BodyId> add_stack(Registry& reg, int n, double ratio, bool light_bottom, double w, double h, double x0,
                              double y0) {
  const MaterialId m = find_material(reg, "stone");
  std::vector<BodyId> out;
  for (int k = 0; k < n; ++k) {
    const BodyId b = add_polygon_body(reg, rectangle(w, h), m, {x0, y0 + (k + 0.5) * h}, 0.0, "block " + std::to_string(k));
    const bool heavy = (k % 2 == 1) == light_bottom;
    if (heavy) set_mass(reg, b, ratio * reg.bodies.mass[b.index()], ratio * reg.bodies.inertia[b.index()]);
    out.push_back(b);
  }
  return out;
}

std::vector<BodyId> add_dropped_polygons(Registry& reg, int n, int vertices, double d, double width, double lift,
                                         double x0) {
  const MaterialId m = find_material(reg, "stone");
  const double pitch = 1.2 * d;
  const int cols = std::max(1, static_cast<int>(std::floor(width / pitch)));
  const int rows = (n + cols - 1) / cols;
  const double top = lift + rows * pitch + d;
  const double t = 0.1;  // wall thickness
  const BodyId left = add_polygon_body(reg, rectangle(t, top + t), m, {x0 - 0.5 * t, 0.5 * (top - t)}, 0.0, "left wall");
  const BodyId right = add_polygon_body(reg, rectangle(t, top + t), m, {x0 + width + 0.5 * t, 0.5 * (top - t)}, 0.0, "right wall");
  fix_body(reg, left);
  fix_body(reg, right);
  std::uint64_t s = 0x9E3779B97F4A7C15ull;  // orientations: a fixed xorshift sequence
  std::vector<BodyId> out;
  const double margin = 0.5 * (width - cols * pitch);
  for (int i = 0; i < n; ++i) {
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    const double angle = static_cast<double>(s >> 11) * 0x1.0p-53 * 6.283185307179586;
    const Vec2 at{x0 + margin + (0.5 + i % cols) * pitch, lift + (0.5 + i / cols) * pitch};
    out.push_back(add_polygon_body(reg, regular_polygon(vertices, d), m, at, angle, "grain " + std::to_string(i)));
  }
  return out;
}

std::vector<BodyId> add_pile(Registry& reg, int base, double d, double x0) {
  const MaterialId m = find_material(reg, "stone");
  const double pitch = 1.02 * d, row_dy = pitch * std::sqrt(3.0) / 2.0;
  std::uint64_t s = 0xD1B54A32D192ED03ull;
  std::vector<BodyId> out;
  for (int j = 0; j < base; ++j)
    for (int i = 0; i < base - j; ++i) {
      s ^= s << 13;
      s ^= s >> 7;
      s ^= s << 17;
      const double angle = static_cast<double>(s >> 11) * 0x1.0p-53 * 1.2566370614359172;
      const Vec2 at{x0 + (i + 0.5 * j) * pitch, 0.5 * d + j * row_dy};
      out.push_back(add_polygon_body(reg, regular_polygon(5, d), m, at, angle, "grain " + std::to_string(out.size())));
    }
  return out;
}

std::vector<BodyId> all_dynamic(const Registry& reg) {
  std::vector<BodyId> out;
  for (std::uint32_t i = 0; i < reg.bodies.size(); ++i)
    if (reg.bodies.inv_mass_y[i] != 0.0) out.push_back(BodyId(i));
  return out;
}

double total_energy(const Registry& reg) {
  const BodyTable& b = reg.bodies;
  double e = kinetic_energy(reg);
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b.inv_mass_x[i] == 0.0 && b.inv_mass_y[i] == 0.0 && b.inv_inertia[i] == 0.0) continue;
    e -= b.mass[i] * (reg.params.gravity.x * b.x[i] + reg.params.gravity.y * b.y[i]);
  }
  return e;
}

}  // namespace nscd::extremes
