// validation/extremes/families_shape.cpp — shape and placement families of the extremes
// suite: vertex counts, thin polygons, exactly touching edges, far from the origin.
#include <cmath>
#include <cstdio>
#include <string>

#include "extremes.hpp"
#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/shared/solver_problems.hpp"

namespace nscd::extremes {
namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

}  // namespace

// thin = false: 30 regular polygons of 3 … 64 vertices (d = 2 cm) dropped into a box 0.2 m
// wide, 0.4 s. thin = true: a stack of 10 plates 0.5 m wide of aspect 1:1 … 1:100 at rest.
Family shape_family(bool thin) {
  Family f;
  if (!thin) {
    f.name = "30 polygons dropped in a box, vertices";
    f.holds = "overlap <= 0.4 mm (2 % of d), none through floor or walls, no energy created (0.1 %), 0.4 s at h = 2e-4";
    for (int nv : {3, 5, 16, 64}) {
      Point p;
      p.value = std::to_string(nv) + " vertices";
      p.quick = nv == 3 || nv == 64;
      p.must_hold = nv == 5;
      p.build = [=] {
        Scenario s;
        s.reg = base_registry(2e-4);
        s.watched = add_dropped_polygons(s.reg, 30, nv, 0.02, 0.2, 0.0);
        s.steps = 2000;
        s.expect.max_overlap = 4e-4;
        s.expect.no_tunnelling = true;
        s.expect.x_left = 0.0;
        s.expect.x_right = 0.2;
        s.expect.energy_slack = 1e-3 * total_energy(s.reg);
        return s;
      };
      f.points.push_back(p);
    }
    return f;
  }
  f.name = "stack of 10 thin plates 0.5 m wide, aspect";
  f.holds = "stays put (drift <= 1 % of the thickness), overlap <= 1 % of the thickness, 0.5 s at h = 1e-3";
  for (double aspect : {1.0, 10.0, 50.0, 100.0}) {
    Point p;
    p.value = "1:" + num(aspect);
    p.quick = aspect == 50.0;
    p.build = [=] {
      const double t = 0.5 / aspect;
      Scenario s;
      s.reg = base_registry(1e-3);
      s.watched = add_stack(s.reg, 10, 1.0, true, 0.5, t);
      s.steps = 500;
      s.expect.max_drift = 0.01 * t;
      s.expect.max_overlap = 0.01 * t;
      return s;
    };
    f.points.push_back(p);
  }
  return f;
}

// Face-on-face contacts: a column of 10 blocks and a running-bond wall of bricks in a box,
// every edge exactly parallel to and touching its neighbour's (gaps 0).
Family touching_family() {
  Family f;
  f.name = "exactly parallel, touching edges";
  f.holds = "stays put (drift <= 0.01 mm), overlap <= 0.01 mm, 0.2 s at h = 2e-4";
  for (int which : {0, 1}) {
    Point p;
    p.value = which == 0 ? "column of 10" : "brick wall 6 x 5";
    p.quick = which == 0;
    p.must_hold = which == 0;
    p.build = [=] {
      Scenario s;
      if (which == 0) {
        s.reg = scenes::block_column({.blocks = 10});
      } else {
        scenes::BrickOptions b;
        b.columns = 5;
        b.rows = 6;
        s.reg = scenes::brick_box(b);
      }
      for (std::uint32_t i = 0; i < s.reg.bodies.size(); ++i)
        if (s.reg.bodies.inv_mass_y[i] != 0.0) s.watched.push_back(BodyId(i));
      s.steps = 1000;
      s.expect.max_drift = 1e-5;
      s.expect.max_overlap = 1e-5;
      return s;
    };
    f.points.push_back(p);
  }
  return f;
}

// A stack of 5 blocks and 20 dropped pentagons, the whole scene shifted by `offset` in x and y.
Family far_family() {
  Family f;
  f.name = "far from the origin (x and y shifted)";
  f.holds = "stack stays put (drift <= 0.01 mm), overlap <= 0.4 mm, grains inside the box, 0.3 s at h = 2e-4";
  for (double offset : {0.0, 1e3, 1e6, 1e8, 1e10}) {
    Point p;
    p.value = num(offset) + " m";
    p.quick = offset == 1e6;
    p.must_hold = offset == 0.0;
    p.build = [=] {
      Scenario s;
      s.reg = base_registry(2e-4, 0.5, offset, offset);
      // the stack 1 m left of the box
      s.watched = add_stack(s.reg, 5, 1.0, true, 0.2, 0.1, offset - 1.0, offset);
      add_dropped_polygons(s.reg, 20, 5, 0.02, 0.2, 0.0, offset);
      // add_dropped_polygons places from y = 0: lift the grains and walls by the offset
      for (std::size_t i = s.watched.back().index() + 1; i < s.reg.bodies.size(); ++i) s.reg.bodies.y[i] += offset;
      s.steps = 1500;
      s.expect.max_drift = 1e-5;  // the grains are not watched for drift: only the stack
      s.expect.max_overlap = 4e-4;
      return s;
    };
    f.points.push_back(p);
  }
  return f;
}

}  // namespace nscd::extremes
