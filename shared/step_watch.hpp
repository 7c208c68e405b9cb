// nscd/shared/step_watch.hpp — what the drivers say about a run's steps besides their
// results (issue #9): alert-distance skips and steps the LMGC90 criterion called converged
// although the natural-map residual says otherwise (StepReport::alert_skips, false_converged).
//
// One warning line per burst, not per step: a burst starts at the first such step after
// `quiet_steps` steps without one; the steps of a burst are counted, and the totals go into
// the driver's summary.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <utility>

#include "nscd/core/error.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/io/text_reader.hpp"
#include "nscd/registry/registry.hpp"
#include "nscd/shared/analysis.hpp"
#include "nscd/solvers/moreau_jean.hpp"

namespace nscd::scenes {

/// The solve profile `p` as a few lines for the end of a run (--solve-profile): each part's
/// thread-seconds and its share of the region's thread-seconds, against `solve_seconds`, the
/// solves' own wall seconds; "" where no solve was profiled.
inline std::string solve_profile_table(const SolveParts& p, double solve_seconds) {
  if (p.region <= 0.0) return {};
  const double whole = p.thread_seconds > 0.0 ? p.thread_seconds : 1.0;
  std::string s;
  char b[200];
  std::snprintf(b, sizeof b,
                "solve profile: %.3f s of the solves' %.3f s in their threads' region, on %.2f threads on average;\n"
                "  the threads' time there (thread-seconds, and a share of region x threads):\n",
                p.region, solve_seconds, p.thread_seconds / p.region);
  s += b;
  const std::pair<const char*, double> rows[] = {{"sweeping", p.sweeping}, {"waiting", p.waiting},
                                                 {"mixing", p.mixing},     {"serial (thread 0)", p.serial},
                                                 {"set-up", p.setup},      {"unclocked", p.thread_seconds - p.parts()}};
  for (const auto& [name, v] : rows) {
    std::snprintf(b, sizeof b, "    %-18s %9.3f s  %5.1f %%\n", name, v, 100.0 * v / whole);
    s += b;
  }
  return s;
}

struct StepWatch {
  std::int64_t quiet_steps = 1000;     ///< steps without an event that end a burst
  std::int64_t alert_skip_steps = 0;   ///< steps with a polygon travelling beyond the alert distance
  double max_travel = 0.0;             ///< largest travel in one step over the run (m)
  std::int64_t residual_checks = 0;    ///< steps whose natural-map residual was computed
  std::int64_t false_converged = 0;    ///< of those: converged by the criterion, residual above the flag
  double max_residual = 0.0;           ///< largest checked natural-map residual / ‖q‖
  std::int64_t coarse_position_steps = 0;  ///< steps far enough from the origin that doubles are coarse
  std::int64_t last_skip = -1'000'000'000, last_false = -1'000'000'000;
  // The overlap budget (docs/user-guide.md, "Overlap budget"): a step whose largest overlap
  // passes overlap_limit is warned about once and counted; a strict driver stops on it.
  double overlap_limit = 0.0;            ///< m; 0: no budget
  std::int64_t over_limit_steps = 0;     ///< steps whose largest overlap passed the limit
  std::int64_t first_over_limit = -1;    ///< the first of them (−1: none)
  // The overlap projection (StepReport::projection_*): how often it acted, and how much.
  std::int64_t projected_steps = 0, projection_sweeps = 0;  ///< (the sweeps: what it cost, summed)
  double max_projection_excess = 0.0, max_projection_shift = 0.0;
  // What the steps cost, phase by phase (StepReport's wall seconds, summed): which phases a
  // thread count speeds up, from two runs' summaries (docs/user-guide.md §2.5b).
  double step_seconds = 0.0, detect_seconds = 0.0, prepare_seconds = 0.0, solve_seconds = 0.0, end_seconds = 0.0;
  // The threads the steps' solves and loops ran on (StepReport::solve_threads, loop_threads),
  // summed: their means say what the choice by measure settled on (docs/user-guide.md §2.5b).
  std::int64_t steps = 0, solve_threads = 0, loop_threads = 0;
  // Where the solves' threads spent their time (--solve-profile: StepReport::solve_parts), summed.
  SolveParts solve_parts;

  void observe(const Registry& reg, const StepReport& r, const StepperOptions& o, std::FILE* out = stdout) {
    step_seconds += r.step_seconds, detect_seconds += r.detect_seconds, prepare_seconds += r.prepare_seconds;
    solve_seconds += r.solve_seconds, end_seconds += r.end_seconds;
    ++steps, solve_threads += r.solve_threads, loop_threads += r.loop_threads;
    solve_parts += r.solve_parts;
    max_travel = std::max(max_travel, r.max_travel);
    if (r.alert_skips > 0) {
      ++alert_skip_steps;
      if (r.step - last_skip > quiet_steps) {
        const std::size_t b = static_cast<std::size_t>(std::max<std::int64_t>(r.fastest_body, 0));
        std::fprintf(out,
                     "WARNING step %lld (t %.6g s): body '%s' moves %.3g m in one step, more than the alert distance %.3g m "
                     "(%zu polygon(s)): contacts can be missed, bodies can pass through each other; keep dt x fastest "
                     "speed below the alert distance (docs/theory.md). Further such steps within %lld steps are only counted.\n",
                     static_cast<long long>(r.step), r.time, reg.bodies.name[b].c_str(), r.max_travel, reg.params.alert,
                     r.alert_skips, static_cast<long long>(quiet_steps));
        std::fflush(out);
      }
      last_skip = r.step;
    }
    if (r.projection_sweeps > 0) {
      ++projected_steps;
      projection_sweeps += r.projection_sweeps;
      max_projection_excess = std::max(max_projection_excess, r.projection_excess);
      max_projection_shift = std::max(max_projection_shift, r.projection_shift);
    }
    if (overlap_limit > 0.0 && r.max_overlap > overlap_limit) {
      if (over_limit_steps++ == 0) {
        first_over_limit = r.step;
        std::fprintf(out,
                     "WARNING step %lld (t %.6g s): largest overlap %.3g m, above the overlap limit %.3g m: the settlement "
                     "measured from here on carries that much interpenetration (tighten --tol, keep --projection on, or "
                     "shorten --dt; docs/user-guide.md, \"Overlap budget\"). Further such steps are only counted.\n",
                     static_cast<long long>(r.step), r.time, r.max_overlap, overlap_limit);
        std::fflush(out);
      }
    }
    if (r.coarse_positions && coarse_position_steps++ == 0) {
      std::fprintf(out,
                   "WARNING step %lld (t %.6g s): coordinates are so far from the origin that positions are resolved to "
                   "%.3g m only (> alert distance / 1000): move the scene's origin near the bodies (docs/theory.md).\n",
                   static_cast<long long>(r.step), r.time, r.position_resolution);
      std::fflush(out);
    }
    if (r.residual_checked) {
      ++residual_checks;
      max_residual = std::max(max_residual, r.residual);
      if (r.false_converged) {
        ++false_converged;
        if (r.step - last_false > quiet_steps) {
          std::fprintf(out,
                       "WARNING step %lld (t %.6g s): the solver reports converged but the natural-map residual / |q| is "
                       "%.3g (> %.3g): its criterion is fooled (large mass ratios? see docs/theory.md, \"When converged "
                       "is not\"). Further such steps within %lld steps are only counted.\n",
                       static_cast<long long>(r.step), r.time, r.residual, o.residual_flag, static_cast<long long>(quiet_steps));
          std::fflush(out);
        }
        last_false = r.step;
      }
    }
  }

  /// "key = value" lines for a summary file (this process's steps).
  std::string summary() const {
    char b[1024];
    std::snprintf(
        b, sizeof b,
        "alert_skip_steps = %lld\nmax_step_travel = %.10g\nresidual_checks = %lld\nfalse_converged_steps = %lld\n"
        "max_checked_residual = %.10g\ncoarse_position_steps = %lld\noverlap_limit = %.10g\n"
        "over_limit_steps = %lld\nfirst_over_limit_step = %lld\nprojected_steps = %lld\n"
        "projection_sweeps = %lld\nmax_projection_excess = %.10g\nmax_projection_shift = %.10g\n",
        static_cast<long long>(alert_skip_steps), max_travel, static_cast<long long>(residual_checks),
        static_cast<long long>(false_converged), max_residual, static_cast<long long>(coarse_position_steps),
        overlap_limit, static_cast<long long>(over_limit_steps), static_cast<long long>(first_over_limit),
        static_cast<long long>(projected_steps), static_cast<long long>(projection_sweeps), max_projection_excess,
        max_projection_shift);
    char c[400];
    const double per = steps > 0 ? 1.0 / static_cast<double>(steps) : 0.0;
    std::snprintf(c, sizeof c,
                  "step_seconds = %.10g\ndetect_seconds = %.10g\nprepare_seconds = %.10g\nsolve_seconds = %.10g\n"
                  "end_step_seconds = %.10g\nmean_solve_threads = %.4g\nmean_loop_threads = %.4g\n",
                  step_seconds, detect_seconds, prepare_seconds, solve_seconds, end_seconds,
                  static_cast<double>(solve_threads) * per, static_cast<double>(loop_threads) * per);
    return std::string(b) + c + solve_parts_keys();
  }

  /// The solve profile's keys (solve_region_seconds, …; thread-seconds), or "" where no solve
  /// was profiled.
  std::string solve_parts_keys() const {
    if (solve_parts.region <= 0.0) return {};
    const SolveParts& p = solve_parts;
    char b[600];
    std::snprintf(b, sizeof b,
                  "solve_region_seconds = %.10g\nsolve_thread_seconds = %.10g\nsolve_sweeping_seconds = %.10g\n"
                  "solve_waiting_seconds = %.10g\nsolve_mixing_seconds = %.10g\nsolve_serial_seconds = %.10g\n"
                  "solve_setup_seconds = %.10g\n",
                  p.region, p.thread_seconds, p.sweeping, p.waiting, p.mixing, p.serial, p.setup);
    return b;
  }

  /// The solve profile as a few lines for the end of a run (--solve-profile): each part's
  /// thread-seconds and its share of the region's thread-seconds; "" where no solve was profiled.
  std::string solve_profile_table() const;

  /// One line for the end of a run, empty when nothing happened.
  std::string closing_line() const {
    if (alert_skip_steps == 0 && false_converged == 0) return {};
    char b[400];
    std::snprintf(b, sizeof b,
                  "      WARNING: %lld step(s) moved a body beyond the alert distance (largest move %.3g m); %lld of %lld "
                  "checked step(s) reported converged with a natural-map residual above the flag\n",
                  static_cast<long long>(alert_skip_steps), max_travel, static_cast<long long>(false_converged),
                  static_cast<long long>(residual_checks));
    return b;
  }
};

inline std::string StepWatch::solve_profile_table() const {
  return scenes::solve_profile_table(solve_parts, solve_seconds);
}

/// The smallest body that can move (not driven, with a mass), by its contactors' size (m): the
/// overlap budget's yardstick in a driver that has no list of grains; 0 when there is none.
inline double smallest_free_body_size(const Registry& reg) {
  double r = 0.0;
  auto consider = [&](BodyId b, double radius) {
    const std::size_t i = b.index();
    if (!reg.bodies.is_driven[i] && reg.bodies.inv_mass_x[i] > 0.0 && (r == 0.0 || radius < r)) r = radius;
  };
  for (std::size_t k = 0; k < reg.polyg.size(); ++k) consider(reg.polyg.body[k], reg.polyg.radius[k]);
  for (std::size_t k = 0; k < reg.diskx.size(); ++k) consider(reg.diskx.body[k], reg.diskx.radius[k]);
  return 2.0 * r;
}

/// The overlap budget (m) that an --overlap-limit value gives: −1 takes kOverlapLimitFraction of
/// `smallest` (the smallest grain's or free body's size), 0 is none, any other value is itself.
inline double overlap_budget(double overlap_limit, double smallest) {
  return overlap_limit < 0.0 ? kOverlapLimitFraction * smallest : overlap_limit;
}

/// --strict-overlap in a driver without checkpoints of its own: the state of the step that passed
/// the budget goes to OUT/stopped_state.nscd (with the driver's `extra` keys), then the run stops
/// with an error (exit 1).
[[noreturn]] inline void stop_over_budget(const Registry& reg, const MoreauJean& mj, const std::filesystem::path& out,
                                          const StepReport& r, const StepWatch& watch,
                                          const std::map<std::string, std::string>& extra = {}) {
  const std::filesystem::path state = out / "stopped_state.nscd";
  std::string kept = "the state is in " + state.string();
  try {
    save_checkpoint(state, reg, mj.warm_start_memory(), extra);
  } catch (const Error& e) {  // e.g. a drive given as a function, which no checkpoint holds
    kept = std::string("no state written: ") + e.what();
  }
  throw Error("step " + std::to_string(r.step) + ": largest overlap " + exact(r.max_overlap) + " m passed the overlap budget " +
              exact(watch.overlap_limit) + " m (--strict-overlap); " + kept);
}

/// A driver's overlap budget over all its phases: the watch, and --strict-overlap's stop.
struct OverlapBudget {
  StepWatch watch;
  bool strict = false;
  std::filesystem::path out;  ///< where stopped_state.nscd goes

  void observe(const Registry& reg, const MoreauJean& mj, const StepReport& r) {
    watch.observe(reg, r, mj.options());
    if (strict && watch.over_limit_steps > 0) stop_over_budget(reg, mj, out, r, watch);
  }
};

}  // namespace nscd::scenes
