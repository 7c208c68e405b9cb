// nscd/interactions/kinematics.hpp — the local kinematics of a 2D contact (paper §2.4).
//
// For a contact point with frame (n, t), candidate body c and antagonist body a, lever arms
// r_c = point − G_c and r_a = point − G_a, the relative velocity of the candidate's material
// point with respect to the antagonist's is U = H* u:
//     U_N = n·(v_c − v_a) + ω_c cross(r_c, n) − ω_a cross(r_a, n)
//     U_T = t·(v_c − v_a) + ω_c cross(r_c, t) − ω_a cross(r_a, t)
// (in 2D, ω × r · n = ω cross(r, n)). The contact force R = R_N n + R_T t acts on the
// candidate, −R on the antagonist: the generalized forces r = H R are
//     candidate:  (R_N n + R_T t,  R_N cross(r_c, n) + R_T cross(r_c, t))
//     antagonist: −(the same with r_a).
#pragma once

#include "nscd/core/math.hpp"

namespace nscd {

/// The projected lever arms of one contact and its frame: everything H and H* need.
struct ContactFrame {
  Vec2 n;
  double cd_rn, cd_rt, an_rn, an_rt;
};

struct BodyVelocity {
  double vx, vy, w;
};

struct LocalVelocity {
  double un, ut;
};

/// U = H* u for one contact.
inline LocalVelocity relative_velocity(const ContactFrame& f, BodyVelocity cd, BodyVelocity an) {
  const Vec2 t = perp(f.n);
  const Vec2 dv{cd.vx - an.vx, cd.vy - an.vy};
  return {dot(f.n, dv) + cd.w * f.cd_rn - an.w * f.an_rn, dot(t, dv) + cd.w * f.cd_rt - an.w * f.an_rt};
}

/// Generalized force on the candidate from the local force (rn, rt); the antagonist gets
/// (−fx, −fy, −(rn an_rn + rt an_rt)).
inline BodyVelocity candidate_force(const ContactFrame& f, double rn, double rt) {
  const Vec2 t = perp(f.n);
  return {rn * f.n.x + rt * t.x, rn * f.n.y + rt * t.y, rn * f.cd_rn + rt * f.cd_rt};
}
inline BodyVelocity antagonist_force(const ContactFrame& f, double rn, double rt) {
  const Vec2 t = perp(f.n);
  return {-(rn * f.n.x + rt * t.x), -(rn * f.n.y + rt * t.y), -(rn * f.an_rn + rt * f.an_rt)};
}

}  // namespace nscd
