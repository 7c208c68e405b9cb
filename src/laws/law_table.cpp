// nscd/laws/law_table.cpp — see law_table.hpp.
#include "nscd/laws/law_table.hpp"

#include <cmath>
#include <string>

#include "nscd/core/error.hpp"
#include "nscd/laws/contact_laws.hpp"

namespace nscd {

// VOIGT_ROD is the one law without a contact law's row (contact_laws.cpp): the springs' law.
constexpr std::string_view kSpringLaw = "VOIGT_ROD";

LawKind parse_law_kind(std::string_view n, std::string_view w) {
  if (const ContactLawRow* row = find_contact_law_row(n)) return row->kind;
  if (n == kSpringLaw) return LawKind::VOIGT_ROD;
  std::string msg = "unknown " + std::string(w) + " name '" + std::string(n) + "'; valid names:";
  for (const ContactLawRow& row : contact_law_rows()) msg += " " + std::string(row.name);
  throw Error(msg + " " + std::string(kSpringLaw));
}

std::string_view name_of(LawKind k) {
  const ContactLawRow* row = contact_law_row(k);
  return row ? row->name : k == LawKind::VOIGT_ROD ? kSpringLaw : "?";
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

}  // namespace nscd
