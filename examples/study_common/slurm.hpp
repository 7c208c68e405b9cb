// examples/study_common/slurm.hpp — the Slurm side of a plan (plan.hpp): job-array scripts
// whose walltime and memory per task come from a measured cost model of ballast.
//   DIR/slurm_prepare.sbatch  array 1-P over prepare.txt (one preparation per task)
//   DIR/slurm.sbatch          array 1-N over commands.txt (one run per task), --requeue: a
//                             requeued task runs the same line, whose --continue resumes the
//                             run from its checkpoint
//   DIR/submit_slurm.sh       submits the first, then the second with --dependency=afterok
//   DIR/slurm/                the tasks' Slurm output files (created: Slurm does not create it)
#pragma once

#include <string>

#include "plan.hpp"

namespace study {

/// The cost of ballast, measured on this project's machine (docs/studies.md §2.2 gives the
/// command and the figures): processor seconds per step per grain of the loading cycles, per
/// grain of a preparation, and the largest resident memory as a + b × grains.
struct CostModel {
  double cycle_seconds_per_step_grain = 0.0;
  double prepare_seconds_per_grain = 0.0;
  double memory_mib_base = 0.0;
  double memory_mib_per_grain = 0.0;
  double time_safety = 3.0;     ///< walltime asked = estimate × this (slower nodes, more sweeps)
  double memory_safety = 2.0;   ///< memory asked = estimate × this
  double min_seconds = 600.0;   ///< never ask for less (scheduling granularity, start-up)
  double min_mib = 256.0;
};
/// The constants measured for docs/studies.md §2.2.
CostModel measured_cost_model();

/// What one task asks Slurm for.
struct TaskRequest {
  double seconds = 0.0;  ///< --time, safety factor included
  double mib = 0.0;      ///< --mem, safety factor included
};
/// A run of `cycles` cycles (cycles > 0) or a preparation (cycles == 0) on `grains` grains.
TaskRequest request_for(const CostModel& m, int grains, int steps_per_cycle, int cycles);

/// Slurm's --time text, D-HH:MM:SS rounded up to the minute ("0-01:05:00").
std::string slurm_time(double seconds);

/// The text of a job-array script over `plan_file` (prepare.txt or commands.txt) of `tasks`
/// lines, each task asking `r`. `title`: the job name.
std::string sbatch_text(const Plan& p, const std::string& plan_file, int tasks, const TaskRequest& r, const std::string& title);

/// Writes the scripts listed above for the plan (a phase without tasks gets no script, and
/// submit_slurm.sh then skips it). Throws std::runtime_error naming a file it cannot write.
void write_slurm(const Plan& p, const CostModel& m);

}  // namespace study
