// validation/extremes/extremes.hpp — the extremes suite (issue #9): scenes pushed to their
// limits (mass ratios, step length, impact speed, friction, restitution, size and aspect
// ratios, vertex counts, exactly touching edges, far from the origin, the ballast sublayer's
// stiffness, the step length on the loaded ballast sample, 10^5 steps at rest), each run with NLGS at
// the drivers' default setting and with NEWTON_AC, each with what must hold.
//
// A run's outcome is one of
//   holds     every condition holds and nothing was reported;
//   warned    every condition holds, but the run reported something (unconverged steps, a
//             false convergence, an alert-distance skip, coarse positions far from the origin);
//   reported  a condition failed and the run said so (the guard refused a step or the scene was
//             refused, or steps were unconverged, falsely converged or skipped the alert distance);
//   SILENT    a condition failed and nothing was reported: the one outcome nscd must not have.
// A family sweeps one parameter in order; its limit is the last value up to which every run
// holds. A NaN or infinite position or velocity fails any run. The suite's exit status is 1 if any run is SILENT or a run marked `must_hold` fails.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "nscd/registry/registry.hpp"
#include "nscd/solvers/moreau_jean.hpp"

namespace nscd::extremes {

constexpr double kNone = std::numeric_limits<double>::infinity();

/// What must hold over a run (kNone: not checked).
struct Expect {
  double max_overlap = kNone;   ///< largest end-of-step overlap (m)
  double max_drift = kNone;     ///< largest displacement of a watched body from its start (m): stays put
  double energy_slack = kNone;  ///< E(t) <= E(0) + slack at every step (J/m): no energy created
  bool no_tunnelling = false;   ///< every watched body stays above `floor_y` and within [x_left, x_right]
  double floor_y = 0.0, x_left = -kNone, x_right = kNone;
};

/// One run: a scene, the bodies watched, a number of steps, what must hold.
struct Scenario {
  Registry reg;
  std::vector<BodyId> watched;
  std::int64_t steps = 0;
  Expect expect;
  /// The energy whose growth `expect.energy_slack` bounds (empty: total_energy). Scenes with
  /// springs or imposed forces add the springs' elastic energy and the force's potential.
  std::function<double(const Registry&)> energy;
  /// A family's own conditions, called after every step (`last` on the last one, or on the
  /// step that threw): returns what failed, in words, or "" (kept: the first failure).
  std::function<std::string(const Registry&, bool last)> check;
  /// Set when the scene itself was refused with an error before any step (e.g. a load the
  /// sublayer cannot carry): the run is judged failed and reported, with this message.
  std::string refused;
  /// What the family measured beyond the common columns, in words, read after the run
  /// (e.g. the sublayer's deflection against the static one); printed with the failures.
  std::function<std::string()> note;
};

/// One parameter value of a family.
struct Point {
  std::string value;                    ///< as printed, e.g. "1:1e3"
  std::function<Scenario()> build;
  bool quick = false;                   ///< part of the CI subset
  bool must_hold = false;               ///< a failure is a suite failure (nominal settings)
};

struct Family {
  std::string name;                     ///< e.g. "stack of 30, masses alternating, light at the bottom"
  std::string holds;                    ///< what must hold, in words
  std::vector<Point> points;            ///< in increasing severity
};

enum class Verdict { Holds, Warned, Reported, Silent };
const char* name_of(Verdict v);

struct Outcome {
  Verdict verdict = Verdict::Holds;
  std::string failed;            ///< the conditions that failed, in words
  std::string refused;           ///< the guard's message when a step was refused
  std::string note;              ///< Scenario::note's text
  std::int64_t steps = 0, unconverged = 0, false_converged = 0, alert_skips = 0, coarse = 0;
  bool non_finite = false;       ///< a body's position or velocity became NaN or infinite
  double max_overlap = 0.0, max_drift = 0.0, energy_gain = 0.0, max_residual = 0.0, seconds = 0.0;
};

/// The drivers' default for `solver` (NLGS: QM/16, tol 1.666e-4, 1000 sweeps; NEWTON_AC: tol
/// 1e-8), with the natural-map residual checked at every step.
StepperOptions setting(SolverKind solver);

/// Runs the scenario with the options and judges it.
Outcome run(Scenario s, const StepperOptions& options);

/// v with 3 significant digits (as "%.3g"), for the judgements' texts.
std::string g3(double v);

// ---- scene builders (scenes.cpp) ------------------------------------------------------------
/// A fixed floor (top face at y = y0, 40 m wide, "big") centred on x0; material "stone"
/// density 2000; default law IQS_CLB with `mu`; alert 1.25 mm; θ = 0.5; h = `dt`.
Registry base_registry(double dt, double mu = 0.5, double x0 = 0.0, double y0 = 0.0);
/// n blocks w × h stacked exactly (gaps 0) on the floor of `reg`, centred on x0, bottom at y0;
/// block k has density 2000 × (k odd == light_bottom ? ratio : 1). Returns the blocks.
std::vector<BodyId> add_stack(Registry& reg, int n, double ratio, bool light_bottom, double w = 0.2, double h = 0.1,
                              double x0 = 0.0, double y0 = 0.0);
/// Regular polygons of `vertices` vertices and circumscribed diameter d on a square lattice of
/// pitch 1.2 d in a box of fixed walls of inner width `width` (floor top y = 0), rows from
/// y = 0.6 d + lift, random orientations (fixed seed). Returns the grains.
std::vector<BodyId> add_dropped_polygons(Registry& reg, int n, int vertices, double d, double width, double lift = 0.0,
                                         double x0 = 0.0);
/// A triangular pile of regular pentagons (circumscribed diameter d; rows of base, base − 1,
/// ..., 1 grains) on a lattice of pitch 1.02 d (no initial overlap), bottom row's centres at
/// y = d/2, random orientations: grains fall a little and settle. Returns the grains.
std::vector<BodyId> add_pile(Registry& reg, int base, double d, double x0 = 0.0);
/// Total energy: kinetic plus gravitational potential (J/m).
double total_energy(const Registry& reg);

/// Every body that can move vertically (not fixed).
std::vector<BodyId> all_dynamic(const Registry& reg);

// ---- the families (families.cpp, families_shape.cpp, families_ballast.cpp) -----------------
std::vector<Family> families(bool full);

}  // namespace nscd::extremes
