// examples/study_common/progress.cpp — see progress.hpp.
#include "progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "nscd/shared/progress.hpp"

namespace fs = std::filesystem;

namespace study {

PhaseCount count_phase(const fs::path& dir, const std::vector<ManifestRow>& rows, bool runs) {
  // check_tasks reads a run's preparation from the rows before it: give it every row, count
  // the phase's
  const auto states = check_tasks(dir, rows);
  PhaseCount c;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].is_run() != runs) continue;
    const TaskState& t = states[i].second;
    ++c.tasks;
    c.tasks_done += t.kind == TaskState::ok ? 1 : 0;
    if (runs) {
      const long planned = std::atol(rows[i].at("cycles").c_str());
      c.cycles += planned;
      c.cycles_done += std::min<long>(t.cycles_done, planned);
    }
  }
  return c;
}

double done_share(const PhaseCount& start, const PhaseCount& now, bool runs) {
  const double left = runs ? double(start.cycles - start.cycles_done) : double(start.tasks - start.tasks_done);
  const double done = runs ? double(now.cycles_done - start.cycles_done) : double(now.tasks_done - start.tasks_done);
  if (left <= 0.0) return 1.0;
  return std::clamp(done / left, 0.0, 1.0);
}

double eta_seconds(double elapsed, double share) {
  if (!(share > 0.0) || !std::isfinite(elapsed)) return std::nan("");
  return elapsed * (1.0 - share) / share;
}

std::string progress_text(const PhaseCount& start, const PhaseCount& now, bool runs, double elapsed) {
  using nscd::scenes::format_duration;
  char b[256];
  const double share = done_share(start, now, runs);
  if (runs)
    std::snprintf(b, sizeof b, "runs: %d of %d done, %ld of %ld cycles (%.0f %%), %s", now.tasks_done, now.tasks,
                  now.cycles_done, now.cycles, now.cycles > 0 ? 100.0 * double(now.cycles_done) / double(now.cycles) : 100.0,
                  format_duration(elapsed).c_str());
  else
    std::snprintf(b, sizeof b, "preparations: %d of %d done, %s", now.tasks_done, now.tasks, format_duration(elapsed).c_str());
  std::string s = b;
  if (share >= 1.0) return s;
  const double eta = eta_seconds(elapsed, share);
  if (!std::isfinite(eta)) return s + (runs ? "; no ETA before the first cycle" : "; no ETA before the first is done");
  return s + "; ETA " + format_duration(eta) + " at the mean rate so far";
}

PhaseProgress::PhaseProgress(fs::path dir, bool runs) : dir_(std::move(dir)), runs_(runs) {
  rows_ = read_manifest(dir_);
  start_ = count_phase(dir_, rows_, runs_);
}

std::string PhaseProgress::line(double elapsed) const {
  try {  // a file being written as it is read must not stop the study
    return progress_text(start_, count_phase(dir_, rows_, runs_), runs_, elapsed);
  } catch (const std::exception& e) {
    return std::string(runs_ ? "runs" : "preparations") + ": progress unknown (" + e.what() + ")";
  }
}

}  // namespace study
