// nscd/shared/progress.hpp — formatting for the progress lines of long runs (drivers print
// elapsed time and an ETA), and the ETA's estimate from the cost per step of the current phase.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <string>
#include <utility>

namespace nscd::scenes {

/// A duration in seconds as "12.3s", "4m05s" or "2h07m"; "?" when it is not finite.
inline std::string format_duration(double s) {
  char b[32];
  if (!std::isfinite(s)) return "?";
  if (s >= 3600) std::snprintf(b, sizeof b, "%dh%02dm", int(s / 3600), int(std::fmod(s, 3600) / 60));
  else if (s >= 60) std::snprintf(b, sizeof b, "%dm%02ds", int(s / 60), int(std::fmod(s, 60)));
  else std::snprintf(b, sizeof b, "%.1fs", s);
  return b;
}

/// The wall time left, estimated from what the steps cost *now*: the mean cost per step over
/// the last `window` seconds of wall time (issue #11). A run's steps do not cost the same
/// throughout: a deposit's first steps (grains falling freely, no contact) cost a hundredth of
/// its impact steps, so the mean over the whole run so far (elapsed / steps done) put the
/// deposit's ETA 5 to 14 times too low. The cost of the current phase is the best guess for the
/// steps left; it is not a bound (the next phase can cost more), and a progress line must not
/// call it one.
class StepCostEta {
 public:
  /// `window`: seconds of wall time over which the cost per step is averaged (> 0).
  explicit StepCostEta(double window = 10.0) : window_(window > 0 ? window : 10.0) {}

  /// Records that `step` steps are done at wall time `wall` (s, from any fixed origin);
  /// both non-decreasing. Call it after every step, or at least at every progress line.
  void observe(std::int64_t step, double wall) {
    marks_.emplace_back(step, wall);
    // keep one mark at or before the start of the window, so the window spans >= `window`
    while (marks_.size() > 2 && wall - marks_[1].second >= window_) marks_.pop_front();
  }

  /// Mean wall seconds per step over the window; NaN before two marks with steps between them.
  double seconds_per_step() const {
    if (marks_.size() < 2) return std::nan("");
    const auto& [s0, w0] = marks_.front();
    const auto& [s1, w1] = marks_.back();
    if (s1 <= s0) return std::nan("");
    return (w1 - w0) / double(s1 - s0);
  }

  /// Wall seconds for `steps_left` more steps at the current cost (NaN when unknown).
  double eta(std::int64_t steps_left) const { return double(steps_left > 0 ? steps_left : 0) * seconds_per_step(); }

 private:
  double window_;
  std::deque<std::pair<std::int64_t, double>> marks_;
};

}  // namespace nscd::scenes
