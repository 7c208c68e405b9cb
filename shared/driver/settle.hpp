// nscd/shared/driver/settle.hpp — the one "step until at rest" loop of the drivers (the deposit,
// the ballast sample's deposit and its sleeper).
//
// settle() calls `step` (one time step; the caller may do it call by call, or count it) until
//   * the bodies are at rest: their rms speed (mass-weighted, scenes::rms_speed) below
//     rule.speed for ceil(rule.window / dt) consecutive steps, counted once rule.min_time of
//     simulated time has passed since the call; or
//   * rule.max_time of simulated time has passed since the call, or rule.max_steps steps.
// With rule.stop_at_rest false only the limits stop it (a fixed number of steps). After every
// step `observe` sees the step's report, the rms speed, the steps done and whether the rest
// rule is met (CSV rows, frames, progress lines).
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <span>

#include "nscd/registry/registry.hpp"
#include "nscd/solvers/moreau_jean.hpp"

namespace nscd::driver {

struct SettleRule {
  double speed = 1e-3;     ///< at rest: rms speed below this (m/s) ...
  double window = 0.05;    ///< ... for this long (s of simulated time: ceil(window / dt) steps in a row)
  double min_time = 0.0;   ///< steps count toward the window from this simulated time since the call (s, inclusive)
  double max_time = std::numeric_limits<double>::infinity();  ///< simulated time limit since the call (s)
  std::int64_t max_steps = 0;  ///< step limit (0: none)
  bool stop_at_rest = true;    ///< false: run to the limits whatever the speed
  int threads = 1;             ///< the rms speed's sum on this many threads (the same bits on any number)
};

/// What observe sees after each step.
struct SettleStep {
  const StepReport& report;
  double rms_speed;    ///< of the bodies, after the step (m/s)
  std::int64_t steps;  ///< steps done by this call, this one included
  double elapsed;      ///< simulated time since the call (s)
  bool at_rest;        ///< the rest rule is met: this is the last step
};

struct SettleResult {
  bool at_rest = false;
  std::int64_t steps = 0;  ///< steps done
  double elapsed = 0.0;    ///< simulated time since the call (s)
  double rms_speed = 0.0;  ///< after the last step (m/s)
  StepReport last;         ///< the last step's report
};

/// Steps `reg` with `step` until the rule stops it (see the file comment). Throws nscd::Error
/// on a rule out of range (speed, window, min_time < 0, max_time not > 0, max_steps < 0, or no
/// limit at all with stop_at_rest false).
SettleResult settle(const Registry& reg, std::span<const BodyId> bodies, const SettleRule& rule, const std::function<StepReport()>& step,
                    const std::function<void(const SettleStep&)>& observe = {});

}  // namespace nscd::driver
