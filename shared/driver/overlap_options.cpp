// nscd/shared/driver/overlap_options.cpp — see overlap_options.hpp.
#include "nscd/shared/driver/overlap_options.hpp"

#include <string>

namespace nscd::driver {

const char* overlap_limit_help(OverlapYardstick y) {
  if (y == OverlapYardstick::FreeBody)
    return "overlap budget (m): a step whose largest overlap passes it is warned about once and counted in summary.txt; "
           "-1: 5e-4 x the smallest free body's size; 0: none";
  return "overlap budget (m): a step whose largest overlap passes it is warned about once and counted in summary.txt; "
         "-1: 5e-4 x the smallest grain's size (5 um for 1 cm grains); 0: none";
}

const char* strict_overlap_help(StrictStop s) {
  if (s == StrictStop::AtCycleEnd)
    return "stop with a checkpoint at the end of the cycle in which the overlap budget was passed (exit 3)";
  return "stop with an error (exit 1) at the first step whose largest overlap passes the budget, its state written to "
         "stopped_state.nscd";
}

void check_overlap_options(double overlap_limit, bool strict_overlap, OverlapYardstick y) {
  const char* what = y == OverlapYardstick::FreeBody ? "the smallest free body" : "the smallest grain";
  if (!(overlap_limit >= 0.0 || overlap_limit == -1.0))
    throw InputError("--overlap-limit must be >= 0 (m; 0: none) or -1 (the default: a fraction of " + std::string(what) +
                     "), got " + detail::text_of(overlap_limit));
  if (strict_overlap && overlap_limit == 0.0)
    throw InputError("--strict-overlap needs an overlap budget: --overlap-limit is 0 (none)");
}

}  // namespace nscd::driver
