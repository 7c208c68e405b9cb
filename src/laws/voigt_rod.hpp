// nscd/laws/voigt_rod.hpp — the VOIGT_ROD spring law treated implicitly inside the solver.
//
// With L_f = L_m + θ h U_N the end-of-step length and U_N the end-of-step rate of extension,
//     R_N = −k (L_f − L0 (1 + ε0)) − ν U_N = a − b U_N,
//     a = −k (L_m − L0 (1 + ε0)),   b = k θ h + ν.
// The affine relation between the impulse P = h R_N and U_N is the paper's "derived Signorini
// law" (§2.9): with w the link's own Delassus scalar and c the velocity the link would have
// without its own impulse (U_N = c + w P),
//     P = h (a − b c) / (1 + h b w),
// solved exactly at each visit. It is unconditionally stable: any k with any h.
#pragma once

namespace nscd {

struct VoigtAffine {
  double ha = 0.0;  ///< h a
  double hb = 0.0;  ///< h b
};

inline VoigtAffine voigt_affine(double k, double nu, double rest_length, double length_m, double h, double theta) {
  return {-h * k * (length_m - rest_length), h * (k * theta * h + nu)};
}

/// The link's impulse for the velocity c it would have without its own impulse.
inline double voigt_impulse(const VoigtAffine& v, double w, double c) { return (v.ha - v.hb * c) / (1.0 + v.hb * w); }

}  // namespace nscd
