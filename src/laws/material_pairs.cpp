// nscd/laws/material_pairs.cpp — see material_pairs.hpp.
#include "nscd/laws/material_pairs.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "nscd/core/error.hpp"
#include "nscd/registry/registry.hpp"

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

}  // namespace nscd
