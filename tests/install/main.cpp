// tests/install/main.cpp — a minimal out-of-tree driver using only the installed public
// headers of nscd: a fixed floor and a pentagon whose lowest corner dips 1 mm into it; one
// PLPLx detection must find exactly one contact point.
//
// Hand computation (units: m):
//   floor: rectangle 2 × 0.2 centred at (0, −0.1)          → top edge on y = 0.
//   pentagon: regular, circumscribed diameter 0.2 (circumradius 0.1), first vertex at
//     angle −π/2 (pointing down), centre at (0, 0.099)       → lowest vertex (0, −0.001).
//     Next-lowest vertices at angles −π/2 ± 2π/5: y = 0.099 + 0.1·sin(−18°) = 0.0681,
//     far above the alert distance 1.25e-3.
//   ⇒ one vertex–edge contact: gap = −0.001, normal (0, 1) from the floor (antagonist,
//     body 0) toward the pentagon (candidate), point at half penetration (0, −0.0005).
#include <cmath>
#include <iostream>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "nscd/interactions/plplx.hpp"

int main() {
  try {
    nscd::Registry reg;
    const nscd::MaterialId rock = nscd::add_material(reg, "ROCK", 2700.0);
    nscd::set_default_contact_law(reg, nscd::LawSpec{nscd::LawKind::IQS_CLB, 0.5, 0.0, 0.0});

    const nscd::BodyId floor = nscd::add_polygon_body(reg, nscd::rectangle(2.0, 0.2), rock, {0.0, -0.1}, 0.0, "floor");
    nscd::fix_body(reg, floor);
    nscd::add_polygon_body(reg, nscd::regular_polygon(5, 0.2, -0.5 * nscd::kPi), rock, {0.0, 0.099}, 0.0, "grain");

    nscd::PlplxDetector det;
    nscd::classify_big_polygons(reg, det.big_ratio);
    const nscd::DetectionStats stats = nscd::detect_plplx(reg, det);

    std::cout << "contacts: " << reg.contacts.size() << '\n';
    if (reg.contacts.size() != 1 || stats.contact_points != 1) {
      std::cerr << "expected exactly 1 contact point\n";
      return 1;
    }
    const double gap = reg.contacts.gap[0];
    const nscd::Vec2 n = reg.contacts.normal[0], p = reg.contacts.point[0];
    std::cout << "gap: " << gap << "  normal: (" << n.x << ", " << n.y << ")  point: (" << p.x << ", " << p.y << ")\n";
    const bool ok = std::abs(gap + 1e-3) < 1e-12 && std::abs(n.x) < 1e-12 && std::abs(n.y - 1.0) < 1e-12 &&
                    std::abs(p.x) < 1e-12 && std::abs(p.y + 5e-4) < 1e-12 && reg.contacts.an_body[0] == floor &&
                    reg.contacts.mu[0] == 0.5;
    if (!ok) {
      std::cerr << "contact geometry differs from the hand computation\n";
      return 1;
    }
    return 0;
  } catch (const nscd::Error& e) {
    std::cerr << "nscd error: " << e.what() << '\n';
    return 2;
  }
}
