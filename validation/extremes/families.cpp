// validation/extremes/families.cpp — the families of the extremes suite and what must hold in
// each (extremes.hpp). Sizes are kept small so that the whole --full sweep runs in minutes;
// the points marked quick form the CI subset (ctest label `extremes`).
#include <cmath>
#include <cstdio>
#include <string>

#include "extremes.hpp"
#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"

namespace nscd::extremes {
namespace {

std::string sci(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

// Stacks of blocks 0.2 × 0.1 m at rest, masses alternating 1:ratio, h = 1e-3 s, 0.5 s.
Family stack_family(int n, bool light_bottom) {
  Family f;
  f.name = "stack of " + std::to_string(n) + (n == 2 ? (light_bottom ? ", heavy on light" : ", light on heavy")
                                                   : (light_bottom ? ", alternating, light at the bottom"
                                                                   : ", alternating, heavy at the bottom"));
  f.holds = "stays put (drift <= 0.1 mm), overlap <= 0.1 mm over 0.5 s at h = 1e-3 s";
  for (double ratio : {10.0, 1e2, 1e3, 1e4, 1e5, 1e6}) {
    Point p;
    p.value = "1:" + sci(ratio);
    p.quick = ratio == 10.0 || ratio == 1e3 || (n == 2 && ratio == 1e6);
    p.build = [=] {
      Scenario s;
      s.reg = base_registry(1e-3);
      s.watched = add_stack(s.reg, n, ratio, light_bottom);
      s.steps = 500;
      s.expect.max_drift = 1e-4;
      s.expect.max_overlap = 1e-4;
      return s;
    };
    f.points.push_back(p);
  }
  return f;
}

// 50 pentagons of 2 cm dropped from 5 cm into a box 0.3 m wide: 0.5 s at step h with θ.
Family step_family(double theta, bool full) {
  Family f;
  f.name = "50 pentagons dropped in a box, theta " + sci(theta);
  f.holds = "overlap <= 1 mm (5 % of d), none through floor or walls, no energy created (0.1 %), 0.5 s";
  std::vector<double> steps{1e-4, 1e-3, 2e-3, 5e-3, 1e-2};
  if (full) steps.insert(steps.begin(), {1e-6, 1e-5});
  for (double h : steps) {
    Point p;
    p.value = "h " + sci(h);
    p.quick = theta == 0.5 && (h == 1e-3 || h == 1e-2);
    p.must_hold = theta == 0.5 && h == 1e-3;
    p.build = [=] {
      Scenario s;
      s.reg = base_registry(h);
      s.reg.params.theta = theta;
      s.watched = add_dropped_polygons(s.reg, 50, 5, 0.02, 0.3, 0.05);
      // h = 1e-6 over 0.5 s would be 500,000 steps: those run 20,000 steps (0.02 s), falling
      s.steps = std::min<std::int64_t>(std::llround(0.5 / h), 20000);
      s.expect.max_overlap = 1e-3;
      s.expect.no_tunnelling = true;
      s.expect.x_left = 0.0;
      s.expect.x_right = 0.3;
      s.expect.energy_slack = 1e-3 * total_energy(s.reg);
      return s;
    };
    f.points.push_back(p);
  }
  return f;
}

// A pentagon of 2 cm thrown down at v onto the apex of a pile of 21 pentagons (base 6, add_pile).
Family impact_family(double h) {
  Family f;
  f.name = "a grain thrown into a pile at h = " + sci(h);
  f.holds = "overlap <= 2 mm (10 % of d), none through the floor, no energy created (0.1 %), 0.1 s";
  for (double v : {1.0, 10.0, 50.0, 100.0}) {
    Point p;
    p.value = sci(v) + " m/s";
    p.quick = h == 2e-4 && (v == 1.0 || v == 100.0);
    p.must_hold = h == 2e-4 && v == 1.0;
    p.build = [=] {
      Scenario s;
      s.reg = base_registry(h);
      add_pile(s.reg, 6, 0.02);
      const std::size_t apex = s.reg.bodies.size() - 1;
      const Vec2 at{s.reg.bodies.x[apex], s.reg.bodies.y[apex] + 0.04};
      const BodyId b = add_polygon_body(s.reg, regular_polygon(5, 0.02), find_material(s.reg, "stone"), at, 0.1, "projectile");
      s.reg.bodies.vy[b.index()] = -v;
      s.watched = all_dynamic(s.reg);
      s.steps = std::llround(0.1 / h);
      s.expect.max_overlap = 2e-3;
      s.expect.no_tunnelling = true;
      s.expect.energy_slack = 1e-3 * std::abs(total_energy(s.reg));
      return s;
    };
    f.points.push_back(p);
  }
  return f;
}

// The pile of 21 pentagons (base 6) collapsing or standing with friction μ, 0.5 s.
Family friction_family() {
  Family f;
  f.name = "pile of 21 pentagons, friction mu";
  f.holds = "overlap <= 0.4 mm (2 % of d), none through the floor, no energy created (0.1 %), 0.5 s at h = 2e-4";
  for (double mu : {0.0, 0.5, 10.0}) {
    Point p;
    p.value = "mu " + sci(mu);
    p.quick = mu == 0.0 || mu == 10.0;
    p.build = [=] {
      Scenario s;
      s.reg = base_registry(2e-4, mu);
      add_pile(s.reg, 6, 0.02);
      s.watched = all_dynamic(s.reg);
      s.steps = 2500;
      s.expect.max_overlap = 4e-4;
      s.expect.no_tunnelling = true;
      s.expect.energy_slack = 1e-3 * std::abs(total_energy(s.reg));
      return s;
    };
    f.points.push_back(p);
  }
  return f;
}

// 20 pentagons dropped from 5 cm in a box with RST_CLB restitution e, 1 s.
Family restitution_family() {
  Family f;
  f.name = "20 pentagons bouncing in a box, RST_CLB restitution e";
  f.holds = "overlap <= 0.4 mm, none through floor or walls, energy gain <= 2 % (Newton restitution with friction may create some), 1 s at h = 2e-4";
  for (double e : {0.0, 0.5, 1.0}) {
    Point p;
    p.value = "e " + sci(e);
    p.quick = e == 1.0;
    p.build = [=] {
      Scenario s;
      s.reg = base_registry(2e-4);
      set_default_contact_law(s.reg, LawSpec{LawKind::RST_CLB, 0.5, e, 0.0});
      s.watched = add_dropped_polygons(s.reg, 20, 5, 0.02, 0.2, 0.05);
      s.steps = 5000;
      s.expect.max_overlap = 4e-4;
      s.expect.no_tunnelling = true;
      s.expect.x_left = 0.0;
      s.expect.x_right = 0.2;
      s.expect.energy_slack = 0.02 * total_energy(s.reg);
      return s;
    };
    f.points.push_back(p);
  }
  return f;
}

// Small pentagons (d = 0.5 m / ratio) dropped onto a free block 0.499 × 0.1 m filling a box.
Family size_family() {
  Family f;
  f.name = "small pentagons on a large block, size ratio";
  f.holds = "overlap <= 2 % of the small d, none into the block, 0.2 s at h = 2e-4";
  for (double ratio : {10.0, 30.0, 100.0}) {
    Point p;
    p.value = "1:" + sci(ratio);
    p.quick = ratio == 10.0;
    p.build = [=] {
      const double d = 0.5 / ratio;
      Scenario s;
      s.reg = base_registry(2e-4);
      const BodyId block = add_polygon_body(s.reg, rectangle(0.499, 0.1), find_material(s.reg, "stone"), {0.25, 0.05}, 0.0, "block");
      const int per_row = static_cast<int>(0.5 / (1.2 * d));
      s.watched = add_dropped_polygons(s.reg, std::min(2 * per_row, 60), 5, d, 0.5, 0.1 + 0.1 * d);
      (void)block;
      s.steps = 1000;
      s.expect.max_overlap = 0.02 * d;
      s.expect.no_tunnelling = true;
      s.expect.floor_y = 0.1;  // the block's top face
      s.expect.x_left = 0.0;
      s.expect.x_right = 0.5;
      return s;
    };
    f.points.push_back(p);
  }
  return f;
}

}  // namespace

Family shape_family(bool thin);
Family touching_family();
Family far_family();
Family sublayer_family(bool stiff);
Family ballast_step_family(bool full);
Family rest_family();

std::vector<Family> families(bool full) {
  std::vector<Family> out;
  for (int n : {2, 30})
    for (bool light_bottom : {true, false}) out.push_back(stack_family(n, light_bottom));
  for (double theta : {0.5, 0.55, 1.0}) out.push_back(step_family(theta, full));
  for (double h : {2e-4, 1e-3, 1e-2}) out.push_back(impact_family(h));
  out.push_back(friction_family());
  out.push_back(restitution_family());
  out.push_back(size_family());
  out.push_back(shape_family(false));
  out.push_back(shape_family(true));
  out.push_back(touching_family());
  out.push_back(far_family());
  out.push_back(sublayer_family(true));
  out.push_back(sublayer_family(false));
  out.push_back(ballast_step_family(full));
  out.push_back(rest_family());
  return out;
}

}  // namespace nscd::extremes
