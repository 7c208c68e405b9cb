// examples/study_common/local_run.hpp — runs a plan (plan.hpp) on this machine with GNU
// parallel, phase by phase:
//   parallel --joblog DIR/joblog_prepare.txt --resume-failed -j JOBS --termseq ... :::: DIR/prepare.txt
//   parallel --joblog DIR/joblog.txt         --resume-failed -j JOBS --termseq ... :::: DIR/commands.txt
// --resume-failed: run again, it skips the tasks its joblog says succeeded and reruns the
// others (a run resumes from its checkpoint: its line carries ballast --continue). Ctrl-C or
// SIGTERM: GNU parallel sends SIGTERM to the running ballast processes, which checkpoint at the
// end of their cycle (--termseq gives them up to 60 s) and are left out of the joblog, so the
// next invocation runs them again.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace study {

/// The arguments given to GNU parallel for one phase (without the executable).
std::vector<std::string> parallel_args(const std::filesystem::path& dir, const std::string& plan_file, const std::string& joblog, int jobs);

/// How running the plan ended.
enum class LocalResult { finished, interrupted };

/// Runs DIR/prepare.txt then DIR/commands.txt with GNU parallel (`parallel` on PATH),
/// `jobs` at a time; the runs start when every preparation has ended (a run whose sample
/// failed fails at once: check_tasks reports it as not run). Failures are read from the files
/// afterwards (check_tasks), not from parallel's exit status. While a phase runs, a progress
/// line (progress.hpp) on stdout every `progress_every` seconds (0: none), and one at its end.
/// Throws std::runtime_error when GNU parallel cannot be found or started.
LocalResult run_with_parallel(const std::filesystem::path& dir, int jobs, double progress_every = 60.0);

}  // namespace study
