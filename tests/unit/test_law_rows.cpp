// The contact laws' dispatch table (contact_laws.hpp): one row per contact law, in LawKind order,
// found by its name, giving the shift its own function gives.
#include <gtest/gtest.h>

#include "nscd/core/error.hpp"
#include "nscd/laws/contact_laws.hpp"
#include "nscd/laws/law_table.hpp"

namespace nscd {
namespace {

TEST(ContactLawRows, EveryContactLawHasItsRowInKindOrderFoundByName) {
  const auto rows = contact_law_rows();
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(kLastContactLaw) + 1);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto kind = static_cast<LawKind>(i);
    ASSERT_EQ(contact_law_row(kind), &rows[i]);
    EXPECT_EQ(rows[i].kind, kind);
    EXPECT_EQ(parse_law_kind(rows[i].name), kind);
    EXPECT_EQ(name_of(kind), rows[i].name);
    EXPECT_EQ(find_contact_law_row(rows[i].name), &rows[i]);
    EXPECT_EQ(rows[i].datbox_tag.size(), 3u) << rows[i].name;
  }
  EXPECT_EQ(contact_law_row(LawKind::VOIGT_ROD), nullptr);
  EXPECT_EQ(find_contact_law_row("VOIGT_ROD"), nullptr);
  EXPECT_EQ(parse_law_kind("VOIGT_ROD"), LawKind::VOIGT_ROD);
  EXPECT_THROW(parse_law_kind("ELASTIC_REPELL_CLB"), Error);
}

TEST(ContactLawRows, TheRowsShiftAsTheLawsOwnFunctions) {
  const double h = 1e-3, theta = 0.5;
  const LawSpec rst{LawKind::RST_CLB, 0.4, 0.5, 0.2};
  for (double gap : {-3e-4, 0.0, 2e-4}) {
    EXPECT_EQ(law_shift(LawSpec{LawKind::IQS_CLB, 0.4}, gap, -0.1, 0.2, h, theta).n, iqs_clb_shift(gap, h, theta).n);
    EXPECT_EQ(law_shift(LawSpec{LawKind::GAP_SGR_CLB, 0.4}, gap, -0.1, 0.2, h, theta).n,
              gap_sgr_clb_shift(gap, h, theta).n);
    const LawShift a = law_shift(rst, gap, -0.1, 0.2, h, theta), b = rst_clb_shift(rst, gap, -0.1, 0.2, h, theta);
    EXPECT_EQ(a.n, b.n);
    EXPECT_EQ(a.t, b.t);
  }
  // a restitution law's impact shifts by e U⁻ (contact_laws.hpp)
  EXPECT_EQ(law_shift(rst, -1e-5, -0.1, 0.2, h, theta).n, 0.5 * -0.1);
}

}  // namespace
}  // namespace nscd
