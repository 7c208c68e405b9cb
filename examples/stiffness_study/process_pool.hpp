// examples/stiffness_study/process_pool.hpp — runs a list of commands as separate processes,
// at most `jobs` at a time (posix_spawn + waitpid), each one's stdout and stderr to its own
// log file, a task waiting for another one to succeed first (a run waits for its sample).
// Progress lines: tasks done / total, elapsed time, ETA.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace stiffness {

struct Task {
  enum class Kind { prepare, run };
  Kind kind = Kind::run;
  std::string name;               ///< short label for the progress lines ("k100_s2006")
  std::vector<std::string> argv;  ///< argv[0]: the executable's path
  std::filesystem::path log;      ///< the process's stdout and stderr (its directory is created)
  int after = -1;                 ///< index of a task that must succeed first (-1: none)
  bool reuse = false;             ///< already done by an earlier study: counted as done, not run
};

struct Outcome {
  bool ok = false;
  bool ran = false;     ///< false: reused, or never started (its prerequisite failed, interrupted)
  std::string why;      ///< for a failure: "exit status 1", "killed by signal 9", ...
  double seconds = 0.0; ///< wall time of the process
};

struct PoolOptions {
  int jobs = 1;
  double progress_every = 30.0;  ///< wall seconds between progress lines while nothing finishes
};

/// Runs every task, in list order as far as the prerequisites allow; returns one outcome per
/// task. A failed task is reported (with its log path and the log's last line) and the others
/// go on; the tasks that wait for it are not started. SIGINT or SIGTERM stops the running
/// processes (SIGTERM) and returns early; interrupted() then says so.
std::vector<Outcome> run_all(const std::vector<Task>& tasks, const PoolOptions& opt);

/// True after run_all returned because of SIGINT or SIGTERM.
bool interrupted();

/// The ballast executable the batch drivers run: `given` (their --ballast) if not empty,
/// else next to the running program (the same directory when installed, ../ballast/ballast
/// in the build tree). Throws std::invalid_argument saying how to give it.
std::filesystem::path find_ballast(const std::string& given);

/// Their --ballast-option KEY=VALUE strings as ballast arguments ("--KEY", "VALUE", ...);
/// throws std::invalid_argument on a string that is not KEY=VALUE.
std::vector<std::string> ballast_option_args(const std::vector<std::string>& key_values);


}  // namespace stiffness
