// nscd/shared/biaxial.cpp — see biaxial.hpp.
#include "nscd/shared/biaxial.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/contactors/round_shapes.hpp"
#include "nscd/core/error.hpp"
#include "nscd/shared/grading.hpp"

namespace nscd::scenes {

namespace {

// The four JONCx walls of half-thickness t, inner faces on x = 0, W and y = 0, H, long enough for
// the corners (the sample may shorten by half and widen by half without opening a corner); the
// bottom and left walls fixed, the top and right walls free along their normal only.
void add_biaxial_walls(BiaxialBox& b, double W, double H, double t) {
  Registry& reg = b.reg;
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
}

// A box without grains: no gravity, the grain and wall materials.
BiaxialBox zero_gravity_box(double density, double wall_density) {
  BiaxialBox b;
  b.reg.params.gravity = {0.0, 0.0};
  b.grain_material = add_material(b.reg, "grain", density);
  b.wall_material = add_material(b.reg, "wall", wall_density);
  return b;
}

}  // namespace

BiaxialBox biaxial_box(const BiaxialOptions& o) {
  if (o.grains == 0) throw Error("biaxial box: grains must be >= 1");
  if (!(o.r_min > 0.0) || !(o.r_max >= o.r_min) || !std::isfinite(o.r_max))
    throw Error("biaxial box: radii must satisfy 0 < r_min <= r_max, got " + std::to_string(o.r_min) + ", " +
                std::to_string(o.r_max));
  if (!(o.aspect > 0.0) || !std::isfinite(o.aspect) || !(o.density > 0.0) || !std::isfinite(o.density) ||
      !(o.wall_density > 0.0) || !std::isfinite(o.wall_density))
    throw Error("biaxial box: aspect, density and wall density must be finite and > 0");
  BiaxialBox b = zero_gravity_box(o.density, o.wall_density);
  Registry& reg = b.reg;
  // 1. the lattice: nx columns, ny rows, spacing s; the box's inner faces at 0, W and 0, H
  const double s = 2.1 * o.r_max;
  const auto nx = static_cast<std::size_t>(std::max(1.0, std::ceil(std::sqrt(static_cast<double>(o.grains) / o.aspect))));
  const std::size_t ny = (o.grains + nx - 1) / nx;
  const double W = static_cast<double>(nx) * s, H = static_cast<double>(ny) * s;
  std::mt19937_64 rng(o.seed);
  const double pentagon_area = 2.5 * std::sin(0.4 * kPi);  // a regular pentagon of circumradius 1
  for (std::size_t k = 0; k < o.grains; ++k) {
    const double r = o.r_min + (o.r_max - o.r_min) * uniform01(rng);
    const Vec2 c{(static_cast<double>(k % nx) + 0.5) * s, (static_cast<double>(k / nx) + 0.5) * s};
    if (o.pentagons) {  // the orientation uniform over a pentagon's period, from the same stream
      const double angle = 0.4 * kPi * uniform01(rng);
      b.grains.push_back(add_polygon_body(reg, regular_polygon(5, 2.0 * r), b.grain_material, c, angle, "pentagon " + std::to_string(k)));
      b.solid_area += pentagon_area * r * r;
    } else {
      b.grains.push_back(add_disk_body(reg, r, b.grain_material, c, "disk " + std::to_string(k)));
      b.solid_area += kPi * r * r;
    }
    b.radius.push_back(r);
  }
  // 2. the walls: JONCx of half-thickness r_max
  add_biaxial_walls(b, W, H, o.r_max);
  return b;
}

BiaxialBox hexagonal_biaxial_box(const HexagonalOptions& o) {
  if (o.columns < 2 || o.rows < 2)
    throw Error("hexagonal biaxial box: columns and rows must be >= 2, got " + std::to_string(o.columns) + ", " +
                std::to_string(o.rows));
  if (!(o.radius > 0.0) || !std::isfinite(o.radius) || !(o.density > 0.0) || !std::isfinite(o.density) ||
      !(o.wall_density > 0.0) || !std::isfinite(o.wall_density))
    throw Error("hexagonal biaxial box: radius, density and wall density must be finite and > 0");
  BiaxialBox b = zero_gravity_box(o.density, o.wall_density);
  Registry& reg = b.reg;
  // 1. the lattice: row k at y = r + k √3 r; even rows hold `columns` disks from x = r, odd rows
  //    one fewer, shifted by r: every disk touches its neighbours (gap 0), the even rows' end
  //    disks touch the side walls, the first and last rows the bottom and top walls
  const double r = o.radius, h = std::sqrt(3.0) * r;
  const double W = 2.0 * r * static_cast<double>(o.columns), H = 2.0 * r + h * static_cast<double>(o.rows - 1);
  for (std::size_t k = 0; k < o.rows; ++k) {
    const bool odd = k % 2 == 1;
    const std::size_t n = odd ? o.columns - 1 : o.columns;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 c{(odd ? 2.0 * r : r) + 2.0 * r * static_cast<double>(i), r + h * static_cast<double>(k)};
      b.grains.push_back(add_disk_body(reg, r, b.grain_material, c, "disk " + std::to_string(b.grains.size())));
      b.radius.push_back(r);
      b.solid_area += kPi * r * r;
    }
  }
  // 2. the walls, half as thick as a disk is wide
  add_biaxial_walls(b, W, H, r);
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

double Stress2::major() const {
  return 0.5 * (xx + yy) + std::sqrt(0.25 * (xx - yy) * (xx - yy) + xy * xy);
}
double Stress2::minor() const {
  return 0.5 * (xx + yy) - std::sqrt(0.25 * (xx - yy) * (xx - yy) + xy * xy);
}

Stress2 internal_stress(const BiaxialBox& b, const WallState& w, const std::vector<std::uint8_t>* only) {
  const BodyTable& bt = b.reg.bodies;
  const ContactTable& c = b.reg.contacts;
  auto is_wall = [&b](BodyId id) { return id == b.bottom || id == b.top || id == b.left || id == b.right; };
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  auto add = [&](BodyId body, Vec2 f, Vec2 p) {  // f on the grain `body`, at the point p
    if (is_wall(body) || (only != nullptr && (*only)[body.index()] == 0)) return;
    const Vec2 l{p.x - bt.x[body.index()], p.y - bt.y[body.index()]};
    sxx += f.x * l.x, syy += f.y * l.y, sxy += 0.5 * (f.x * l.y + f.y * l.x);
  };
  for (std::size_t k = 0; k < c.size(); ++k) {
    const Vec2 n = c.normal[k], tg = perp(n);
    const Vec2 f = c.rn[k] * n + c.rt[k] * tg;  // on the candidate; the antagonist gets −f
    add(c.cd_body[k], f, c.point[k]);
    add(c.an_body[k], -1.0 * f, c.point[k]);
  }
  const double area = w.width * w.height;
  if (!(area > 0.0)) return {};
  return {-sxx / area, -syy / area, -sxy / area};
}

void StressAverage::add(double dt, double sigma1, double sigma3, const Stress2& internal) {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw Error("stress average: dt must be finite and > 0, got " + std::to_string(dt));
  if (!std::isfinite(sigma1) || !std::isfinite(sigma3) || !std::isfinite(internal.xx) || !std::isfinite(internal.yy) ||
      !std::isfinite(internal.xy))
    throw Error("stress average: a stress is not finite");
  time_ += dt;
  s1_ += dt * sigma1;
  s3_ += dt * sigma3;
  in_.xx += dt * internal.xx, in_.yy += dt * internal.yy, in_.xy += dt * internal.xy;
  ++steps_;
}

double StressAverage::sigma1() const {
  if (steps_ == 0) throw Error("stress average: no step added");
  return s1_ / time_;
}
double StressAverage::sigma3() const {
  if (steps_ == 0) throw Error("stress average: no step added");
  return s3_ / time_;
}
Stress2 StressAverage::internal() const {
  if (steps_ == 0) throw Error("stress average: no step added");
  return {in_.xx / time_, in_.yy / time_, in_.xy / time_};
}

FrictionAngles friction_angles(const std::vector<double>& strain, const std::vector<double>& phi, double residual_from,
                               double peak_from) {
  if (strain.size() != phi.size()) throw Error("friction angles: strain and phi differ in size");
  if (phi.empty()) throw Error("friction angles: no row");
  FrictionAngles a;
  a.peak = -std::numeric_limits<double>::infinity();
  double sum = 0.0, sq = 0.0;
  std::size_t k0 = 0;  // the first row of the peak's search; the rows before it are left out of the means
  while (k0 < phi.size() && strain[k0] < peak_from) ++k0;
  for (std::size_t k = 0; k < phi.size(); ++k) {
    const std::size_t lo = std::max(k0, k >= 2 ? k - 2 : 0), hi = std::min(phi.size() - 1, k + 2);
    double m = 0.0;
    for (std::size_t j = lo; j <= hi; ++j) m += phi[j] / static_cast<double>(hi - lo + 1);
    if (k >= k0 && m > a.peak) a.peak = m, a.peak_strain = strain[k];
    if (strain[k] >= residual_from) sum += phi[k], sq += phi[k] * phi[k], ++a.residual_rows;
  }
  if (!std::isfinite(a.peak)) throw Error("friction angles: no row at strain >= " + std::to_string(peak_from));
  const auto n = static_cast<double>(a.residual_rows);
  a.residual = a.residual_rows > 0 ? sum / n : std::nan("");
  a.spread = a.residual_rows > 1 ? std::sqrt(std::max(0.0, sq / n - a.residual * a.residual)) : 0.0;
  return a;
}

double mobilized_friction_deg(double sigma1, double sigma3) {
  const double sum = sigma1 + sigma3;
  if (!(sum > 0.0)) return 0.0;
  return std::asin(std::clamp((sigma1 - sigma3) / sum, -1.0, 1.0)) * 180.0 / kPi;
}

double biaxial_packing_fraction(const BiaxialBox& b, const WallState& w) {
  return w.width > 0.0 && w.height > 0.0 ? b.solid_area / (w.width * w.height) : 0.0;
}

}  // namespace nscd::scenes
