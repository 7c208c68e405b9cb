// tests/unit/nlgs_colored_fixtures.hpp — what the colored-order tests share (test_nlgs_colored.cpp,
// test_nlgs_colored_steps.cpp): the options of a colored sweep on some threads.
#pragma once

#include "nscd/solvers/nlgs.hpp"

namespace nscd::nlgs_colored_fixtures {

inline NlgsOptions colored(int threads) {
  NlgsOptions o;
  o.order = SweepOrder::Colored;
  o.threads = threads;
  o.min_sweeps = o.max_sweeps = 40;  // the same work whatever the threads
  return o;
}

}  // namespace nscd::nlgs_colored_fixtures
