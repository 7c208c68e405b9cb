// nscd/shared/drum.cpp — see drum.hpp.
#include "nscd/shared/drum.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/contactors/round_shapes.hpp"
#include "nscd/core/error.hpp"
#include "nscd/laws/material_pairs.hpp"
#include "nscd/shared/grading.hpp"

namespace nscd::scenes {

namespace {

void check_drum_options(const DrumOptions& o) {
  if (o.grains == 0) throw Error("drum scene: grains must be >= 1");
  if (!(o.r_min > 0.0) || !(o.r_max >= o.r_min) || !std::isfinite(o.r_max))
    throw Error("drum scene: radii must satisfy 0 < r_min <= r_max, got " + std::to_string(o.r_min) + ", " +
                std::to_string(o.r_max));
  if (!(o.fill > 0.0 && o.fill <= 0.5)) throw Error("drum scene: fill must lie in (0, 0.5], got " + std::to_string(o.fill));
  if (!(o.packing > 0.0 && o.packing < 1.0)) throw Error("drum scene: packing must lie in (0, 1)");
  if (!(o.density > 0.0) || !std::isfinite(o.density)) throw Error("drum scene: density must be finite and > 0");
  if (!(o.bump_radius >= 0.0) || !std::isfinite(o.bump_radius)) throw Error("drum scene: bump_radius must be finite and >= 0");
}

// The grains' radii, drawn first from the stream so that the orientations follow them.
std::vector<double> drum_grain_radii(const DrumOptions& o, std::mt19937_64& rng) {
  std::vector<double> radius(o.grains);
  for (double& r : radius) r = o.r_min + (o.r_max - o.r_min) * uniform01(rng);
  return radius;
}

// The free disk's radius from the fill fraction: fill π R² packing = Σ grain areas (a disk
// π r², a regular pentagon of circumradius r (5/2) sin 72° r²).
double drum_inner_radius(const DrumOptions& o, const std::vector<double>& radius) {
  double sum_r2 = 0.0;
  for (const double r : radius) sum_r2 += r * r;
  const double area_per_r2 = o.pentagons ? 2.5 * std::sin(0.4 * kPi) : kPi;
  return std::sqrt(area_per_r2 * sum_r2 / (kPi * o.fill * o.packing));
}

// The drum: a ring of thickness r_max (its mass matters to nothing: every dof is kinematic).
void add_drum_ring(DrumScene& d, const DrumOptions& o) {
  Registry& reg = d.reg;
  const double R = d.radius, Ro = R + o.r_max;
  RigidBodySpec ring;
  ring.name = "drum";
  ring.material = d.wall_material;
  ring.mass = o.density * kPi * (Ro * Ro - R * R);
  ring.inertia = 0.5 * ring.mass * (Ro * Ro + R * R);
  d.drum = add_body(reg, ring);
  attach_xksid(reg, d.drum, {0.0, 0.0}, R);
  fix_body(reg, d.drum);
  if (o.bump_radius > 0.0) {  // touching bumps centred on the ring: as many as its perimeter holds
    d.bumps = static_cast<std::size_t>(std::floor(kPi * R / o.bump_radius));
    for (std::size_t k = 0; k < d.bumps; ++k) {
      const double a = 2.0 * kPi * static_cast<double>(k) / static_cast<double>(d.bumps);
      attach_diskx(reg, d.drum, {R * std::cos(a), R * std::sin(a)}, o.bump_radius);
    }
  }
}

// The lattice sites inside the ring (a margin of 0.05 r_max to the wall), row by row from the
// bottom; in the last row the sites nearest the vertical axis.
std::vector<Vec2> drum_lattice_sites(const DrumOptions& o, double inner) {
  const double s = 2.05 * o.r_max, h = s * std::sqrt(3.0) / 2.0, reach = inner - 1.05 * o.r_max;
  std::vector<Vec2> sites;
  for (std::size_t j = 0; sites.size() < o.grains; ++j) {
    const double y = -reach + static_cast<double>(j) * h;
    if (y > reach) break;
    const double w = std::sqrt(std::max(0.0, reach * reach - y * y));
    const double shift = (j % 2 == 1) ? 0.5 * s : 0.0;
    std::vector<Vec2> row;
    const auto imax = static_cast<long long>(std::floor((w + shift) / s)) + 1;
    for (long long i = -imax; i <= imax; ++i) {
      const double x = static_cast<double>(i) * s - shift;
      if (std::abs(x) <= w) row.push_back({x, y});
    }
    std::stable_sort(row.begin(), row.end(), [](Vec2 a, Vec2 b) { return std::abs(a.x) < std::abs(b.x); });
    for (const Vec2& p : row) {
      if (sites.size() == o.grains) break;
      sites.push_back(p);
    }
  }
  if (sites.size() < o.grains)
    throw Error("drum scene: the lattice in the ring holds " + std::to_string(sites.size()) + " grains, fewer than " +
                std::to_string(o.grains) + " (lower the fill fraction)");
  return sites;
}

void add_drum_grains(DrumScene& d, const DrumOptions& o, const std::vector<double>& radius,
                     const std::vector<Vec2>& sites, std::mt19937_64& rng) {
  for (std::size_t k = 0; k < o.grains; ++k) {
    if (o.pentagons) {  // orientations uniform over a pentagon's period, from the same stream
      const double angle = 0.4 * kPi * uniform01(rng);
      d.grains.push_back(add_polygon_body(d.reg, regular_polygon(5, 2.0 * radius[k]), d.grain_material, sites[k], angle,
                                          "pentagon " + std::to_string(k)));
    } else {
      d.grains.push_back(add_disk_body(d.reg, radius[k], d.grain_material, sites[k], "disk " + std::to_string(k)));
    }
  }
}

}  // namespace

DrumScene drum_scene(const DrumOptions& o) {
  check_drum_options(o);
  DrumScene d;
  d.grain_material = add_material(d.reg, "grain", o.density);
  d.wall_material = add_material(d.reg, "drum", o.density);
  // one stream: the radii, then (pentagons) the orientations
  std::mt19937_64 rng(o.seed);
  const std::vector<double> radius = drum_grain_radii(o, rng);
  const double inner = drum_inner_radius(o, radius);
  d.radius = inner + o.bump_radius;  // the bumps stand on the ring, around the free disk
  d.inner_radius = inner;
  // the drum's body first, then the grains on the lattice sites
  add_drum_ring(d, o);
  add_drum_grains(d, o, radius, drum_lattice_sites(o, inner), rng);
  return d;
}

namespace {

// How far each body's contactors reach from its centre of mass (a DISKx: |offset| + r, a POLYG:
// its farthest vertex); 0 for bodies without one.
std::vector<double> body_reach(const Registry& reg) {
  std::vector<double> reach(reg.bodies.size(), 0.0);
  for (std::size_t k = 0; k < reg.diskx.size(); ++k) {
    double& r = reach[reg.diskx.body[k].index()];
    r = std::max(r, norm(reg.diskx.offset[k]) + reg.diskx.radius[k]);
  }
  for (std::size_t k = 0; k < reg.polyg.size(); ++k) {
    double& r = reach[reg.polyg.body[k].index()];
    r = std::max(r, reg.polyg.radius[k]);
  }
  return reach;
}

}  // namespace

std::string grains_outside(const DrumScene& d, double tolerance) {
  const Registry& reg = d.reg;
  const BodyTable& b = reg.bodies;
  const Vec2 o{b.x[d.drum.index()], b.y[d.drum.index()]};
  const std::vector<double> grain_reach = body_reach(reg);
  for (const BodyId id : d.grains) {
    const std::size_t i = id.index();
    const double reach = norm(Vec2{b.x[i] - o.x, b.y[i] - o.y}) + grain_reach[i];
    if (!std::isfinite(reach) || reach > d.radius + tolerance)
      return "grain '" + reg.bodies.name[i] + "' lies outside the drum (its far edge at " + std::to_string(reach) +
             " m from the centre, the drum's radius " + std::to_string(d.radius) + " m)";
  }
  return {};
}

BedAngle bed_angle(const DrumScene& d) {
  const BodyTable& b = d.reg.bodies;
  const Vec2 o{b.x[d.drum.index()], b.y[d.drum.index()]};
  double m = 0.0;
  Vec2 g{0.0, 0.0};
  for (const BodyId id : d.grains) {
    const std::size_t i = id.index();
    m += b.mass[i];
    g += b.mass[i] * Vec2{b.x[i] - o.x, b.y[i] - o.y};
  }
  BedAngle a;
  if (!(m > 0.0)) {
    a.angle_deg = std::numeric_limits<double>::quiet_NaN();
    return a;
  }
  g *= 1.0 / m;
  a.centre_of_mass = g;
  a.distance = norm(g);
  // the angle of OG from the downward vertical (0, −1), positive toward +x
  a.angle_deg = std::atan2(g.x, -g.y) * 180.0 / kPi;
  return a;
}

BedMotion bed_motion(const DrumScene& d) {
  const BodyTable& b = d.reg.bodies;
  const std::size_t o = d.drum.index();
  BedMotion m;
  double l = 0.0, inertia = 0.0;
  for (const BodyId id : d.grains) {
    const std::size_t i = id.index();
    const Vec2 r{b.x[i] - b.x[o], b.y[i] - b.y[o]};
    l += b.mass[i] * cross(r, Vec2{b.vx[i], b.vy[i]});
    inertia += b.mass[i] * dot(r, r);
  }
  m.spin = inertia > 0.0 ? l / inertia : 0.0;
  // U_T = t·(v_c − v_a) + ω_c cross(r_c, t) − ω_a cross(r_a, t) (docs/theory.md §6), with the
  // lever arms of the last detection
  const ContactTable& c = d.reg.contacts;
  double slip = 0.0;
  for (std::size_t k = 0; k < c.size(); ++k) {
    if (c.an_body[k] != d.drum || !(c.rn[k] > 0.0)) continue;
    const std::size_t i = c.cd_body[k].index(), a = c.an_body[k].index();
    const Vec2 t = perp(c.normal[k]);
    const double ut = dot(t, Vec2{b.vx[i] - b.vx[a], b.vy[i] - b.vy[a]}) + b.spin[i] * c.cd_rt[k] - b.spin[a] * c.an_rt[k];
    slip += std::abs(ut);
    ++m.wall_contacts;
  }
  m.wall_slip = m.wall_contacts > 0 ? slip / static_cast<double>(m.wall_contacts) : 0.0;
  return m;
}

double surface_fit_angle(const DrumScene& d) {
  const BodyTable& b = d.reg.bodies;
  const Registry& reg = d.reg;
  const std::vector<double> grain_radius = body_reach(reg);  // a grain's top: its centre's y plus its reach
  double r_max = 0.0, x_lo = INFINITY, x_hi = -INFINITY;
  for (const BodyId id : d.grains) r_max = std::max(r_max, grain_radius[id.index()]);
  for (const BodyId id : d.grains) x_lo = std::min(x_lo, b.x[id.index()]), x_hi = std::max(x_hi, b.x[id.index()]);
  const double mid = 0.5 * (x_lo + x_hi), half = 0.3 * (x_hi - x_lo), width = 2.0 * r_max;
  if (!(half > 0.0) || !(width > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  const auto columns = static_cast<std::size_t>(std::ceil(2.0 * half / width));
  std::vector<double> top(columns, -INFINITY);
  for (const BodyId id : d.grains) {
    const std::size_t i = id.index();
    const double u = (b.x[i] - (mid - half)) / width;
    if (u < 0.0 || u >= static_cast<double>(columns)) continue;
    double& t = top[static_cast<std::size_t>(u)];
    t = std::max(t, b.y[i] + grain_radius[i]);
  }
  double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (std::size_t c = 0; c < columns; ++c) {
    if (!std::isfinite(top[c])) continue;
    const double x = mid - half + (static_cast<double>(c) + 0.5) * width;
    n += 1.0, sx += x, sy += top[c], sxx += x * x, sxy += x * top[c];
  }
  const double den = n * sxx - sx * sx;
  if (n < 3.0 || !(den > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return std::atan((n * sxy - sx * sy) / den) * 180.0 / kPi;
}

double segment_fill(double radius, double distance) {
  if (!(radius > 0.0) || !std::isfinite(radius) || !(distance >= 0.0) || !std::isfinite(distance))
    throw Error("segment_fill: needs radius > 0 and distance >= 0 (finite)");
  // the centroid's distance falls from R (α → 0) to 0 (α = 2π) as the central angle α grows
  auto centroid = [radius](double alpha) {
    const double s = std::sin(0.5 * alpha);
    return 4.0 * radius * s * s * s / (3.0 * (alpha - std::sin(alpha)));
  };
  if (distance >= radius) return 0.0;
  double lo = 1e-6, hi = 2.0 * kPi;  // centroid(lo) > distance >= centroid(hi) = 0
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double m = 0.5 * (lo + hi);
    (centroid(m) > distance ? lo : hi) = m;
  }
  const double alpha = 0.5 * (lo + hi);
  return (alpha - std::sin(alpha)) / (2.0 * kPi);
}

}  // namespace nscd::scenes
