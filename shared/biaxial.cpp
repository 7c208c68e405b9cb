// nscd/shared/biaxial.cpp — see biaxial.hpp.
#include "nscd/shared/biaxial.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/round_shapes.hpp"
#include "nscd/core/error.hpp"
#include "nscd/shared/grading.hpp"

namespace nscd::scenes {

BiaxialBox biaxial_box(const BiaxialOptions& o) {
  if (o.grains == 0) throw Error("biaxial box: grains must be >= 1");
  if (!(o.r_min > 0.0) || !(o.r_max >= o.r_min) || !std::isfinite(o.r_max))
    throw Error("biaxial box: radii must satisfy 0 < r_min <= r_max, got " + std::to_string(o.r_min) + ", " +
                std::to_string(o.r_max));
  if (!(o.aspect > 0.0) || !std::isfinite(o.aspect) || !(o.density > 0.0) || !std::isfinite(o.density))
    throw Error("biaxial box: aspect and density must be finite and > 0");
  BiaxialBox b;
  Registry& reg = b.reg;
  reg.params.gravity = {0.0, 0.0};
  b.grain_material = add_material(reg, "grain", o.density);
  b.wall_material = add_material(reg, "wall", o.density);
  // 1. the lattice: nx columns, ny rows, spacing s; the box's inner faces at 0, W and 0, H
  const double s = 2.1 * o.r_max;
  const auto nx = static_cast<std::size_t>(std::max(1.0, std::ceil(std::sqrt(static_cast<double>(o.grains) / o.aspect))));
  const std::size_t ny = (o.grains + nx - 1) / nx;
  const double W = static_cast<double>(nx) * s, H = static_cast<double>(ny) * s;
  std::mt19937_64 rng(o.seed);
  for (std::size_t k = 0; k < o.grains; ++k) {
    const double r = o.r_min + (o.r_max - o.r_min) * uniform01(rng);
    const Vec2 c{(static_cast<double>(k % nx) + 0.5) * s, (static_cast<double>(k / nx) + 0.5) * s};
    b.grains.push_back(add_disk_body(reg, r, b.grain_material, c, "disk " + std::to_string(k)));
  }
  // 2. the walls: JONCx of half-thickness r_max, long enough for the corners (the sample may
  //    shorten by half and widen by half without opening a corner)
  const double t = o.r_max;
  b.wall_half_thickness = t;
  const double hx = 0.75 * W + 2.0 * t, hy = 0.75 * H + 2.0 * t;
  b.bottom = add_jonc_body(reg, hx, t, b.wall_material, {0.5 * W, -t}, 0.0, "bottom wall");
  b.top = add_jonc_body(reg, hx, t, b.wall_material, {0.5 * W, H + t}, 0.0, "top wall");
  b.left = add_jonc_body(reg, hy, t, b.wall_material, {-t, 0.5 * H}, 0.5 * kPi, "left wall");
  b.right = add_jonc_body(reg, hy, t, b.wall_material, {W + t, 0.5 * H}, 0.5 * kPi, "right wall");
  fix_body(reg, b.bottom);
  fix_body(reg, b.left);
  fix_dof(reg, b.top, Dof::X);
  fix_dof(reg, b.top, Dof::Rot);
  fix_dof(reg, b.right, Dof::Y);
  fix_dof(reg, b.right, Dof::Rot);
  return b;
}

WallState wall_state(const BiaxialBox& b) {
  const BodyTable& bt = b.reg.bodies;
  const double t = b.wall_half_thickness;
  WallState w;
  w.width = (bt.x[b.right.index()] - t) - (bt.x[b.left.index()] + t);
  w.height = (bt.y[b.top.index()] - t) - (bt.y[b.bottom.index()] + t);
  // the walls are the antagonists of their contacts (DKJCx); what a wall pushes on the grains
  // is Σ (r_n n + r_t t) over its contacts; the grains push back as much
  double f_top = 0.0, f_right = 0.0;
  const ContactTable& c = b.reg.contacts;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const Vec2 n = c.normal[k], tg = perp(n);
    const Vec2 f = c.rn[k] * n + c.rt[k] * tg;
    if (c.an_body[k] == b.top) f_top -= f.y;
    else if (c.an_body[k] == b.right) f_right -= f.x;
  }
  w.sigma1 = w.width > 0.0 ? f_top / w.width : 0.0;
  w.sigma3 = w.height > 0.0 ? f_right / w.height : 0.0;
  return w;
}

double mobilized_friction_deg(double sigma1, double sigma3) {
  const double sum = sigma1 + sigma3;
  if (!(sum > 0.0)) return 0.0;
  return std::asin(std::clamp((sigma1 - sigma3) / sum, -1.0, 1.0)) * 180.0 / kPi;
}

double biaxial_packing_fraction(const BiaxialBox& b, const WallState& w) {
  double area = 0.0;
  for (std::size_t k = 0; k < b.reg.diskx.size(); ++k) area += kPi * b.reg.diskx.radius[k] * b.reg.diskx.radius[k];
  return w.width > 0.0 && w.height > 0.0 ? area / (w.width * w.height) : 0.0;
}

}  // namespace nscd::scenes
