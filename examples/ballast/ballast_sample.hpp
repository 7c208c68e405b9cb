// examples/ballast/ballast_sample.hpp — steps 0 and 1 of a ballast run (ballast_study.cpp): the
// output folder, and the sample: a resumed run's checkpoint (--resume), a prepared sample
// (--sample) or one prepared by the run. For ballast_study.cpp; not a public interface.
#pragma once

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "ballast_study.hpp"
#include "nscd/shared/ballast.hpp"
#include "nscd/shared/step_watch.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "run_state.hpp"

namespace ballast {

using Clock = std::chrono::steady_clock;
/// Wall seconds since t0.
inline double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// What the steps of a run share: its options, its sample and its state.
struct Run {
  Config c;
  Config cli;  // the options as given, before a checkpoint or a loaded sample set any
  nscd::scenes::BallastScene s;
  RunState st;
  std::vector<nscd::MoreauJean::WarmStartEntry> warm;
  bool resumed = false, cycles_started = false;
  std::string sample_used;  // the sample file this run started from (empty: prepared)
};

/// 0. The output folder: never mixed with an earlier run's files.
void claim_output(const Run& r);
/// 1. The sample: a checkpoint's, a prepared one, or a new one (deposited in prepare_sample).
void obtain_sample(Run& r);
/// The largest load the sublayer can carry: its springs squeezed to zero length. A heavier
/// load pushes the pads through the floor (a settlement of kilometres, not a result).
void refuse_excess_load(const Run& r, double k_sample);
/// 1c. A new sample: the grains deposited until rest, then the sleeper placed and settled;
/// saved as sample.nscd.
void prepare_sample(Run& r, nscd::MoreauJean& mj, nscd::scenes::StepWatch& watch, const std::filesystem::path& out);

}  // namespace ballast
