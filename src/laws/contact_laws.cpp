// nscd/laws/contact_laws.cpp — see contact_laws.hpp.
#include "nscd/laws/contact_laws.hpp"

#include <algorithm>
#include <iterator>

namespace nscd {

// The horizon of every shift is h, not θh: the next step detects at q_m + h u_f, so the gap the
// law must keep non-negative is g + h U_N (docs/theory.md §8.2; LMGC90 uses the same /h).
LawShift iqs_clb_shift(double gap, double h, double /*theta*/) { return {std::max(0.0, gap) / h, 0.0}; }

LawShift gap_sgr_clb_shift(double gap, double h, double /*theta*/) { return {gap / h, 0.0}; }

LawShift rst_clb_shift(const LawSpec& law, double gap, double un_begin, double ut_begin, double h, double theta) {
  // Newton's law applies to a contact closed at t_i and to one that closes during the step:
  // a body arriving from a distance reaches the obstacle (overlap at q_m, or a gap at the next
  // detection g_m + h U_N⁻ <= 0 at its start velocity) within one step. Treating the latter as
  // open (IQS) stopped it dead, U⁺ = 0, and the next step had no U⁻ left to restitute: no bounce.
  const double gap_begin = gap - (1.0 - theta) * h * un_begin;
  const double gap_next_predicted = gap + h * un_begin;
  if (gap_begin <= kClosedGap || gap_next_predicted <= kClosedGap) return {law.e_n * un_begin, law.e_t * ut_begin};
  return iqs_clb_shift(gap, h, theta);
}

namespace {

LawShift iqs_row(const LawSpec&, double gap, double, double, double h, double theta) {
  return iqs_clb_shift(gap, h, theta);
}
LawShift gap_sgr_row(const LawSpec&, double gap, double, double, double h, double theta) {
  return gap_sgr_clb_shift(gap, h, theta);
}

// In LawKind order: contact_law_row indexes it by the kind.
constexpr ContactLawRow kContactLaws[] = {
    {LawKind::IQS_CLB, "IQS_CLB", "iqs", false, iqs_row},
    {LawKind::GAP_SGR_CLB, "GAP_SGR_CLB", "gap", false, gap_sgr_row},
    {LawKind::RST_CLB, "RST_CLB", "rst", true, rst_clb_shift},
};
static_assert(std::size(kContactLaws) == static_cast<std::size_t>(kLastContactLaw) + 1,
              "one row per contact law, in LawKind order");

}  // namespace

std::span<const ContactLawRow> contact_law_rows() { return kContactLaws; }

const ContactLawRow* contact_law_row(LawKind k) {
  const auto i = static_cast<std::size_t>(k);
  return i < std::size(kContactLaws) ? &kContactLaws[i] : nullptr;
}

const ContactLawRow* find_contact_law_row(std::string_view name) {
  for (const ContactLawRow& r : kContactLaws)
    if (r.name == name) return &r;
  return nullptr;
}

LawShift law_shift(const LawSpec& law, double gap, double un_begin, double ut_begin, double h, double theta) {
  const ContactLawRow* row = contact_law_row(law.kind);
  return row ? row->shift(law, gap, un_begin, ut_begin, h, theta) : LawShift{};
}

}  // namespace nscd
