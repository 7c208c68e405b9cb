// nscd/solvers/step_guard.hpp — the stepper's guard (issue #9): what MoreauJean::step checks
// so that a step is either valid or refused, never silently wrong.
//
//   start state  the positions and velocities at t_i are finite (else the state was corrupted
//                outside the stepper: a reader, a driver writing the tables);
//   free state   q_m and u_free are finite (else a user's force function, an imposed velocity
//                or an overflow of q + h u produced a NaN or an Inf);
//   solution     impulses of the contacts and spring links, u_f and q_f are finite;
//   alert skip   no polygon travels farther than the alert distance in the step:
//                travel = h (max(|u_i|, |u_f|) + max(|ω_i|, |ω_f|) R) with R the polygon's
//                radius about its body's centre of mass. A larger travel can close a gap that
//                the detection at q_m did not see (docs/theory.md, "Alert distance and step");
//   resolution   far from the origin the spacing of doubles (ulp of the largest coordinate)
//                becomes coarse: above alert/1000 positions are rounded by more than a
//                contact can be trusted to (1e10 m: 2 µm).
//
// The checks read only; they never change a value, so a run with them gives the same
// trajectory bit for bit. The messages name the step, the bodies ('name' (#index)) and the
// contacts (index in the step's problem, as in its dump, and its two bodies).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "nscd/registry/registry.hpp"
#include "nscd/solvers/contact_system.hpp"

namespace nscd {

/// "'name' (#i)" for messages.
std::string body_label(const Registry& reg, std::size_t body);

/// Empty if every body's position, angle and velocity at the start of the step are finite;
/// otherwise what is wrong, for at most a few bodies. (The checks read a large system's bodies
/// on `threads` threads, from kLightParallelMin on: the same answer on any number.)
std::string check_start_state(const Registry& reg, int threads = 1);

/// Empty if q_m and u_free are finite for every body; otherwise what is wrong (naming the
/// external force when the start state was finite).
std::string check_free_state(const Registry& reg, std::span<const double> qm_x, std::span<const double> qm_y,
                             std::span<const double> qm_a, std::span<const SolverBody> free, double t_m,
                             int threads = 1);

/// Empty if the solver's answer is finite: contact and link impulses, u_f and q_f =
/// q_m + θ h u_f; otherwise what is wrong, naming contacts and bodies. The contacts of a large
/// system are read on `threads` threads (OpenMP; the same answer on any number).
std::string check_solution(const Registry& reg, const ContactSystem& sys, std::span<const double> qm_x,
                           std::span<const double> qm_y, std::span<const double> qm_a, double h, double theta,
                           int threads = 1);

struct AlertTravel {
  std::size_t skips = 0;        ///< polygons whose travel exceeds the alert distance
  double max_travel = 0.0;      ///< the largest travel (m)
  std::int64_t fastest = -1;    ///< body of the largest travel (−1: no polygon)
  double resolution = 0.0;      ///< spacing of doubles at the largest |x|, |y| of a polygon's body (m)
};

/// Travel of every polygon over the step from the velocities at t_i (in the registry) and at
/// t_f (`end`), against reg.params.alert; on `threads` threads from kLightParallelMin polygons on
/// (the same answer: counts and maxima, the first fastest body in polygon order).
AlertTravel alert_travel(const Registry& reg, std::span<const SolverBody> end, double h, int threads = 1);

}  // namespace nscd
