// nscd/solvers/contact_part.hpp — the one contact-Jacobian part of nscd: the solver's view of
// a body, a contact and a spring link, and the few formulas every solver, the assembly of W and
// H, and the problem dump share (Jolt's AxisConstraintPart is the model: the equation in the
// comment, one small type).
//
// A contact α between candidate body c and antagonist body a, frame (n, t = perp(n)), projected
// lever arms c_rn = cross(r_c, n), c_rt = cross(r_c, t) (r = point − centre of mass):
//     U = H*_α u:   U_N = n·(v_c − v_a) + ω_c c_rn − ω_a a_rn
//                   U_T = t·(v_c − v_a) + ω_c c_rt − ω_a a_rt
//     H_α P:        body c gets ( P_N n + P_T t,  P_N c_rn + P_T c_rt ), body a the opposite
//     W_αα = H*_α M⁻¹ H_α  (delassus_block)
// `jacobian_rows` gives the same rows as plain 3-vectors per body, for the assembly of W and
// of the global H. A spring link is the same with the normal row only.
//
// Kinematic bodies (walls, the floor, driven dofs: inverse mass 0 on every dof) are read but
// never written by any solver: each contact and link carries which of its bodies are dynamic.
#pragma once

#include <cstdint>

#include "nscd/laws/coulomb2d.hpp"
#include "nscd/laws/voigt_rod.hpp"

namespace nscd {

struct alignas(64) SolverBody {
  double vx = 0.0, vy = 0.0, w = 0.0;            ///< velocity being iterated (u_f)
  double inv_mx = 0.0, inv_my = 0.0, inv_i = 0.0; ///< 0 on kinematic dofs
};

/// True if a solver may change the body's velocity (some dof has a non-zero inverse mass).
inline bool is_dynamic(const SolverBody& b) { return b.inv_mx != 0.0 || b.inv_my != 0.0 || b.inv_i != 0.0; }

struct SolverContact {
  std::uint32_t cd = 0, an = 0;                  ///< body indices
  double nx = 0.0, ny = 0.0;                     ///< normal; t = (−ny, nx)
  double cd_rn = 0.0, cd_rt = 0.0, an_rn = 0.0, an_rt = 0.0;
  Block2 W;                                      ///< own Delassus block
  CoulombFactors f;                              ///< its reciprocals
  double sn = 0.0, st = 0.0;                     ///< law shifts
  double mu = 0.0;
  double pn = 0.0, pt = 0.0;                     ///< impulses (N·s per unit thickness)
  bool cd_dynamic = true, an_dynamic = true;     ///< kinematic bodies are never written
};
// Cold data of a contact (its registry row, its status) live beside, in ContactSystem.

/// A PTPT2 spring link in the solver: normal direction only, implicit VOIGT_ROD law.
struct SolverLink {
  std::uint32_t cd = 0, an = 0;  ///< body indices
  double nx = 0.0, ny = 0.0;     ///< from the antagonist point to the candidate point
  double cd_rn = 0.0, an_rn = 0.0;
  double w = 0.0;                ///< own Delassus scalar
  VoigtAffine law;
  double p = 0.0;                ///< impulse along n
  bool cd_dynamic = true, an_dynamic = true;
  std::uint32_t row = 0;         ///< row of Registry::links
};

inline double link_velocity(const SolverLink& l, const SolverBody& cd, const SolverBody& an) {
  return l.nx * (cd.vx - an.vx) + l.ny * (cd.vy - an.vy) + cd.w * l.cd_rn - an.w * l.an_rn;
}

inline void apply_link_impulse(const SolverLink& l, SolverBody& cd, SolverBody& an, double dp) {
  if (l.cd_dynamic) {
    cd.vx += cd.inv_mx * dp * l.nx;
    cd.vy += cd.inv_my * dp * l.ny;
    cd.w += cd.inv_i * dp * l.cd_rn;
  }
  if (l.an_dynamic) {
    an.vx -= an.inv_mx * dp * l.nx;
    an.vy -= an.inv_my * dp * l.ny;
    an.w -= an.inv_i * dp * l.an_rn;
  }
}

inline double link_delassus(const SolverLink& l, const SolverBody& cd, const SolverBody& an) {
  return cd.inv_mx * l.nx * l.nx + cd.inv_my * l.ny * l.ny + cd.inv_i * l.cd_rn * l.cd_rn + an.inv_mx * l.nx * l.nx +
         an.inv_my * l.ny * l.ny + an.inv_i * l.an_rn * l.an_rn;
}

/// Condenses a link into its candidate when the antagonist is kinematic and the link acts on a
/// single free dof d of the candidate (H* component c): with U = c v_d + U_known and the link
/// impulse P = h a − h b U, that dof's momentum balance gives the effective mass m + h b c² and
/// the free velocity (m v_d + c (h a − h b U_known)) / (m + h b c²). Returns false (nothing
/// changed) when the link does not qualify.
inline bool condense_link(const SolverLink& l, SolverBody& cd, const SolverBody& an) {
  if (an.inv_mx != 0.0 || an.inv_my != 0.0 || an.inv_i != 0.0) return false;
  double* v[3] = {&cd.vx, &cd.vy, &cd.w};
  double* inv[3] = {&cd.inv_mx, &cd.inv_my, &cd.inv_i};
  const double comp[3] = {l.nx, l.ny, l.cd_rn};
  int dof = -1, count = 0;
  for (int d = 0; d < 3; ++d)
    if (*inv[d] > 0.0 && comp[d] != 0.0) {
      dof = d;
      ++count;
    }
  if (count != 1) return false;
  const double c = comp[dof];
  SolverBody known = cd;
  double* known_v[3] = {&known.vx, &known.vy, &known.w};
  *known_v[dof] = 0.0;
  const double u_known = link_velocity(l, known, an);
  const double m = 1.0 / *inv[dof];
  const double m_eff = m + l.law.hb * c * c;
  *v[dof] = (m * *v[dof] + c * (l.law.ha - l.law.hb * u_known)) / m_eff;
  *inv[dof] = 1.0 / m_eff;
  return true;
}

/// W_αα from the two bodies' inverse masses and the lever arms.
inline Block2 delassus_block(const SolverContact& c, const SolverBody& cd, const SolverBody& an) {
  const double tx = -c.ny, ty = c.nx;
  Block2 W;
  W.nn = cd.inv_mx * c.nx * c.nx + cd.inv_my * c.ny * c.ny + cd.inv_i * c.cd_rn * c.cd_rn +
         an.inv_mx * c.nx * c.nx + an.inv_my * c.ny * c.ny + an.inv_i * c.an_rn * c.an_rn;
  W.nt = cd.inv_mx * c.nx * tx + cd.inv_my * c.ny * ty + cd.inv_i * c.cd_rn * c.cd_rt +
         an.inv_mx * c.nx * tx + an.inv_my * c.ny * ty + an.inv_i * c.an_rn * c.an_rt;
  W.tt = cd.inv_mx * tx * tx + cd.inv_my * ty * ty + cd.inv_i * c.cd_rt * c.cd_rt +
         an.inv_mx * tx * tx + an.inv_my * ty * ty + an.inv_i * c.an_rt * c.an_rt;
  return W;
}

/// Relative velocity U = H* u of a contact (unshifted).
inline void contact_velocity(const SolverContact& c, const SolverBody& cd, const SolverBody& an, double& un,
                             double& ut) {
  const double dvx = cd.vx - an.vx, dvy = cd.vy - an.vy;
  un = c.nx * dvx + c.ny * dvy + cd.w * c.cd_rn - an.w * c.an_rn;
  ut = -c.ny * dvx + c.nx * dvy + cd.w * c.cd_rt - an.w * c.an_rt;
}

/// u += M⁻¹ H ΔP for a contact's candidate (impulse_on_cd) or antagonist (impulse_on_an), with
/// (fx, fy) = ΔP_N n + ΔP_T t.
inline void impulse_on_cd(const SolverContact& c, SolverBody& cd, double fx, double fy, double dpn, double dpt) {
  cd.vx += cd.inv_mx * fx;
  cd.vy += cd.inv_my * fy;
  cd.w += cd.inv_i * (dpn * c.cd_rn + dpt * c.cd_rt);
}
inline void impulse_on_an(const SolverContact& c, SolverBody& an, double fx, double fy, double dpn, double dpt) {
  an.vx -= an.inv_mx * fx;
  an.vy -= an.inv_my * fy;
  an.w -= an.inv_i * (dpn * c.an_rn + dpt * c.an_rt);
}

/// u += M⁻¹ H ΔP for the two bodies of a contact.
inline void apply_impulse(const SolverContact& c, SolverBody& cd, SolverBody& an, double dpn, double dpt) {
  const double fx = dpn * c.nx - dpt * c.ny, fy = dpn * c.ny + dpt * c.nx;
  if (c.cd_dynamic) impulse_on_cd(c, cd, fx, fy, dpn, dpt);
  if (c.an_dynamic) impulse_on_an(c, an, fx, fy, dpn, dpt);
}

/// … for one of its bodies only (the candidate if `on_cd`): what apply_impulse adds to it,
/// bit for bit.
inline void apply_impulse_to(const SolverContact& c, SolverBody& b, bool on_cd, double dpn, double dpt) {
  const double fx = dpn * c.nx - dpt * c.ny, fy = dpn * c.ny + dpt * c.nx;
  on_cd ? impulse_on_cd(c, b, fx, fy, dpn, dpt) : impulse_on_an(c, b, fx, fy, dpn, dpt);
}

/// The rows of H*_α as 3-vectors over each body's (vx, vy, ω), signs included: U_N =
/// cd_n·u_c + an_n·u_a, U_T = cd_t·u_c + an_t·u_a. A link has its normal row only (t rows 0).
struct JacobianRows {
  double cd_n[3], cd_t[3], an_n[3], an_t[3];
};

inline JacobianRows jacobian_rows(const SolverContact& c) {
  return {{c.nx, c.ny, c.cd_rn}, {-c.ny, c.nx, c.cd_rt}, {-c.nx, -c.ny, -c.an_rn}, {c.ny, -c.nx, -c.an_rt}};
}

inline JacobianRows jacobian_rows(const SolverLink& l) {
  return {{l.nx, l.ny, l.cd_rn}, {0.0, 0.0, 0.0}, {-l.nx, -l.ny, -l.an_rn}, {0.0, 0.0, 0.0}};
}

}  // namespace nscd
