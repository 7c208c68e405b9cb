// examples/study_common/progress_test.cpp — the progress lines of a running plan (progress.hpp):
// the counts, the share and the ETA on hand-made folders, and the lines run_with_parallel
// prints while GNU parallel runs a small plan of shell commands (no ballast).
#include "progress.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "local_run.hpp"

namespace fs = std::filesystem;
using namespace study;

namespace {

fs::path fresh_progress_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("nscd_study_progress_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write_progress_file(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

// One preparation, then two runs of `cycles` cycles each, every task a shell command: the
// preparation writes the sample, a run writes a cycles.csv row every `pause` seconds and a
// valid summary at the end (what check_tasks reads of a ballast run).
Plan shell_plan(const fs::path& dir, int cycles, double pause) {
  Plan p;
  p.dir = dir;
  p.study = "test_study";
  p.columns = {"seed"};
  const fs::path sample = dir / "sample_1";
  p.prepare = {Job{"sample_1", {"/bin/sh", "-c", "echo x > " + (sample / "sample.nscd").string()}, sample, "", 0, {"1"}, false}};
  for (const char* name : {"a", "b"}) {
    const fs::path f = dir / name;
    const std::string csv = (f / "cycles.csv").string();
    const std::string script = "printf 'cycle\\n' > " + csv + "; i=0; while [ $i -lt " + std::to_string(cycles) + " ]; do sleep " +
                               std::to_string(pause) + "; i=$((i+1)); echo $i >> " + csv + "; done; echo 'result = valid' > " +
                               (f / "summary.txt").string();
    p.runs.push_back(Job{name, {"/bin/sh", "-c", script}, f, "sample_1", cycles, {"1"}, true});
  }
  return p;
}

bool has_parallel() { return std::system("command -v parallel >/dev/null 2>&1") == 0; }

}  // namespace

TEST(StudyProgress, CountsTheCyclesAndTasksOfAPhase) {
  const fs::path d = fresh_progress_dir("counts");
  write_plan(shell_plan(d, 4, 0.0));
  const auto rows = read_manifest(d);
  // nothing done
  PhaseCount runs0 = count_phase(d, rows, true), prep0 = count_phase(d, rows, false);
  EXPECT_EQ(prep0.tasks, 1);
  EXPECT_EQ(prep0.tasks_done, 0);
  EXPECT_EQ(runs0.tasks, 2);
  EXPECT_EQ(runs0.cycles, 8);
  EXPECT_EQ(runs0.cycles_done, 0);
  EXPECT_EQ(done_share(runs0, runs0, true), 0.0);
  EXPECT_TRUE(std::isnan(eta_seconds(30.0, 0.0)));
  EXPECT_NE(progress_text(runs0, runs0, true, 30.0).find("runs: 0 of 2 done, 0 of 8 cycles (0 %), 30.0s; no ETA before the first cycle"),
            std::string::npos)
      << progress_text(runs0, runs0, true, 30.0);
  // the sample, run a finished (4 cycles), run b at 1 of 4 (its second row cut short)
  write_progress_file(d / "sample_1/sample.nscd", "x");
  write_progress_file(d / "a/cycles.csv", "cycle\n1\n2\n3\n4\n");
  write_progress_file(d / "a/summary.txt", "result = valid\n");
  write_progress_file(d / "b/cycles.csv", "cycle\n1\n2");
  const PhaseCount runs1 = count_phase(d, rows, true);
  EXPECT_EQ(count_phase(d, rows, false).tasks_done, 1);
  EXPECT_EQ(runs1.tasks_done, 1);
  EXPECT_EQ(runs1.cycles_done, 5);
  EXPECT_DOUBLE_EQ(done_share(runs0, runs1, true), 5.0 / 8.0);
  // 5 of 8 cycles in 100 s: 3 left at 20 s each
  EXPECT_DOUBLE_EQ(eta_seconds(100.0, done_share(runs0, runs1, true)), 60.0);
  EXPECT_NE(progress_text(runs0, runs1, true, 100.0).find("runs: 1 of 2 done, 5 of 8 cycles (62 %), 1m40s; ETA 1m00s at the mean rate so far"),
            std::string::npos)
      << progress_text(runs0, runs1, true, 100.0);
  // a phase resumed: the share counts from what was left when it started
  EXPECT_DOUBLE_EQ(done_share(runs1, runs1, true), 0.0);
  PhaseCount all = runs1;
  all.cycles_done = 8;
  all.tasks_done = 2;
  EXPECT_DOUBLE_EQ(done_share(runs1, all, true), 1.0);
  EXPECT_EQ(progress_text(runs1, all, true, 10.0), "runs: 2 of 2 done, 8 of 8 cycles (100 %), 10.0s");  // done: no ETA
  // nothing left at the start: done
  EXPECT_DOUBLE_EQ(done_share(all, all, true), 1.0);
}

TEST(StudyProgress, LinesWhileGnuParallelRunsThePlan) {
  if (!has_parallel()) GTEST_SKIP() << "GNU parallel is not installed";
  const fs::path d = fresh_progress_dir("parallel");
  write_plan(shell_plan(d, 3, 0.5));  // each run lasts >= 1.5 s
  testing::internal::CaptureStdout();
  const LocalResult r = run_with_parallel(d, 2, 0.25);
  const std::string out = testing::internal::GetCapturedStdout();
  EXPECT_EQ(r, LocalResult::finished);
  EXPECT_NE(out.find("preparations: 1 of 1 done"), std::string::npos) << out;
  const std::size_t last = out.find("runs: 2 of 2 done, 6 of 6 cycles (100 %)");
  ASSERT_NE(last, std::string::npos) << out;
  // at least one line while the runs ran (every 0.25 s over >= 1.5 s), before the last
  const std::size_t first = out.find("runs: ");
  EXPECT_LT(first, last) << out;
  EXPECT_NE(out.find(" of 6 cycles ("), std::string::npos);
}
