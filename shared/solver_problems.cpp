// nscd/shared/solver_problems.cpp — see solver_problems.hpp.
#include "nscd/shared/solver_problems.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "nscd/shared/grading.hpp"

namespace nscd::scenes {
namespace {

bool finite_positive(double v) { return std::isfinite(v) && v > 0.0; }

void require(bool ok, const char* who, const std::string& what) {
  if (!ok) throw Error(std::string(who) + ": " + what);
}

// Time step, θ, alert and the one contact law (IQS_CLB, μ, no restitution) of every scene here.
void common_setup(Registry& reg, double mu) {
  reg.params.dt = kProblemDt;
  reg.params.theta = 0.5;
  reg.params.alert = kProblemAlert;
  set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, mu, 0.0, 0.0});
}

// A fixed rectangle, top face on y = 0, centred on x = xc, marked big.
BodyId add_fixed_floor(Registry& reg, MaterialId m, double width, double xc) {
  const double t = 0.1;
  const BodyId b = add_polygon_body(reg, rectangle(width, t), m, {xc, -0.5 * t}, 0.0, "floor");
  fix_body(reg, b);
  for (std::size_t p = 0; p < reg.polyg.size(); ++p)
    if (reg.polyg.body[p] == b) reg.polyg.is_big[p] = 1;
  return b;
}

// Lowest y of a polygon's vertices once rotated by `angle` about its own origin.
double lowest_vertex(const Polygon& shape, double angle) {
  double y = std::numeric_limits<double>::infinity();
  for (const Vec2& v : transformed(shape, {0.0, 0.0}, angle)) y = std::min(y, v.y);
  return y;
}

}  // namespace

Registry block_column(const ColumnOptions& o) {
  require(o.blocks > 0, "block_column", "needs at least one block");
  require(finite_positive(o.width) && finite_positive(o.height) && finite_positive(o.density), "block_column",
          "width, height and density must be finite and > 0");
  require(std::isfinite(o.mu) && o.mu >= 0.0, "block_column", "mu must be >= 0");
  Registry reg;
  common_setup(reg, o.mu);
  const MaterialId m = add_material(reg, "block", o.density);
  add_fixed_floor(reg, m, std::max(1.0, 5.0 * o.width), 0.0);
  // Block k spans y in [k h, (k + 1) h]: each bottom face lies exactly on the face below.
  const Polygon shape = rectangle(o.width, o.height);
  for (int k = 0; k < o.blocks; ++k)
    add_polygon_body(reg, shape, m, {0.0, (k + 0.5) * o.height}, 0.0, "block " + std::to_string(k));
  return reg;
}

Registry pentagon_pile(const PileOptions& o) {
  require(o.base > 0, "pentagon_pile", "needs at least one grain in the bottom row");
  require(finite_positive(o.diameter) && finite_positive(o.density), "pentagon_pile", "diameter and density must be finite and > 0");
  require(std::isfinite(o.pitch_factor) && o.pitch_factor > 0.5 && o.pitch_factor < 2.0, "pentagon_pile",
          "pitch factor must lie in (0.5, 2)");
  require(std::isfinite(o.mu) && o.mu >= 0.0, "pentagon_pile", "mu must be >= 0");
  require(std::isfinite(o.alert) && o.alert >= 0.0 && std::isfinite(o.floor_overlap) && o.floor_overlap >= 0.0,
          "pentagon_pile", "alert and floor overlap must be >= 0");
  Registry reg;
  common_setup(reg, o.mu);
  reg.params.alert = o.alert;
  const MaterialId m = add_material(reg, "grain", o.density);
  const double d = o.diameter, pitch = o.pitch_factor * d;
  const double row_dy = pitch * std::sqrt(3.0) / 2.0;  // triangular lattice: 6 neighbours at `pitch`
  add_fixed_floor(reg, m, o.base * pitch + 4.0 * d, 0.5 * (o.base - 1) * pitch);

  // Rows j = 0, 1, ...: base − j grains, each row shifted half a pitch to the right, so every
  // grain sits in the hollow between two grains of the row below.
  const Polygon shape = regular_polygon(5, d);
  const double period = 2.0 * kPi / 5.0;
  std::mt19937_64 rng(o.seed);
  const double y_ref = 0.45 * d;  // row 0's lattice height: between a pentagon's inradius and circumradius
  int index = 0;
  for (int j = 0; j < o.base; ++j) {
    for (int i = 0; i < o.base - j; ++i, ++index) {
      const double angle = period * uniform01(rng);
      const double x = (i + 0.5 * j) * pitch;
      // the bottom row sits `floor_overlap` deep in the floor; the others on the lattice
      const double y = j == 0 ? -lowest_vertex(shape, angle) - o.floor_overlap : y_ref + j * row_dy;
      add_polygon_body(reg, shape, m, {x, y}, angle, "grain " + std::to_string(index));
    }
  }
  return reg;
}

Registry brick_box(const BrickOptions& o) {
  require(o.columns > 0 && o.rows > 0, "brick_box", "columns and rows must be > 0");
  require(finite_positive(o.width) && finite_positive(o.height) && finite_positive(o.density), "brick_box",
          "width, height and density must be finite and > 0");
  require(std::isfinite(o.mu) && o.mu >= 0.0, "brick_box", "mu must be >= 0");
  Registry reg;
  common_setup(reg, o.mu);
  const MaterialId m = add_material(reg, "brick", o.density);
  const MaterialId wall = add_material(reg, "wall", o.density);
  const double w = o.width, h = o.height, inner = o.columns * w;
  add_box(reg, wall, inner, o.rows * h, kWallThickness);

  const Polygon whole = rectangle(w, h), half = rectangle(0.5 * w, h);
  auto brick = [&](const Polygon& shape, double left, double width, int row, int k) {
    add_polygon_body(reg, shape, m, {left + 0.5 * width, (row + 0.5) * h}, 0.0,
                     "brick " + std::to_string(row) + "." + std::to_string(k));
  };
  for (int r = 0; r < o.rows; ++r) {
    if (r % 2 == 0) {
      // even rows: whole bricks from wall to wall
      for (int k = 0; k < o.columns; ++k) brick(whole, k * w, w, r, k);
    } else {
      // odd rows: a half brick at each wall, whole bricks over the joints of the row below
      brick(half, 0.0, 0.5 * w, r, 0);
      for (int k = 0; k + 1 < o.columns; ++k) brick(whole, (k + 0.5) * w, w, r, k + 1);
      brick(half, inner - 0.5 * w, 0.5 * w, r, o.columns);
    }
  }
  return reg;
}

Scene lmgc90_deposit(std::uint64_t seed) {
  Scene s;
  s.grain_material = add_material(s.reg, "grain", 2700.0);
  s.wall_material = add_material(s.reg, "wall", 2700.0);
  common_setup(s.reg, 0.5);
  s.box_width = 1.54;
  s.box_height = 1.45;
  s.walls = add_box(s.reg, s.wall_material, s.box_width, s.box_height, 0.05);
  const std::vector<double> d = expand_grading(uniform_radius_grading(700, 0.0125, 0.025, seed), seed);
  s.lattice = {0.0275, 0.0275, 28, 0.055, 0.055, seed ^ 0x9E3779B97F4A7C15ull};
  s.grains = add_pentagons_on_lattice(s.reg, s.grain_material, d, s.lattice);
  return s;
}

FrictionProblem2D problem_of(Registry& reg, const StepperOptions& options) {
  MoreauJean stepper(reg, options);
  return problem_of(stepper);
}

FrictionProblem2D problem_of(MoreauJean& stepper) {
  stepper.begin_step();
  stepper.detect();
  stepper.prepare();
  return stepper.local_problem();
}

}  // namespace nscd::scenes
