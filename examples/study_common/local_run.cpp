// examples/study_common/local_run.cpp — GNU parallel over the plan files (see local_run.hpp).
#include "local_run.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "progress.hpp"

extern char** environ;

namespace fs = std::filesystem;

namespace study {
namespace {

volatile std::sig_atomic_t g_stop = 0;
volatile pid_t g_child = -1;
void on_signal(int) {
  g_stop = 1;
  if (g_child > 0) kill(g_child, SIGTERM);  // GNU parallel then stops its jobs (SIGTERM each)
}

fs::path find_parallel() {
  const char* path = std::getenv("PATH");
  std::stringstream s(path ? path : "/usr/bin:/bin");
  for (std::string d; std::getline(s, d, ':');) {
    const fs::path p = fs::path(d.empty() ? "." : d) / "parallel";
    if (access(p.c_str(), X_OK) == 0) return p;
  }
  throw std::runtime_error("GNU parallel is not installed (Debian: apt-get install parallel; cmake/install-deps.sh installs it); "
                           "or run the plan another way: --plan-only writes it (docs/studies.md)");
}

// One phase; returns false when interrupted. While GNU parallel runs it, a progress line every
// `progress_every` seconds (0: none) and one at its end.
bool run_phase(const fs::path& parallel, const std::vector<std::string>& args, const PhaseProgress* progress,
               double progress_every) {
  if (g_stop) return false;  // interrupted between the phases
  std::vector<std::string> all{parallel.string()};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  pid_t pid = -1;
  const int err = posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ);
  if (err != 0) throw std::runtime_error("cannot start " + parallel.string() + ": " + std::strerror(err));
  g_child = pid;
  if (g_stop) kill(pid, SIGTERM);
  int status = 0;
  double next_line = progress_every;
  for (;;) {  // poll (a signal only cuts a sleep short), a line when one is due
    const pid_t w = waitpid(pid, &status, WNOHANG);
    if (w == pid || (w < 0 && errno != EINTR)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    if (progress && progress_every > 0 && elapsed() >= next_line) {
      std::printf("%s\n", progress->line(elapsed()).c_str());
      std::fflush(stdout);
      while (next_line <= elapsed()) next_line += progress_every;
    }
  }
  g_child = -1;
  if (progress && !g_stop) {
    std::printf("%s\n", progress->line(elapsed()).c_str());
    std::fflush(stdout);
  }
  return !g_stop;
}

}  // namespace

std::vector<std::string> parallel_args(const fs::path& dir, const std::string& plan_file, const std::string& joblog, int jobs) {
  std::vector<std::string> a{"--joblog", (dir / joblog).string(), "--resume-failed", "-j", std::to_string(jobs),
                             // SIGTERM, then up to 60 s for ballast to end its cycle with a checkpoint
                             "--termseq", "TERM,60000,KILL,25"};
  a.insert(a.end(), {"::::", (dir / plan_file).string()});
  return a;
}

LocalResult run_with_parallel(const fs::path& dir, int jobs, double progress_every) {
  const fs::path parallel = find_parallel();
  struct sigaction sa {}, old_int {}, old_term {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  g_stop = 0;
  sigaction(SIGINT, &sa, &old_int);
  sigaction(SIGTERM, &sa, &old_term);
  bool ok = true;
  try {
    for (const auto& [file, joblog] : {std::pair{"prepare.txt", "joblog_prepare.txt"}, std::pair{"commands.txt", "joblog.txt"}}) {
      std::printf("GNU parallel: %s (%d at a time; joblog %s)\n", (dir / file).c_str(), jobs, (dir / joblog).c_str());
      const bool runs = std::string(file) == "commands.txt";
      std::optional<PhaseProgress> progress;  // none without a readable manifest: the runs go on without lines
      try {
        if (fs::exists(dir / "manifest.csv")) progress.emplace(dir, runs);
      } catch (const std::exception& e) {
        std::printf("(no progress lines: %s)\n", e.what());
      }
      if (!(ok = run_phase(parallel, parallel_args(dir, file, joblog, jobs), progress ? &*progress : nullptr, progress_every)))
        break;
    }
  } catch (...) {
    sigaction(SIGINT, &old_int, nullptr);
    sigaction(SIGTERM, &old_term, nullptr);
    throw;
  }
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  return ok ? LocalResult::finished : LocalResult::interrupted;
}

}  // namespace study
