// nscd/shared/driver/overlap_options.hpp — the overlap budget's two options, --overlap-limit and
// --strict-overlap (docs/user-guide.md, "Overlap budget"), declared and checked alike by every
// driver that watches it (scenes::OverlapBudget, scenes::StepWatch).
//
// A driver's Config holds them as `double overlap_limit = -1.0` and `bool strict_overlap`; its
// option table lists overlap_limit_option and strict_overlap_option, its checks call
// check_overlap_options, and scenes::overlap_budget turns the option into metres.
#pragma once

#include "nscd/shared/driver/options.hpp"

namespace nscd::driver {

/// What --overlap-limit -1 takes a fraction of: the smallest grain, or (a driver without a list of
/// grains) the smallest free body.
enum class OverlapYardstick { Grain, FreeBody };

/// What --strict-overlap does: stop with an error at the first step past the budget (exit 1), or
/// stop with a checkpoint at the end of the cycle that passed it (exit 3, the ballast study).
enum class StrictStop { AtStep, AtCycleEnd };

const char* overlap_limit_help(OverlapYardstick y);
const char* strict_overlap_help(StrictStop s);

/// Throws InputError unless --overlap-limit is >= 0 or -1, and --strict-overlap has a budget.
void check_overlap_options(double overlap_limit, bool strict_overlap, OverlapYardstick y);

/// The --overlap-limit row, for a Config with `double overlap_limit`.
template <class C>
Option<C> overlap_limit_option(OverlapYardstick y) {
  return {"overlap-limit", &C::overlap_limit, overlap_limit_help(y), Kind::Free};
}

/// The --strict-overlap row, for a Config with `bool strict_overlap`; a switch unless the driver
/// gives its bools other flags (the ballast study's "--name=false").
template <class C>
Option<C> strict_overlap_option(StrictStop s, unsigned flags = kSwitch) {
  return {"strict-overlap", &C::strict_overlap, strict_overlap_help(s), Kind::Free, flags};
}

}  // namespace nscd::driver
