// nscd/laws/law_table.hpp — the tables of the laws module: the contact laws (IQS_CLB,
// GAP_SGR_CLB, RST_CLB) with their parameters, LMGC90's "see table" that picks one per pair of
// materials, and the VOIGT_ROD spring law of the sublayer links.
//
// What each law does is in contact_laws.hpp and voigt_rod.hpp; the functions that fill these
// tables (add_material, set_contact_law, …) are in material_pairs.hpp.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace nscd {

enum class LawKind : std::uint8_t { IQS_CLB, GAP_SGR_CLB, RST_CLB, VOIGT_ROD };
/// The contact laws are the kinds before VOIGT_ROD (a spring law, never in a ContactLawTable),
/// which stays last: a new contact law goes before it, and the readers that bound a stored
/// contact law's kind (checkpoints) follow.
inline constexpr LawKind kLastContactLaw = static_cast<LawKind>(static_cast<int>(LawKind::VOIGT_ROD) - 1);

/// Resolve a name ("IQS_CLB", …); throws nscd::Error naming the valid choices.
LawKind parse_law_kind(std::string_view name, std::string_view what = "contact law");
std::string_view name_of(LawKind k);

/// One contact law with its parameters.
struct LawSpec {
  LawKind kind = LawKind::IQS_CLB;
  double mu = 0.0;   ///< friction coefficient
  double e_n = 0.0;  ///< normal restitution (RST_CLB)
  double e_t = 0.0;  ///< tangential restitution (RST_CLB)
};

/// Throws nscd::Error if mu < 0, e_n outside [0, 1], e_t outside [-1, 1] (a negative tangential
/// restitution is admissible in Moreau's impact law), or a non-finite value.
void validate(const LawSpec& law);

/// Which law applies to a pair of materials (LMGC90's "see table"): a symmetric dense
/// matrix of indices into `laws`, with `default_law` for pairs never set.
struct ContactLawTable {
  std::vector<LawSpec> laws;
  std::vector<std::int32_t> pair_law;  ///< n×n, -1 = default
  std::size_t n_materials = 0;
  std::int32_t default_law = -1;       ///< -1: no law, pairs of these materials never interact
};

/// VOIGT_ROD: the visco-elastic spring of the sublayer (paper §2.9, eq. 17), strain
/// ε = (L − L0)/L0 − ε0. The force on the candidate along n (from the antagonist point to the
/// candidate point) is R_N = −k L0 ε − ν L0 ε̇ = −k (L − L0 (1 + ε0)) − ν L̇: k in N/m and ν in
/// N·s/m per unit thickness, the paper's calibration F = k δ. See docs/theory.md.
struct VoigtRod {
  double k = 0.0;     ///< stiffness (N/m), >= 0
  double nu = 0.0;    ///< viscosity (N·s/m), >= 0
  double L0 = 0.0;    ///< reference length (m), > 0
  double eps0 = 0.0;  ///< prestrain
};

}  // namespace nscd
