// nscd/laws/material_pairs.hpp — materials and the law of each pair of them (LMGC90's "see
// table"): the functions that fill Registry::materials and Registry::contact_laws.
#pragma once

#include <cstdint>
#include <string>

#include "nscd/core/ids.hpp"
#include "nscd/laws/law_table.hpp"

namespace nscd {

struct Registry;

/// Adds a material; throws on a duplicate name or a density that is not > 0.
MaterialId add_material(Registry& reg, const std::string& name, double density);
/// Looks a material up by name; throws if absent.
MaterialId find_material(const Registry& reg, const std::string& name);
/// The law for a pair of materials (symmetric). Validates the parameters (mu >= 0, e in [0,1]).
void set_contact_law(Registry& reg, MaterialId a, MaterialId b, const LawSpec& law);
/// The law for every pair not set explicitly.
void set_default_contact_law(Registry& reg, const LawSpec& law);
/// Index into contact_laws.laws for a material pair, -1 if none applies.
std::int32_t contact_law_index(const Registry& reg, MaterialId a, MaterialId b);

}  // namespace nscd
