// nscd/laws/law_table.cpp — see law_table.hpp.
#include "nscd/laws/law_table.hpp"

#include <cmath>
#include <string>

#include "nscd/core/error.hpp"
#include "nscd/core/name_table.hpp"

namespace nscd {
namespace {

constexpr NameTable<LawKind, 4> kLaws{{{"IQS_CLB", LawKind::IQS_CLB},
                                       {"GAP_SGR_CLB", LawKind::GAP_SGR_CLB},
                                       {"RST_CLB", LawKind::RST_CLB},
                                       {"VOIGT_ROD", LawKind::VOIGT_ROD}}};

}  // namespace

LawKind parse_law_kind(std::string_view n, std::string_view w) { return parse_name(kLaws, n, w); }
std::string_view name_of(LawKind k) { return name_in(kLaws, k); }

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
