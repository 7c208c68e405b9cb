// nscd/shared/samples.cpp — see samples.hpp.
#include "nscd/shared/samples.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/contactors/round_shapes.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/text_reader.hpp"

namespace nscd::scenes {
namespace {

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

// The polygons of a body are marked big so that walls stay out of the broad-phase grid
// (otherwise the tiles would have to be as large as the floor).
void mark_big(Registry& reg, BodyId b) {
  for (std::size_t p = 0; p < reg.polyg.size(); ++p)
    if (reg.polyg.body[p] == b) reg.polyg.is_big[p] = 1;
}

BodyId add_wall(Registry& reg, MaterialId m, double w, double h, Vec2 centre, const std::string& name) {
  const BodyId b = add_polygon_body(reg, rectangle(w, h), m, centre, 0.0, name);
  fix_body(reg, b);
  mark_big(reg, b);
  return b;
}

// Material and contact law of the paper (§3): ρ = 2367 kg/m³, restitution 0, μ = 0.5.
MaterialId paper_material(Registry& reg, const std::string& name) {
  const MaterialId m = add_material(reg, name, kPaperDensity);
  if (reg.contact_laws.default_law < 0) set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, kPaperFriction, 0.0, 0.0});
  return m;
}

}  // namespace

BoxWalls add_box(Registry& reg, MaterialId material, double width, double height, double t) {
  if (!positive(width) || !positive(height) || !positive(t))
    throw Error("add_box: width, height and wall thickness must be finite and > 0, got " + exact(width) +
                ", " + exact(height) + ", " + exact(t));
  BoxWalls w;
  // Floor: top face at y = 0, running under both walls.
  w.floor = add_wall(reg, material, width + 2.0 * t, t, {0.5 * width, -0.5 * t}, "floor");
  // Walls: from the floor's bottom (y = −t) up to y = height, inner faces at x = 0 and x = width.
  const double wall_h = height + t, wall_y = 0.5 * (height - t);
  w.left = add_wall(reg, material, t, wall_h, {-0.5 * t, wall_y}, "left wall");
  w.right = add_wall(reg, material, t, wall_h, {width + 0.5 * t, wall_y}, "right wall");
  return w;
}

BoxWalls add_jonc_box(Registry& reg, MaterialId material, double width, double height, double b) {
  if (!positive(width) || !positive(height) || !positive(b))
    throw Error("add_jonc_box: width, height and half-thickness must be finite and > 0, got " + exact(width) + ", " +
                exact(height) + ", " + exact(b));
  const double t = 2.0 * b;
  BoxWalls w;
  // a jonc's flat faces span its core segment: 2 × half_length; vertical walls turned by 90°
  w.floor = add_jonc_body(reg, 0.5 * width + t, b, material, {0.5 * width, -b}, 0.0, "floor");
  const double wall_half = 0.5 * (height + t), wall_y = 0.5 * (height - t);
  w.left = add_jonc_body(reg, wall_half, b, material, {-b, wall_y}, 0.5 * kPi, "left wall");
  w.right = add_jonc_body(reg, wall_half, b, material, {width + b, wall_y}, 0.5 * kPi, "right wall");
  for (BodyId id : {w.floor, w.left, w.right}) fix_body(reg, id);
  return w;
}

std::vector<BodyId> add_pentagons_on_lattice(Registry& reg, MaterialId material, std::span<const double> diameters,
                                             const LatticeSpec& L) {
  if (L.columns <= 0) throw Error("add_pentagons_on_lattice: columns must be > 0, got " + std::to_string(L.columns));
  if (!positive(L.pitch_x) || !positive(L.pitch_y) || !std::isfinite(L.x0) || !std::isfinite(L.y0))
    throw Error("add_pentagons_on_lattice: pitches must be finite and > 0 and the origin finite");
  std::mt19937_64 rng(L.seed);
  const double period = 2.0 * kPi / 5.0;  // a regular pentagon maps onto itself every 72°
  const auto cols = static_cast<std::size_t>(L.columns);
  std::vector<BodyId> out;
  out.reserve(diameters.size());
  for (std::size_t i = 0; i < diameters.size(); ++i) {
    const Vec2 site{L.x0 + static_cast<double>(i % cols) * L.pitch_x, L.y0 + static_cast<double>(i / cols) * L.pitch_y};
    const double angle = period * uniform01(rng);
    out.push_back(add_polygon_body(reg, regular_polygon(5, diameters[i]), material, site, angle,
                                   "grain " + std::to_string(i)));
  }
  return out;
}

Scene paper_sample(const SampleOptions& opt) {
  if (!positive(opt.box_width) || !positive(opt.wall_thickness) || !positive(opt.pitch_factor))
    throw Error("paper_sample: box width, wall thickness and pitch factor must be finite and > 0");
  const Grading g = opt.grains > 0 ? paper_grading(opt.grains) : paper_grading();
  const double dmax = largest_diameter(paper_grading());  // the lattice of the full grading, whatever n
  const double pitch = opt.pitch_factor * dmax;
  const double clear = kClearanceFactor * dmax;

  // Columns: the first and last grains (diameter up to d_max) keep the clearance to the walls,
  //   (columns − 1)·pitch + d_max + 2c <= width.
  const double span = opt.box_width - dmax - 2.0 * clear;
  if (span < 0.0)
    throw Error("paper_sample: box width " + exact(opt.box_width) + " m is narrower than one grain plus clearances (" +
                exact(dmax + 2.0 * clear) + " m)");
  const int columns = static_cast<int>(std::floor(span / pitch + 1e-9)) + 1;
  const std::size_t n = grain_count(g);
  const std::size_t rows = (n + static_cast<std::size_t>(columns) - 1) / static_cast<std::size_t>(columns);

  Scene s;
  s.grain_material = paper_material(s.reg, "ballast");
  s.wall_material = add_material(s.reg, "wall", kPaperDensity);
  s.lattice.columns = columns;
  s.lattice.pitch_x = s.lattice.pitch_y = pitch;
  s.lattice.x0 = 0.5 * (opt.box_width - (columns - 1) * pitch);  // lattice centred between the walls
  s.lattice.y0 = clear + 0.5 * dmax;
  s.lattice.seed = opt.seed;
  s.box_width = opt.box_width;
  s.box_height = s.lattice.y0 + static_cast<double>(rows - 1) * pitch + 0.5 * dmax + clear;

  s.walls = add_box(s.reg, s.wall_material, s.box_width, s.box_height, opt.wall_thickness);
  // The shuffle and the orientations draw from two streams derived from the one seed.
  const std::vector<double> d = expand_grading(g, opt.seed);
  LatticeSpec orient = s.lattice;
  orient.seed = opt.seed ^ 0x9E3779B97F4A7C15ull;
  s.grains = add_pentagons_on_lattice(s.reg, s.grain_material, d, orient);
  return s;
}

double scaled_box_width(std::size_t n) {
  if (n == 0) throw Error("scaled_box_width: needs at least one grain");
  const double dmax = largest_diameter(paper_grading());
  const double paper_n = static_cast<double>(grain_count(paper_grading()));
  return std::max(kPaperBoxWidth * static_cast<double>(n) / paper_n, dmax * (1.0 + 2.0 * kClearanceFactor) + 1e-6);
}

Scene paper_sample_loose(std::uint64_t seed) {
  SampleOptions o;
  o.seed = seed;
  o.pitch_factor = kLoosePitchFactor;
  return paper_sample(o);
}

Scene paper_sample_packed(std::uint64_t seed) {
  SampleOptions o;
  o.seed = seed;
  o.pitch_factor = kPackedPitchFactor;
  return paper_sample(o);
}

void converge_to_centroid(Registry& reg, double rate) {
  const std::size_t n = reg.bodies.size();
  double cx = 0.0, cy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    cx += reg.bodies.x[i] / static_cast<double>(n);
    cy += reg.bodies.y[i] / static_cast<double>(n);
  }
  for (std::size_t i = 0; i < n; ++i) {
    reg.bodies.vx[i] = -rate * (reg.bodies.x[i] - cx);
    reg.bodies.vy[i] = -rate * (reg.bodies.y[i] - cy);
  }
}

Scene pentagon_field(std::size_t n, double diameter, double pitch, std::uint64_t seed) {
  if (n == 0) throw Error("pentagon_field: needs at least one pentagon");
  if (!positive(diameter) || !positive(pitch)) throw Error("pentagon_field: diameter and pitch must be finite and > 0");
  Scene s;
  s.grain_material = paper_material(s.reg, "ballast");
  s.lattice.columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  s.lattice.pitch_x = s.lattice.pitch_y = pitch;
  s.lattice.x0 = s.lattice.y0 = 0.5 * pitch;
  s.lattice.seed = seed;
  const std::vector<double> d(n, diameter);
  s.grains = add_pentagons_on_lattice(s.reg, s.grain_material, d, s.lattice);
  return s;
}

}  // namespace nscd::scenes
