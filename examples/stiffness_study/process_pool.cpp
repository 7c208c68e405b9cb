// examples/stiffness_study/process_pool.cpp — the process pool of the stiffness study (see
// process_pool.hpp). Children are started with posix_spawn (stdin from /dev/null, stdout and
// stderr to the task's log) and reaped with waitpid(pid, WNOHANG) in a 0.1 s polling loop,
// which also prints the progress lines.
#include "process_pool.hpp"

#include "nscd/shared/progress.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace fs = std::filesystem;

namespace stiffness {
namespace {

using Clock = std::chrono::steady_clock;
volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The last line of a log (its last 4 kB), or "" — shown when a task fails.
std::string tail_text(const std::filesystem::path& log, std::size_t bytes = 4096) {
  std::ifstream in(log, std::ios::binary);
  if (!in) return "";
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  const std::streamoff from = std::max<std::streamoff>(0, size - static_cast<std::streamoff>(bytes));
  in.seekg(from);
  std::string s(static_cast<std::size_t>(size - from), '\0');
  in.read(s.data(), static_cast<std::streamsize>(s.size()));
  return s;
}

std::string last_line(const std::filesystem::path& log) {
  std::string s = tail_text(log);
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  const auto nl = s.find_last_of('\n');
  return nl == std::string::npos ? s : s.substr(nl + 1);
}

// How far a ballast run is, from its last progress line
//   "cycle   12/30  settlement ...  0.47 s/cycle  ETA 8.5s"
// (none yet: nullopt; the preparation prints no such line). The line may be up to ballast's
// --progress-every old: the time since the log was last written is taken off the remainder.
struct Progress {
  double fraction = 0.0;   ///< cycles done / cycles
  double remaining = 0.0;  ///< wall seconds left, estimated
};
std::optional<Progress> log_progress(const std::filesystem::path& log) {
  const std::string s = tail_text(log);
  const auto at = s.rfind("\ncycle ");
  if (at == std::string::npos) return std::nullopt;
  const std::string line = s.substr(at + 1, s.find('\n', at + 1) - at - 1);
  int done = 0, total = 0;
  if (std::sscanf(line.c_str() + 6, " %d/%d", &done, &total) != 2 || total <= 0 || done <= 0) return std::nullopt;
  Progress p;
  p.fraction = std::min(1.0, double(done) / double(total));
  const auto unit = line.find(" s/cycle");
  const auto from = unit == std::string::npos ? std::string::npos : line.rfind(' ', unit - 1);
  const double per = from == std::string::npos ? NAN : std::strtod(line.c_str() + from + 1, nullptr);
  std::error_code ec;
  const auto written = std::filesystem::last_write_time(log, ec);
  const double age = ec ? 0.0 : std::chrono::duration<double>(std::filesystem::file_time_type::clock::now() - written).count();
  p.remaining = std::isnan(per) ? NAN : std::max(0.0, per * double(total - done) - std::max(0.0, age));
  return p;
}

// Starts one task; returns its pid, or -1 with `why` set.
pid_t spawn(const Task& t, std::string& why) {
  std::error_code ec;
  std::filesystem::create_directories(t.log.parent_path(), ec);
  std::vector<char*> argv;
  for (const std::string& a : t.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, t.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = -1;
  const int err = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (err != 0) {
    why = std::string("cannot start ") + argv[0] + ": " + std::strerror(err);
    return -1;
  }
  return pid;
}

std::string status_text(int status) {
  if (WIFEXITED(status)) return "exit status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return std::string("killed by signal ") + std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) + ")";
  return "stopped (status " + std::to_string(status) + ")";
}

enum class State { pending, running, done };

struct Slot {
  State state = State::pending;
  pid_t pid = -1;
  Clock::time_point start;
};

}  // namespace

bool interrupted() { return g_stop != 0; }

std::vector<Outcome> run_all(const std::vector<Task>& tasks, const PoolOptions& opt) {
  const std::size_t n = tasks.size();
  std::vector<Outcome> out(n);
  std::vector<Slot> slot(n);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  const auto t0 = Clock::now();
  auto last_line_at = Clock::now();
  std::size_t finished = 0;
  int running = 0;

  // ETA: the remaining wall time of every unfinished task, shared by the parallel slots. A
  // running ballast run tells its own from its progress line; otherwise a task is expected to
  // last as long as the finished ones of its kind, else as the running ones of its kind
  // project, else unknown ("?").
  const auto eta = [&]() -> double {
    double sum[2] = {0, 0}, proj[2] = {0, 0};
    int cnt[2] = {0, 0}, pcnt[2] = {0, 0};
    std::vector<std::optional<Progress>> prog(n);
    for (std::size_t i = 0; i < n; ++i) {
      const int k = tasks[i].kind == Task::Kind::run;
      if (slot[i].state == State::done && out[i].ran && out[i].ok) sum[k] += out[i].seconds, ++cnt[k];
      if (slot[i].state == State::running && (prog[i] = log_progress(tasks[i].log)) && std::isfinite(prog[i]->remaining))
        proj[k] += since(slot[i].start) + prog[i]->remaining, ++pcnt[k];
    }
    const auto total = [&](int k) { return cnt[k] ? sum[k] / cnt[k] : pcnt[k] ? proj[k] / pcnt[k] : NAN; };
    double work = 0.0;
    std::size_t left = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (slot[i].state == State::done) continue;
      ++left;
      const int k = tasks[i].kind == Task::Kind::run;
      if (slot[i].state == State::pending) work += total(k);
      else if (prog[i] && std::isfinite(prog[i]->remaining)) work += prog[i]->remaining;
      else if (std::isnan(total(k))) work = NAN;
      else work += std::max(0.0, total(k) - since(slot[i].start));
    }
    return left ? work / double(std::min<std::size_t>(left, std::size_t(opt.jobs))) : 0.0;
  };
  const auto finish = [&](std::size_t i, bool ok, bool ran, const std::string& why) {
    slot[i].state = State::done;
    out[i].ok = ok;
    out[i].ran = ran;
    out[i].why = why;
    if (ran) out[i].seconds = since(slot[i].start);
    ++finished;
    last_line_at = Clock::now();
    const char* tag = ok ? (ran ? "ok    " : "reused") : "FAILED";
    std::printf("[%3zu/%zu] %s %-16s", finished, n, tag, tasks[i].name.c_str());
    if (ran) std::printf(" %8s", nscd::scenes::format_duration(out[i].seconds).c_str());
    std::printf("   elapsed %s  ETA %s\n", nscd::scenes::format_duration(since(t0)).c_str(), nscd::scenes::format_duration(eta()).c_str());
    if (!ok) {
      std::printf("          %s; log: %s\n", why.c_str(), tasks[i].log.string().c_str());
      if (ran) std::printf("          last log line: %s\n", last_line(tasks[i].log).c_str());
    }
    std::fflush(stdout);
  };

  while (finished < n && !g_stop) {
    // Start what can start: prerequisites succeeded, a free slot.
    for (std::size_t i = 0; i < n; ++i) {
      if (slot[i].state != State::pending) continue;
      const int a = tasks[i].after;
      if (a >= 0 && slot[a].state != State::done) continue;
      if (a >= 0 && !out[a].ok) {
        finish(i, false, false, "not run: " + tasks[a].name + " failed");
        continue;
      }
      if (tasks[i].reuse) {
        finish(i, true, false, "");
        continue;
      }
      if (running >= opt.jobs) continue;
      std::string why;
      slot[i].start = Clock::now();
      slot[i].pid = spawn(tasks[i], why);
      if (slot[i].pid < 0) {
        finish(i, false, false, why);
        continue;
      }
      slot[i].state = State::running;
      ++running;
    }
    // Reap what ended.
    bool any = false;
    for (std::size_t i = 0; i < n; ++i) {
      if (slot[i].state != State::running) continue;
      int status = 0;
      const pid_t r = waitpid(slot[i].pid, &status, WNOHANG);
      if (r == 0 || (r < 0 && errno == EINTR)) continue;
      --running;
      any = true;
      const bool ok = r == slot[i].pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
      finish(i, ok, true, r < 0 ? std::string("waitpid: ") + std::strerror(errno) : ok ? "" : status_text(status));
    }
    if (any) continue;
    if (since(last_line_at) >= opt.progress_every) {
      last_line_at = Clock::now();
      std::printf("  %zu/%zu done, running:", finished, n);
      for (std::size_t i = 0; i < n; ++i) {
        if (slot[i].state != State::running) continue;
        const auto p = log_progress(tasks[i].log);
        std::printf(" %s", tasks[i].name.c_str());
        if (p) std::printf(" (%.0f%%)", 100 * p->fraction);
        else if (tasks[i].kind == Task::Kind::prepare) std::printf(" (preparing)");
      }
      std::printf(";  elapsed %s  ETA %s\n", nscd::scenes::format_duration(since(t0)).c_str(), nscd::scenes::format_duration(eta()).c_str());
      std::fflush(stdout);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }

  if (g_stop) {  // interrupted: stop the children, mark what never ran
    for (std::size_t i = 0; i < n; ++i) {
      if (slot[i].state == State::running) {
        kill(slot[i].pid, SIGTERM);
        int status = 0;
        waitpid(slot[i].pid, &status, 0);
        out[i].ran = true;
        out[i].seconds = since(slot[i].start);
      }
      if (slot[i].state != State::done) out[i].why = "interrupted";
    }
    std::printf("interrupted: %zu of %zu tasks finished; the running ones were stopped\n", finished, n);
  }
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  return out;
}

fs::path find_ballast(const std::string& given) {
  const auto usable = [](const fs::path& p) { return fs::is_regular_file(p) && access(p.c_str(), X_OK) == 0; };
  if (!given.empty()) {
    if (!usable(given)) throw std::invalid_argument("--ballast '" + given + "' is not an executable file");
    return fs::absolute(given);
  }
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec)
    for (const fs::path& p : {self.parent_path() / "ballast", self.parent_path().parent_path() / "ballast" / "ballast"})
      if (usable(p)) return p;
  throw std::invalid_argument("cannot find the ballast executable next to " + (ec ? std::string("this program") : self.string()) +
                              "; build it (--target ballast) or give --ballast PATH");
}

std::vector<std::string> ballast_option_args(const std::vector<std::string>& key_values) {
  std::vector<std::string> args;
  for (const std::string& kv : key_values) {
    const auto eq = kv.find('=');
    if (eq == 0 || eq == std::string::npos || kv.find(' ') < eq)
      throw std::invalid_argument("--ballast-option '" + kv + "' is not KEY=VALUE");
    args.insert(args.end(), {"--" + kv.substr(0, eq), kv.substr(eq + 1)});
  }
  return args;
}

}  // namespace stiffness
