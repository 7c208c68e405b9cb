// nscd/laws/contact_laws.cpp — see contact_laws.hpp.
#include "nscd/laws/contact_laws.hpp"

#include <algorithm>

namespace nscd {

LawShift iqs_clb_shift(double gap, double h, double theta) { return {std::max(0.0, gap) / (theta * h), 0.0}; }

LawShift gap_sgr_clb_shift(double gap, double h, double theta) { return {gap / (theta * h), 0.0}; }

LawShift rst_clb_shift(const LawSpec& law, double gap, double un_begin, double ut_begin, double h, double theta) {
  const double gap_begin = gap - (1.0 - theta) * h * un_begin;
  if (gap_begin <= kClosedGap) return {law.e_n * un_begin, law.e_t * ut_begin};
  return iqs_clb_shift(gap, h, theta);
}

LawShift law_shift(const LawSpec& law, double gap, double un_begin, double ut_begin, double h, double theta) {
  switch (law.kind) {
    case LawKind::IQS_CLB:
      return iqs_clb_shift(gap, h, theta);
    case LawKind::GAP_SGR_CLB:
      return gap_sgr_clb_shift(gap, h, theta);
    case LawKind::RST_CLB:
      return rst_clb_shift(law, gap, un_begin, ut_begin, h, theta);
  }
  return {};
}

}  // namespace nscd
