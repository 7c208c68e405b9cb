// nscd/contactors/round_shapes.cpp — see round_shapes.hpp.
#include "nscd/contactors/round_shapes.hpp"

#include <cmath>
#include <string>

#include "nscd/core/error.hpp"
#include "nscd/core/math.hpp"

namespace nscd {
namespace {

void require(bool ok, const char* what, double value) {
  if (!ok) throw Error(std::string(what) + ", got " + std::to_string(value));
}

}  // namespace

MassProperties diskx_mass(double radius, double rho) {
  require(std::isfinite(radius) && radius > 0.0, "DISKx: the radius must be > 0", radius);
  require(std::isfinite(rho) && rho > 0.0, "DISKx: the density must be > 0", rho);
  const double m = rho * kPi * radius * radius;
  return {m, 0.5 * m * radius * radius};
}

MassProperties joncx_mass(double a, double b, double rho) {
  require(std::isfinite(a) && a >= 0.0, "JONCx: the half-length must be >= 0", a);
  require(std::isfinite(b) && b > 0.0, "JONCx: the half-thickness must be > 0", b);
  require(std::isfinite(rho) && rho > 0.0, "JONCx: the density must be > 0", rho);
  const double m_rect = 4.0 * rho * a * b;
  const double i_rect = m_rect * (4.0 * a * a + 4.0 * b * b) / 12.0;
  const double m_half = 0.5 * rho * kPi * b * b;
  const double c = 4.0 * b / (3.0 * kPi);
  const double i_half = m_half * (0.5 * b * b - c * c + (a + c) * (a + c));
  return {m_rect + 2.0 * m_half, i_rect + 2.0 * i_half};
}

}  // namespace nscd
