// examples/study_common/plan.hpp — a batch study as plan files that existing engines run
// (issue #11): every ballast command of the study, one a line, in two phases —
//   DIR/prepare.txt   the sample preparations (`ballast --prepare-only ...`), one a line
//   DIR/commands.txt  the runs (`ballast --sample ... --continue ...`), one a line; a run needs
//                     its sample, so prepare.txt must be done first
//   DIR/manifest.csv  one row per line of both files: phase,task,name,<study columns>,cycles,
//                     needs,output,command (task: the line number in the phase's file, i.e.
//                     the Slurm array task id; needs: the preparation a run waits for)
// GNU parallel runs a file as it is (`parallel --joblog J --resume-failed :::: FILE`), a Slurm
// job array runs line $SLURM_ARRAY_TASK_ID (slurm.hpp). Each line creates its output folder
// and appends its stdout and stderr to log.txt there. The gathering (check_tasks) reads the
// manifest back, whatever ran it, and tells each task's state from its files (and the joblogs
// of GNU parallel when they are there).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace study {

struct Job {
  std::string name;                  ///< unique in the plan: "sample_2006", "k100_s2006"
  std::vector<std::string> argv;     ///< argv[0]: the ballast executable
  std::filesystem::path folder;      ///< the output folder (absolute); log.txt goes in it
  std::string needs;                 ///< the name of the preparation it needs ("" for none)
  int cycles = 0;                    ///< cycles the run must reach (0: a preparation)
  std::vector<std::string> values;   ///< the study's manifest columns (Plan::columns)
  bool append_log = false;           ///< >> log.txt (a run that may be resumed) instead of >
};

struct Plan {
  std::filesystem::path dir;         ///< the study directory (absolute)
  std::string study;                 ///< the driver's name: "stiffness_study" (Slurm job name)
  std::vector<std::string> columns;  ///< the study's manifest columns, e.g. {"seed", "k_factor"}
  std::vector<Job> prepare, runs;    ///< the two phases (a phase may be empty)
  int grains = 0;                    ///< grains of a sample, for the cost model (slurm.hpp)
  int steps_per_cycle = 250;         ///< 1/(f dt), for the cost model
  int threads = 1;                   ///< threads of each ballast run (Slurm's --cpus-per-task)
};

/// `s` quoted for a POSIX shell when it needs it ('...' with ' written '\'').
std::string shell_quote(const std::string& s);
/// The job's line in the plan: mkdir -p F && exec ARGV > F/log.txt 2>&1 (>> when append_log).
std::string command_line(const Job& j);

/// Writes DIR/prepare.txt, DIR/commands.txt and DIR/manifest.csv (creates DIR); a plan file
/// that changes loses its joblog (GNU parallel's --resume-failed matches jobs by line number).
/// Throws std::runtime_error naming the file it cannot write.
void write_plan(const Plan& p);

/// One row of manifest.csv, by column name.
struct ManifestRow {
  std::map<std::string, std::string> cell;
  const std::string& at(const std::string& column) const;  ///< throws naming the column
  bool is_run() const { return at("phase") == "run"; }
};
/// Reads DIR/manifest.csv (RFC 4180 quoting). Throws std::runtime_error naming the file and the
/// line on a missing file, a missing column or a row with too few cells.
std::vector<ManifestRow> read_manifest(const std::filesystem::path& dir);

/// GNU parallel's --joblog: the last entry of each command (a command rerun by --resume-failed
/// has several). A missing file is an empty map.
struct JoblogEntry {
  int exit_value = 0;
  int signal = 0;
};
std::map<std::string, JoblogEntry> read_joblog(const std::filesystem::path& file);

/// What a task of the manifest left behind.
struct TaskState {
  enum Kind { ok, failed, missing, unfinished, not_run } kind = missing;
  std::string why;                ///< for every kind but ok: one line
  std::filesystem::path log;      ///< its log.txt
  int cycles_done = 0;            ///< rows of its cycles.csv (runs)
};
const char* kind_name(TaskState::Kind k);  ///< "ok", "FAILED", "MISSING", "UNFINISHED", "NOT RUN"

/// The state of every task of the manifest, by name, in the manifest's order: a preparation is
/// ok with its sample.nscd; a run is ok when its cycles.csv has its planned cycles and its
/// summary.txt says "result = valid". A nonzero exit in the joblogs (DIR/joblog_prepare.txt,
/// DIR/joblog.txt), a summary with another result, or a failed preparation (for its runs) is
/// a failure; no output is missing; fewer cycles is unfinished.
std::vector<std::pair<std::string, TaskState>> check_tasks(const std::filesystem::path& dir, const std::vector<ManifestRow>& rows);

/// Prints one line per task that is not ok (with its log and the log's last line) and a count;
/// returns the number of tasks not ok.
int report_tasks(const std::vector<std::pair<std::string, TaskState>>& states);

/// One CSV record (RFC 4180: "..." with "" for a quote; no line breaks inside a field).
std::vector<std::string> csv_cells(const std::string& line);

}  // namespace study
