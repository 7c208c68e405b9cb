// examples/study_common/progress.hpp — how far a plan running on this machine is: one line
// per minute while GNU parallel runs a phase (local_run.hpp), read from the tasks' files.
//   preparations: 2 of 3 done, 31.0s
//   runs: 5 of 33 done, 1430 of 3300 cycles (43 %), 25m10s; ETA 33m at the mean rate so far
// A study's runs do not cost the same (accuracy_study starts its NEWTON_AC runs, 4-7x the
// reference's cost a cycle, first): the ETA at the mean rate over the phase so far is then
// too long at first and shortens as the cheap runs go. It is an estimate, not a bound.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "plan.hpp"

namespace study {

/// One phase's tasks (phase "prepare" or "run" of the manifest) at one moment.
struct PhaseCount {
  int tasks = 0;          ///< the phase's tasks in the manifest
  int tasks_done = 0;     ///< of them, ok (check_tasks)
  long cycles = 0;        ///< runs: the cycles planned, summed over the runs
  long cycles_done = 0;   ///< runs: complete rows of their cycles.csv, summed
};

/// The phase's counts now, from DIR/manifest.csv's rows and the tasks' files.
PhaseCount count_phase(const std::filesystem::path& dir, const std::vector<ManifestRow>& rows, bool runs);

/// The share of the phase's work done since `start` (cycles for runs, tasks for preparations),
/// in [0, 1]; 1 when there was nothing left to do at the start.
double done_share(const PhaseCount& start, const PhaseCount& now, bool runs);

/// Seconds left at the mean rate since the start: elapsed × (1 − share) / share; NaN before any
/// work was done.
double eta_seconds(double elapsed, double share);

/// The progress line (no newline): see the header's examples.
std::string progress_text(const PhaseCount& start, const PhaseCount& now, bool runs, double elapsed);

/// Watches one phase of the plan in DIR: the counts at its start, then a line on demand.
class PhaseProgress {
 public:
  PhaseProgress(std::filesystem::path dir, bool runs);
  std::string line(double elapsed) const;  ///< reads the tasks' files again; never throws

 private:
  std::filesystem::path dir_;
  bool runs_;
  std::vector<ManifestRow> rows_;
  PhaseCount start_;
};

}  // namespace study
