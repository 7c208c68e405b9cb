// nscd/laws/contact_laws.hpp — the contact laws as affine shifts of the single-contact problem.
//
// Every law of nscd is Signorini–Coulomb in velocities (coulomb2d.hpp) applied to a shifted
// relative velocity U_s = U + s, with s computed once per step per contact. The NLGS loop
// thus never branches on the law.
//
//   IQS_CLB(mu)          s_N = max(0, g) / h: a contact still open at q_m may close by the next
//                        detection (q_m + h u_f) but not overlap there; an existing overlap
//                        may not grow and is not pushed out.
//   GAP_SGR_CLB(mu)      s_N = g / h: the gap at the next detection is >= 0, overlap is pushed
//                        out.
//   RST_CLB(e_n, e_t, mu) for a contact closed at the start of the step (g_i <= kClosedGap)
//                        or closing before the next detection (g_m + h U_N⁻ <= kClosedGap at the
//                        start velocity: an impact):
//                        s_N = e_n U_N⁻, s_T = e_t U_T⁻, i.e. the law holds on the weighted
//                        mean (U⁺ + e U⁻)/(1 + e) (paper §2.8, Newton restitution);
//                        otherwise it acts as IQS_CLB.
// Why h and not θh (the horizon of q_f = q_m + θ h u_f): docs/theory.md §8.2.
// Here g is the gap at q_m, U⁻ the relative velocity at the start of the step, and
// g_i ≈ g − (1 − θ) h U_N⁻ the gap at the start of the step.
#pragma once

#include <span>
#include <string_view>

#include "nscd/registry/registry.hpp"

namespace nscd {

/// Gaps at or below this (m) count as closed for RST_CLB.
inline constexpr double kClosedGap = 1e-9;

struct LawShift {
  double n = 0.0, t = 0.0;
};

LawShift iqs_clb_shift(double gap, double h, double theta);
LawShift gap_sgr_clb_shift(double gap, double h, double theta);
LawShift rst_clb_shift(const LawSpec& law, double gap, double un_begin, double ut_begin, double h, double theta);

/// One contact law as a row of the laws' dispatch table. Adding a law is its LawKind
/// (law_table.hpp), its shift and its row (contact_laws.cpp): names, checkpoints, the DATBOX
/// reader and writer and the stepper find it through the row.
struct ContactLawRow {
  LawKind kind;
  std::string_view name;        ///< the name users and LMGC90's TACT_BEHAV.DAT give it
  std::string_view datbox_tag;  ///< prefix of the law names write_datbox makes up ("iqs01")
  bool restitution;             ///< has e_n and e_t besides mu (read and written as rstn, rstt)
  LawShift (*shift)(const LawSpec& law, double gap, double un_begin, double ut_begin, double h, double theta);
};

/// The contact laws' rows, in LawKind order (VOIGT_ROD, a spring law, has none).
std::span<const ContactLawRow> contact_law_rows();
/// The row of a contact law, nullptr for VOIGT_ROD.
const ContactLawRow* contact_law_row(LawKind k);
/// The row named `name`, nullptr if no contact law has that name.
const ContactLawRow* find_contact_law_row(std::string_view name);

/// The shift of a contact's law, through its row (once per contact per step, outside the solver loop).
LawShift law_shift(const LawSpec& law, double gap, double un_begin, double ut_begin, double h, double theta);

}  // namespace nscd
