// nscd/core/registry.cpp — see registry.hpp.
#include "nscd/core/registry.hpp"

namespace nscd {

void PlplxTable::clear() { resize(0); }

void PlplxTable::resize(std::size_t n) {
  candidate.resize(n);
  antagonist.resize(n);
  cd_body.resize(n);
  an_body.resize(n);
  feature.resize(n);
  gap.resize(n);
  normal.resize(n);
  point.resize(n);
  cd_rn.resize(n);
  cd_rt.resize(n);
  an_rn.resize(n);
  an_rt.resize(n);
  rn.resize(n);
  rt.resize(n);
  status.resize(n);
  law.resize(n);
  mu.resize(n);
}

}  // namespace nscd

#include <cmath>
#include <string>

#include "nscd/core/error.hpp"

namespace nscd {

MaterialId add_material(Registry& reg, const std::string& name, double density) {
  for (const auto& n : reg.materials.name)
    if (n == name) throw Error("material '" + name + "' is defined twice");
  if (!(density > 0.0) || !std::isfinite(density))
    throw Error("material '" + name + "': density must be finite and > 0, got " + std::to_string(density));
  reg.materials.name.push_back(name);
  reg.materials.density.push_back(density);
  // grow the pair table, keeping what was set
  auto& t = reg.contact_laws;
  const std::size_t n_old = t.n_materials, n_new = reg.materials.size();
  std::vector<std::int32_t> grown(n_new * n_new, -1);
  for (std::size_t i = 0; i < n_old; ++i)
    for (std::size_t j = 0; j < n_old; ++j) grown[i * n_new + j] = t.pair_law[i * n_old + j];
  t.pair_law = std::move(grown);
  t.n_materials = n_new;
  return MaterialId(static_cast<std::uint32_t>(n_new - 1));
}

MaterialId find_material(const Registry& reg, const std::string& name) {
  for (std::size_t i = 0; i < reg.materials.size(); ++i)
    if (reg.materials.name[i] == name) return MaterialId(static_cast<std::uint32_t>(i));
  throw Error("unknown material '" + name + "'");
}

void validate(const LawSpec& law) {
  const std::string name(name_of(law.kind));
  if (law.kind == LawKind::VOIGT_ROD)
    throw Error("VOIGT_ROD is a spring law for PTPT2 links (add_spring), not a contact law");
  if (!std::isfinite(law.mu) || law.mu < 0.0)
    throw Error(name + ": friction coefficient mu must be >= 0, got " + std::to_string(law.mu));
  if (!(law.e_n >= 0.0 && law.e_n <= 1.0))
    throw Error(name + ": normal restitution e_n must lie in [0, 1], got " + std::to_string(law.e_n));
  if (!(law.e_t >= -1.0 && law.e_t <= 1.0))
    throw Error(name + ": tangential restitution e_t must lie in [-1, 1], got " + std::to_string(law.e_t));
}

void set_contact_law(Registry& reg, MaterialId a, MaterialId b, const LawSpec& law) {
  validate(law);
  auto& t = reg.contact_laws;
  if (a.index() >= t.n_materials || b.index() >= t.n_materials) throw Error("set_contact_law: unknown material id");
  t.laws.push_back(law);
  const auto k = static_cast<std::int32_t>(t.laws.size() - 1);
  t.pair_law[a.index() * t.n_materials + b.index()] = k;
  t.pair_law[b.index() * t.n_materials + a.index()] = k;
}

void set_default_contact_law(Registry& reg, const LawSpec& law) {
  validate(law);
  reg.contact_laws.laws.push_back(law);
  reg.contact_laws.default_law = static_cast<std::int32_t>(reg.contact_laws.laws.size() - 1);
}

std::int32_t contact_law_index(const Registry& reg, MaterialId a, MaterialId b) {
  const auto& t = reg.contact_laws;
  if (a.index() < t.n_materials && b.index() < t.n_materials) {
    const std::int32_t k = t.pair_law[a.index() * t.n_materials + b.index()];
    if (k >= 0) return k;
  }
  return t.default_law;
}

void validate(const Parameters& p) {
  if (!(p.dt > 0.0) || !std::isfinite(p.dt)) throw Error("time step dt must be finite and > 0, got " + std::to_string(p.dt));
  if (!(p.theta >= 0.5 && p.theta <= 1.0)) throw Error("theta must lie in [0.5, 1], got " + std::to_string(p.theta));
  if (!(p.alert >= 0.0) || !std::isfinite(p.alert)) throw Error("alert distance must be finite and >= 0, got " + std::to_string(p.alert));
  if (!std::isfinite(p.gravity.x) || !std::isfinite(p.gravity.y)) throw Error("gravity must be finite");
}

}  // namespace nscd
