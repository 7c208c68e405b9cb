// nscd/laws/coulomb2d.hpp — the single-contact 2D Signorini–Coulomb problem, solved exactly.
//
// Given the contact's own 2×2 Delassus block W (W = H* M⁻¹ H restricted to the contact,
// symmetric positive definite) and b, the relative velocity the contact would have without
// its own impulse (law shifts included), find the impulse P = (P_N, P_T) such that
// U = b + W P satisfies (paper eq. 11, in velocities):
//     U_N >= 0, P_N >= 0, U_N P_N = 0,  |P_T| <= mu P_N,  U_T != 0  =>  P_T = -mu P_N sign(U_T).
// Four cases are tried in order — open, stick, slide forward, slide backward — and the first
// consistent one is returned (on the cone's edge, where rounding can fail every test by an
// ulp, the nearest slide). The full block (with the coupling W_NT that lever arms create)
// is used, so the answer is exact, not a diagonal approximation.
//
// Header-only and branch-light: it runs inside the NLGS loop, once per contact visit.
#pragma once

#include <cmath>

#include "nscd/registry/registry.hpp"

namespace nscd {

/// Symmetric 2×2 block [[nn, nt], [nt, tt]] in the (n, t) frame.
struct Block2 {
  double nn = 0.0, nt = 0.0, tt = 0.0;
};

struct LocalImpulse {
  double pn = 0.0, pt = 0.0;
  ContactStatus status = ContactStatus::Open;
};

/// The reciprocals the solve divides by, fixed for a contact during a whole NLGS solve
/// (W and mu do not change): computed once per step, they take the divisions out of the
/// sweep. A reciprocal of 0 marks a case that does not exist (det <= 0, den <= 0).
struct CoulombFactors {
  double inv_det = 0.0;                   ///< 1 / (W_NN W_TT − W_NT²)
  double inv_den_fwd = 0.0, inv_den_bwd = 0.0;  ///< 1 / (W_NN ∓ mu W_NT), slide forward / backward
};

inline CoulombFactors coulomb_factors(const Block2& W, double mu) {
  CoulombFactors f;
  const double det = W.nn * W.tt - W.nt * W.nt;
  const double fwd = W.nn - mu * W.nt, bwd = W.nn + mu * W.nt;
  if (det > 0.0) f.inv_det = 1.0 / det;
  if (fwd > 0.0) f.inv_den_fwd = 1.0 / fwd;
  if (bwd > 0.0) f.inv_den_bwd = 1.0 / bwd;
  return f;
}

inline LocalImpulse solve_coulomb_2d(const Block2& W, const CoulombFactors& f, double bn, double bt, double mu) {
  // 1. Open: without impulse the contact separates (or stays at rest).
  if (bn >= 0.0) return {0.0, 0.0, ContactStatus::Open};

  // 2. Stick: U = 0, P = −W⁻¹ b, valid inside the cone.
  if (f.inv_det > 0.0) {
    const double pn = (-W.tt * bn + W.nt * bt) * f.inv_det;
    const double pt = (W.nt * bn - W.nn * bt) * f.inv_det;
    if (pn >= 0.0 && std::abs(pt) <= mu * pn) return {pn, pt, ContactStatus::Stick};
  }

  // 3. Slide with sense s (U_T has the sign of s, P_T = −s mu P_N) and U_N = 0:
  //    b_N + (W_NN − s mu W_NT) P_N = 0.
  // On the edge of the cone (U_T = 0: stick and slide coincide) rounding can fail both the
  // stick test above and s U_T >= 0 here by an ulp; the slide with the least negative s U_T
  // is then the answer (the other sense is off by a finite margin).
  LocalImpulse nearest;
  double nearest_margin = -HUGE_VAL;
  for (const double s : {bt >= 0.0 ? 1.0 : -1.0, bt >= 0.0 ? -1.0 : 1.0}) {
    const double inv_den = s > 0.0 ? f.inv_den_fwd : f.inv_den_bwd;
    if (!(inv_den > 0.0)) continue;
    const double pn = -bn * inv_den;
    const double ut = bt + (W.nt - s * mu * W.tt) * pn;
    const LocalImpulse slide{pn, -s * mu * pn, s > 0.0 ? ContactStatus::SlipForward : ContactStatus::SlipBackward};
    if (pn >= 0.0 && s * ut >= 0.0) return slide;
    if (pn >= 0.0 && s * ut > nearest_margin) {
      nearest_margin = s * ut;
      nearest = slide;
    }
  }
  if (nearest_margin > -HUGE_VAL) return nearest;

  // 4. No consistent case (a degenerate block): fall back to frictionless normal closure.
  const double pn = W.nn > 0.0 ? -bn / W.nn : 0.0;
  return {pn, 0.0, ContactStatus::SlipForward};
}

/// The same, computing the factors on the spot (a single solve).
inline LocalImpulse solve_coulomb_2d(const Block2& W, double bn, double bt, double mu) {
  return solve_coulomb_2d(W, coulomb_factors(W, mu), bn, bt, mu);
}

}  // namespace nscd
