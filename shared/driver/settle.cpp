// nscd/shared/driver/settle.cpp — see settle.hpp.
#include "nscd/shared/driver/settle.hpp"

#include <cmath>
#include <string>

#include "nscd/core/error.hpp"
#include "nscd/io/text_reader.hpp"
#include "nscd/shared/analysis.hpp"

namespace nscd::driver {

SettleResult settle(const Registry& reg, std::span<const BodyId> bodies, const SettleRule& rule, const std::function<StepReport()>& step,
                    const std::function<void(const SettleStep&)>& observe) {
  if (!(rule.speed >= 0.0) || !(rule.window >= 0.0) || !(rule.min_time >= 0.0) || !(rule.max_time > 0.0) || rule.max_steps < 0)
    throw Error("settle: speed, window and min_time must be >= 0, max_time > 0 and max_steps >= 0; got speed " + exact(rule.speed) +
                ", window " + exact(rule.window) + ", min_time " + exact(rule.min_time) + ", max_time " + exact(rule.max_time) +
                ", max_steps " + std::to_string(rule.max_steps));
  if (!rule.stop_at_rest && rule.max_steps == 0 && std::isinf(rule.max_time))
    throw Error("settle: without the rest rule, a step or time limit is needed");
  const double t_start = reg.time;
  const auto window = static_cast<std::int64_t>(std::ceil(rule.window / reg.params.dt));
  std::int64_t calm = 0;
  SettleResult res;
  while (reg.time - t_start < rule.max_time && (rule.max_steps == 0 || res.steps < rule.max_steps)) {
    res.last = step();
    ++res.steps;
    res.elapsed = reg.time - t_start;
    res.rms_speed = scenes::rms_speed(reg, bodies, rule.threads);
    if (rule.stop_at_rest && res.elapsed >= rule.min_time) {
      calm = res.rms_speed < rule.speed ? calm + 1 : 0;
      res.at_rest = calm >= window;
    }
    if (observe) observe(SettleStep{res.last, res.rms_speed, res.steps, res.elapsed, res.at_rest});
    if (res.at_rest) break;
  }
  return res;
}

}  // namespace nscd::driver
