// nscd/interactions/ptpt2.cpp — see ptpt2.hpp.
#include "nscd/interactions/ptpt2.hpp"

#include <cmath>
#include <string>

#include "nscd/contactors/pt2dx.hpp"
#include "nscd/core/error.hpp"

namespace nscd {

LinkId add_spring(Registry& reg, PointId cd, PointId an, VoigtRod law) {
  const std::string who = "PTPT2 link " + std::to_string(reg.links.size());
  if (!cd.valid() || cd.index() >= reg.points.size() || !an.valid() || an.index() >= reg.points.size())
    throw Error(who + ": unknown PT2Dx point id");
  if (!std::isfinite(law.k) || law.k < 0.0)
    throw Error(who + ": VOIGT_ROD stiffness k must be >= 0, got " + std::to_string(law.k));
  if (!std::isfinite(law.nu) || law.nu < 0.0)
    throw Error(who + ": VOIGT_ROD viscosity nu must be >= 0, got " + std::to_string(law.nu));
  if (!std::isfinite(law.eps0) || !std::isfinite(law.L0)) throw Error(who + ": VOIGT_ROD L0 and eps0 must be finite");
  const auto& b = reg.bodies;
  const std::size_t bc = reg.points.body[cd.index()].index(), ba = reg.points.body[an.index()].index();
  const Vec2 d =
      point_position(reg, cd, b.x[bc], b.y[bc], b.angle[bc]) - point_position(reg, an, b.x[ba], b.y[ba], b.angle[ba]);
  if (!(norm(d) > 0.0)) throw Error(who + ": the two points coincide (the spring has no direction)");
  if (law.L0 <= 0.0) law.L0 = norm(d);
  reg.links.candidate.push_back(cd);
  reg.links.antagonist.push_back(an);
  reg.links.law.push_back(law);
  reg.links.length.push_back(norm(d));
  reg.links.normal.push_back(normalized(d));
  reg.links.rn.push_back(0.0);
  return LinkId(static_cast<std::uint32_t>(reg.links.size() - 1));
}

LinkFrame link_frame(const Registry& reg, LinkId link, std::span<const double> x, std::span<const double> y,
                     std::span<const double> angle) {
  const PointId cd = reg.links.candidate[link.index()], an = reg.links.antagonist[link.index()];
  const std::size_t bc = reg.points.body[cd.index()].index(), ba = reg.points.body[an.index()].index();
  const Vec2 pc = point_position(reg, cd, x[bc], y[bc], angle[bc]);
  const Vec2 pa = point_position(reg, an, x[ba], y[ba], angle[ba]);
  LinkFrame f;
  const Vec2 d = pc - pa;
  f.length = norm(d);
  // a link squeezed to zero length keeps its last direction
  f.n = f.length > 0.0 ? (1.0 / f.length) * d : reg.links.normal[link.index()];
  f.cd_rn = cross(pc - Vec2{x[bc], y[bc]}, f.n);
  f.an_rn = cross(pa - Vec2{x[ba], y[ba]}, f.n);
  return f;
}

}  // namespace nscd
