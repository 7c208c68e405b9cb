// examples/study_common/slurm.cpp — job-array scripts and the cost model (see slurm.hpp).
#include "slurm.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace study {
namespace {

void write_script(const fs::path& f, const std::string& text) {
  {
    std::ofstream out(f, std::ios::trunc);
    out << text;
    if (!out.flush()) throw std::runtime_error("cannot write " + f.string());
  }
  fs::permissions(f, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add);
}

}  // namespace

CostModel measured_cost_model() {
  CostModel m;
  // docs/studies.md §2.2 and §5.9: the cycles at issue #36's sweep (ω = 1.3, Anderson 3,
  // projection) cost 1.42 s of processor time a cycle on the full sample in rows of cells,
  // measured on a loaded machine (an overestimate; the strips, now the default, need fewer
  // sweeps): 1.42 / (250 × 724) s per step per grain;
  // preparations 0.037 and 0.057 s per grain on the 181- and 724-grain samples, the larger
  // kept; largest resident memory 18,672 and 24,476 kB, the line through both points.
  m.cycle_seconds_per_step_grain = 7.8e-6;
  m.prepare_seconds_per_grain = 0.057;
  m.memory_mib_base = 16.3;
  m.memory_mib_per_grain = 0.0104;
  return m;
}

TaskRequest request_for(const CostModel& m, int grains, int steps_per_cycle, int cycles) {
  if (grains < 1 || steps_per_cycle < 1 || cycles < 0) throw std::invalid_argument("the cost model needs grains, steps per cycle >= 1 and cycles >= 0");
  const double g = grains;
  const double estimate = cycles > 0 ? double(cycles) * double(steps_per_cycle) * g * m.cycle_seconds_per_step_grain
                                     : g * m.prepare_seconds_per_grain;
  TaskRequest r;
  r.seconds = std::max(m.min_seconds, m.time_safety * estimate);
  r.mib = std::max(m.min_mib, std::ceil(m.memory_safety * (m.memory_mib_base + m.memory_mib_per_grain * g)));
  return r;
}

std::string slurm_time(double seconds) {
  const long long minutes = std::max<long long>(1, static_cast<long long>(std::ceil(seconds / 60.0)));
  char b[64];
  std::snprintf(b, sizeof b, "%lld-%02lld:%02lld:00", minutes / 1440, (minutes / 60) % 24, minutes % 60);
  return b;
}

std::string sbatch_text(const Plan& p, const std::string& plan_file, int tasks, const TaskRequest& r, const std::string& title) {
  const std::string dir = p.dir.string();
  const std::string file = (p.dir / plan_file).string();
  std::string s = "#!/bin/bash\n";
  s += "# " + title + ": one line of " + file + " per array task (written by " + p.study + " --plan-only).\n";
  s += "# Submit everything with " + (p.dir / "submit_slurm.sh").string() + " (the preparations first),\n";
  s += "# then gather with: " + p.study + " --gather " + dir + "\n";
  s += "#SBATCH --job-name=" + title + "\n";
  s += "#SBATCH --array=1-" + std::to_string(tasks) + "\n";
  s += "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=" + std::to_string(std::max(1, p.threads)) + "\n";
  s += "#SBATCH --time=" + slurm_time(r.seconds) + "\n";
  s += "#SBATCH --mem=" + std::to_string(static_cast<long long>(r.mib)) + "M\n";
  s += "#SBATCH --requeue\n#SBATCH --open-mode=append\n";
  s += "#SBATCH --output=" + (p.dir / "slurm" / (title + "_%a.out")).string() + "\n";
  s += "# walltime and memory: the cost model of docs/studies.md (2.2), " + std::to_string(p.grains) + " grains, " +
       std::to_string(p.steps_per_cycle) + " steps per cycle, safety factors included\n";
  s += "set -eu\n";
  s += "export OMP_NUM_THREADS=${SLURM_CPUS_PER_TASK:-1}\n";
  s += "line=$(sed -n \"${SLURM_ARRAY_TASK_ID}p\" " + shell_quote(file) + ")\n";
  s += "if [ -z \"$line\" ]; then echo \"no line $SLURM_ARRAY_TASK_ID in " + file + "\" >&2; exit 2; fi\n";
  s += "echo \"$(date -u +%FT%TZ) task $SLURM_ARRAY_TASK_ID (restart ${SLURM_RESTART_COUNT:-0}) on $(hostname): $line\"\n";
  s += "# a run line carries ballast --continue: after a requeue it resumes from its checkpoint;\n";
  s += "# SIGTERM (time limit, preemption) makes ballast checkpoint at the end of its cycle and exit\n";
  s += "exec bash -c \"$line\"\n";
  return s;
}

void write_slurm(const Plan& p, const CostModel& m) {
  std::error_code ec;
  fs::create_directories(p.dir / "slurm", ec);
  if (ec) throw std::runtime_error("cannot create " + (p.dir / "slurm").string() + ": " + ec.message());
  int max_cycles = 0;
  for (const Job& j : p.runs) max_cycles = std::max(max_cycles, j.cycles);
  const std::string prep_name = p.study + "_prepare", run_name = p.study;
  std::string submit = "#!/bin/sh\n# Submits the study's Slurm job arrays: the preparations, then the runs once they all succeeded.\nset -e\n";
  submit += "cd " + shell_quote(p.dir.string()) + "\n";
  if (!p.prepare.empty()) {
    write_script(p.dir / "slurm_prepare.sbatch",
                 sbatch_text(p, "prepare.txt", int(p.prepare.size()), request_for(m, std::max(1, p.grains), p.steps_per_cycle, 0), prep_name));
    submit += "prep=$(sbatch --parsable slurm_prepare.sbatch)\nprep=${prep%%;*}\necho \"preparations: job $prep\"\n";
  } else {
    fs::remove(p.dir / "slurm_prepare.sbatch", ec);
  }
  if (!p.runs.empty()) {
    write_script(p.dir / "slurm.sbatch",
                 sbatch_text(p, "commands.txt", int(p.runs.size()), request_for(m, std::max(1, p.grains), p.steps_per_cycle, std::max(1, max_cycles)), run_name));
    submit += p.prepare.empty() ? "runs=$(sbatch --parsable slurm.sbatch)\n" : "runs=$(sbatch --parsable --dependency=afterok:$prep slurm.sbatch)\n";
    submit += "echo \"runs: job ${runs%%;*} (squeue -j ${runs%%;*}); when it is done: " + p.study + " --gather " + p.dir.string() + "\"\n";
  } else {
    fs::remove(p.dir / "slurm.sbatch", ec);
  }
  write_script(p.dir / "submit_slurm.sh", submit);
}

}  // namespace study
