// nscd/shared/ballast.cpp — see ballast.hpp.
#include "nscd/shared/ballast.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/contactors/pt2dx.hpp"
#include "nscd/core/error.hpp"
#include "nscd/interactions/ptpt2.hpp"
#include "nscd/io/text_reader.hpp"

namespace nscd::scenes {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw Error("ballast scene: " + what);
}
bool pos(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

void validate(const BallastOptions& o) {
  require(pos(o.box_width), "box width must be > 0");
  require(pos(o.pitch_factor), "pitch factor must be > 0");
  require(pos(o.grading_fraction) && o.grading_fraction <= 1000.0, "grading fraction must lie in (0, 1000]");
  require(std::isfinite(o.mu) && o.mu >= 0.0, "friction mu must be >= 0");
  require(o.pads >= 1, "needs at least one pad");
  require(pos(o.pad_height) && pos(o.pad_gap) && pos(o.pad_density), "pad height, gap and density must be > 0");
  require(std::isfinite(o.k) && o.k >= 0.0 && std::isfinite(o.nu) && o.nu >= 0.0, "spring k and nu must be >= 0");
  require(pos(o.spring_length) && std::isfinite(o.eps0), "spring length must be > 0 and the prestrain finite");
  require(pos(o.sleeper_width) && pos(o.sleeper_height) && pos(o.sleeper_density), "sleeper size and density must be > 0");
  require(o.bars >= 0 && (o.bars == 0 || pos(o.bar_size)), "bars must be >= 0 with a size > 0");
  require(o.sleeper_width < o.box_width, "the sleeper must be narrower than the box");
  const double pad_w = (o.box_width - (o.pads + 1) * o.pad_gap) / o.pads;
  require(pad_w > 0.0, "the pads do not fit in the box (too many pads or too large gaps)");
}

BallastScene ballast_sample(const BallastOptions& o) {
  validate(o);
  BallastScene s;
  Registry& reg = s.scene.reg;
  Grading g = paper_grading();
  for (GradingClass& c : g)
    c.count = static_cast<std::size_t>(std::max(1.0, std::round(o.grading_fraction * static_cast<double>(c.count))));
  const double dmax = largest_diameter(g);
  s.largest_diameter = dmax;

  // 1. Materials and the contact law (every pair: IQS_CLB, μ).
  s.scene.grain_material = add_material(reg, "ballast", kPaperDensity);
  s.scene.wall_material = add_material(reg, "wall", kPaperDensity);
  s.pad_material = add_material(reg, "pad", o.pad_density);
  s.sleeper_material = add_material(reg, "aluminium", o.sleeper_density);
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, o.mu, 0.0, 0.0});

  // 2. Start lattice above the pads, as in paper_sample (clearance 0.1 d_max).
  const double clear = kClearanceFactor * dmax;
  const double pad_top = o.spring_length + o.pad_height;
  const double pitch = o.pitch_factor * dmax;
  const double span = o.box_width - dmax - 2.0 * clear;
  require(span >= 0.0, "box narrower than one grain");
  const int columns = static_cast<int>(std::floor(span / pitch + 1e-9)) + 1;
  const std::size_t n = grain_count(g);
  const std::size_t rows = (n + static_cast<std::size_t>(columns) - 1) / static_cast<std::size_t>(columns);
  LatticeSpec lat;
  lat.columns = columns;
  lat.pitch_x = lat.pitch_y = pitch;
  lat.x0 = 0.5 * (o.box_width - (columns - 1) * pitch);
  lat.y0 = pad_top + clear + 0.5 * dmax;
  lat.seed = o.seed ^ 0x9E3779B97F4A7C15ull;
  s.scene.lattice = lat;
  s.scene.box_width = o.box_width;
  s.scene.box_height = lat.y0 + static_cast<double>(rows - 1) * pitch + 0.5 * dmax + clear;

  // 3. Box: walls and the ground (floor), fixed.
  s.scene.walls = add_box(reg, s.scene.wall_material, o.box_width, s.scene.box_height, kWallThickness);

  // 4. Sublayer: pads guided vertically, one spring each from the ground.
  const double pad_w = (o.box_width - (o.pads + 1) * o.pad_gap) / o.pads;
  for (int i = 0; i < o.pads; ++i) {
    const double xc = o.pad_gap + 0.5 * pad_w + i * (pad_w + o.pad_gap);
    const BodyId pad = add_polygon_body(reg, rectangle(pad_w, o.pad_height), s.pad_material,
                                        {xc, o.spring_length + 0.5 * o.pad_height}, 0.0, "pad " + std::to_string(i));
    fix_dof(reg, pad, Dof::X);
    fix_dof(reg, pad, Dof::Rot);
    const PointId top = attach_point_world(reg, pad, {xc, o.spring_length});
    const PointId anchor = attach_point_world(reg, s.scene.walls.floor, {xc, 0.0});
    s.springs.push_back(add_spring(reg, top, anchor, VoigtRod{o.k, o.nu, o.spring_length, o.eps0}));
    s.pads.push_back(pad);
  }

  // 5. Grains.
  const std::vector<double> d = expand_grading(g, o.seed);
  s.scene.grains = add_pentagons_on_lattice(reg, s.scene.grain_material, d, lat);
  return s;
}

BodyId place_sleeper(BallastScene& s, const BallastOptions& o) {
  Registry& reg = s.scene.reg;
  const double xc = 0.5 * s.scene.box_width;
  const double half = 0.5 * o.sleeper_width;
  // highest grain point under the footprint |x − xc| <= half: the vertices inside it, and the
  // points where edges cross its sides (a grain straddling a side, its top vertex just outside,
  // is highest there; counting vertices only would set the sleeper into it)
  double surface = -1e300;
  const double sides[2] = {xc - half, xc + half};
  for (BodyId gb : s.scene.grains)
    for (std::size_t k = 0; k < reg.polyg.size(); ++k) {
      if (reg.polyg.body[k] != gb) continue;
      const Polygon w = world_polygon(reg, PolygId(static_cast<std::uint32_t>(k)));
      for (std::size_t i = 0; i < w.size(); ++i) {
        const Vec2 a = w[i], b = w[(i + 1) % w.size()];
        if (std::abs(a.x - xc) <= half) surface = std::max(surface, a.y);
        for (const double x : sides)
          if ((a.x - x) * (b.x - x) < 0.0) surface = std::max(surface, a.y + (x - a.x) / (b.x - a.x) * (b.y - a.y));
      }
    }
  require(surface > -1e300, "no grain under the sleeper's footprint");
  const double clearance = 1e-3;
  const double bars_h = o.bars > 0 ? o.bar_size : 0.0;
  std::vector<Polygon> shapes{rectangle(o.sleeper_width, o.sleeper_height)};
  for (int i = 0; i < o.bars; ++i) {
    // bars evenly spaced along the lower face, flush with it
    const double x = o.bars == 1 ? 0.0 : -half + 0.5 * o.bar_size + i * (o.sleeper_width - o.bar_size) / (o.bars - 1);
    shapes.push_back(transformed(rectangle(o.bar_size, o.bar_size), {x, -0.5 * o.sleeper_height - 0.5 * o.bar_size}));
  }
  // shape frame: the rectangle's centre; its bottom (or the bars' bottom) `clearance` above the surface
  const Vec2 origin{xc, surface + clearance + bars_h + 0.5 * o.sleeper_height};
  s.sleeper = add_polygon_body(reg, shapes, s.sleeper_material, origin, 0.0, "sleeper");
  return s.sleeper;
}

BallastScene recognise_ballast(Registry&& reg) {
  BallastScene s;
  s.scene.reg = std::move(reg);
  Registry& r = s.scene.reg;
  const BodyTable& b = r.bodies;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const std::string& n = b.name[i];
    const BodyId id(static_cast<std::uint32_t>(i));
    if (n.rfind("grain ", 0) == 0) s.scene.grains.push_back(id);
    else if (n.rfind("pad ", 0) == 0) s.pads.push_back(id);
    else if (n == "sleeper") s.sleeper = id;
    else if (n == "floor") s.scene.walls.floor = id;
    else if (n == "left wall") s.scene.walls.left = id;
    else if (n == "right wall") s.scene.walls.right = id;
  }
  require(!s.scene.grains.empty() && !s.pads.empty() && s.scene.walls.floor.valid() && s.scene.walls.right.valid(),
          "the loaded scene has no grains, pads, floor or right wall: not a ballast sample");
  s.scene.grain_material = b.material[s.scene.grains[0].index()];
  s.pad_material = b.material[s.pads[0].index()];
  if (s.sleeper.valid()) s.sleeper_material = b.material[s.sleeper.index()];
  for (std::uint32_t k = 0; k < r.links.size(); ++k) s.springs.push_back(LinkId(k));
  // box width = the right wall's inner face; largest grain = twice the largest radius
  double inner = 1e300;
  for (std::size_t k = 0; k < r.polyg.size(); ++k) {
    if (r.polyg.body[k] == s.scene.walls.right)
      for (const Vec2 v : world_polygon(r, PolygId(static_cast<std::uint32_t>(k)))) inner = std::min(inner, v.x);
    else if (b.name[r.polyg.body[k].index()].rfind("grain ", 0) == 0)
      s.largest_diameter = std::max(s.largest_diameter, 2.0 * r.polyg.radius[k]);
  }
  s.scene.box_width = inner;
  return s;
}

std::string grain_below_sublayer(const BallastScene& s) {
  const Registry& r = s.scene.reg;
  if (s.pads.empty()) return {};
  double pad_top = std::numeric_limits<double>::infinity();
  for (std::uint32_t k = 0; k < r.polyg.size(); ++k)
    if (std::find(s.pads.begin(), s.pads.end(), r.polyg.body[k]) != s.pads.end()) {
      double top = -std::numeric_limits<double>::infinity();
      for (const Vec2& v : world_polygon(r, PolygId(k))) top = std::max(top, v.y);
      pad_top = std::min(pad_top, top);
    }
  for (const BodyId g : s.scene.grains) {
    const double y = r.bodies.y[g.index()];
    if (y < pad_top)
      return "grain '" + r.bodies.name[g.index()] + "' at (" + exact(r.bodies.x[g.index()]) + ", " + exact(y) +
             ") m has left the layer through the sublayer (its centre is below the lowest pad top, y = " + exact(pad_top) + " m)";
  }
  return {};
}

void scale_sublayer_stiffness(BallastScene& s, double factor) {
  require(std::isfinite(factor) && factor > 0.0, "stiffness factor must be > 0");
  Registry& r = s.scene.reg;
  for (LinkId l : s.springs) {
    VoigtRod& law = r.links.law[l.index()];
    const double L = link_frame(r, l, r.bodies.x, r.bodies.y, r.bodies.angle).length;
    const double stretch = L - law.L0 * (1.0 + law.eps0);  // force = −k stretch, kept
    law.k *= factor;
    law.eps0 = (L - stretch / factor) / law.L0 - 1.0;
  }
}

}  // namespace nscd::scenes
