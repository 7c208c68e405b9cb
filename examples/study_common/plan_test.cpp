// examples/study_common/plan_test.cpp — the plan files, the manifest and joblog readers and
// the task states (plan.hpp) on hand-made folders: no ballast is run.
#include "plan.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace study;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("nscd_study_common_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string read_all(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

// One preparation, two runs of 3 cycles needing it; the second run's option has a quote, a
// comma and a space (shell and CSV quoting).
Plan two_runs(const fs::path& dir) {
  Plan p;
  p.dir = dir;
  p.study = "test_study";
  p.columns = {"seed", "k_factor"};
  Job prep{"sample_7", {"/bin/ballast", "--prepare-only", "true", "--seed", "7"}, dir / "sample_7", "", 0, {"7", ""}, false};
  Job a{"k1_s7", {"/bin/ballast", "--k-factor", "1"}, dir / "k1_s7", "sample_7", 3, {"7", "1"}, true};
  Job b{"k2_s7", {"/bin/ballast", "--note", "it's a, b"}, dir / "k2_s7", "sample_7", 3, {"7", "2"}, true};
  p.prepare = {prep};
  p.runs = {a, b};
  return p;
}

const TaskState& state(const std::vector<std::pair<std::string, TaskState>>& s, const std::string& name) {
  for (const auto& [n, t] : s)
    if (n == name) return t;
  throw std::runtime_error("no task " + name);
}

}  // namespace

TEST(StudyPlan, ShellQuotingKeepsEveryArgumentWhole) {
  EXPECT_EQ(shell_quote("--k-factor"), "--k-factor");
  EXPECT_EQ(shell_quote("/a/b.nscd"), "/a/b.nscd");
  EXPECT_EQ(shell_quote("a b"), "'a b'");
  EXPECT_EQ(shell_quote("it's"), "'it'\\''s'");
  EXPECT_EQ(shell_quote(""), "''");
}

TEST(StudyPlan, CommandLineCreatesTheFolderAndAppendsToItsLog) {
  const Plan p = two_runs("/d");
  EXPECT_EQ(command_line(p.prepare[0]), "mkdir -p /d/sample_7 && exec /bin/ballast --prepare-only true --seed 7 > /d/sample_7/log.txt 2>&1");
  EXPECT_EQ(command_line(p.runs[0]), "mkdir -p /d/k1_s7 && exec /bin/ballast --k-factor 1 >> /d/k1_s7/log.txt 2>&1");
}

TEST(StudyPlan, FilesHoldOneLinePerTaskAndTheManifestReadsBack) {
  const fs::path d = fresh_dir("files");
  const Plan p = two_runs(d);
  write_plan(p);
  EXPECT_EQ(read_all(d / "prepare.txt"), command_line(p.prepare[0]) + "\n");
  EXPECT_EQ(read_all(d / "commands.txt"), command_line(p.runs[0]) + "\n" + command_line(p.runs[1]) + "\n");
  const std::vector<ManifestRow> rows = read_manifest(d);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].at("phase"), "prepare");
  EXPECT_EQ(rows[0].at("task"), "1");
  EXPECT_EQ(rows[2].at("phase"), "run");
  EXPECT_EQ(rows[2].at("task"), "2");  // the Slurm array task id: its line in commands.txt
  EXPECT_EQ(rows[2].at("k_factor"), "2");
  EXPECT_EQ(rows[2].at("needs"), "sample_7");
  EXPECT_EQ(rows[2].at("command"), command_line(p.runs[1]));  // quotes and commas survive the CSV
  EXPECT_EQ(fs::path(rows[1].at("output")), d / "k1_s7");
  EXPECT_THROW(rows[0].at("no_such_column"), std::runtime_error);
}

TEST(StudyPlan, AChangedPlanFileLosesItsJoblog) {
  const fs::path d = fresh_dir("joblog_reset");
  Plan p = two_runs(d);
  write_plan(p);
  write(d / "joblog.txt", "x\n");
  write(d / "joblog_prepare.txt", "x\n");
  write_plan(p);  // the same plan: the joblogs stay (GNU parallel resumes from them)
  EXPECT_TRUE(fs::exists(d / "joblog.txt"));
  p.runs.pop_back();
  write_plan(p);  // commands.txt changed: its joblog would skip tasks by line number
  EXPECT_FALSE(fs::exists(d / "joblog.txt"));
  EXPECT_TRUE(fs::exists(d / "joblog_prepare.txt"));
}

TEST(StudyPlan, ManifestErrorsNameTheFile) {
  const fs::path d = fresh_dir("bad_manifest");
  EXPECT_THROW(read_manifest(d), std::runtime_error);
  write(d / "manifest.csv", "phase,task,name\nrun,1,x\n");
  try {
    read_manifest(d);
    FAIL() << "a manifest without the output column was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("manifest.csv has no column 'cycles'"), std::string::npos) << e.what();
  }
}

TEST(StudyPlan, JoblogKeepsTheLastEntryOfEachCommand) {
  const fs::path d = fresh_dir("joblog");
  write(d / "j.txt",
        "Seq\tHost\tStarttime\tJobRuntime\tSend\tReceive\tExitval\tSignal\tCommand\n"
        "1\t:\t1.0\t0.1\t0\t0\t0\t0\techo a\n"
        "2\t:\t1.0\t0.1\t0\t0\t1\t0\tfalse x\n"
        "3\t:\t1.0\t0.1\t0\t0\t0\t15\techo c\n"
        "2\t:\t2.0\t0.1\t0\t0\t0\t0\tfalse x\n"
        "4\t:\t2.0");  // cut short
  const auto m = read_joblog(d / "j.txt");
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m.at("false x").exit_value, 0);  // rerun by --resume-failed, then succeeded
  EXPECT_EQ(m.at("echo c").signal, 15);
  EXPECT_TRUE(read_joblog(d / "none.txt").empty());
}

TEST(StudyPlan, TaskStatesComeFromTheFilesAndTheJoblogs) {
  const fs::path d = fresh_dir("states");
  const Plan p = two_runs(d);
  write_plan(p);
  // nothing ran: the sample missing, its runs not run
  auto s = check_tasks(d, read_manifest(d));
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(state(s, "sample_7").kind, TaskState::missing);
  EXPECT_EQ(state(s, "k1_s7").kind, TaskState::not_run);
  EXPECT_EQ(state(s, "k1_s7").why, "not run: sample_7 not done");
  // the sample there, the runs not started: missing
  write(d / "sample_7/sample.nscd", "x");
  EXPECT_EQ(state(check_tasks(d, read_manifest(d)), "k1_s7").kind, TaskState::missing);
  // the sample, one run finished, one stopped after a cycle (its last row cut short)
  write(d / "sample_7/sample.nscd", "x");
  const std::string header = "cycle,time,settlement_min_load\n";
  write(d / "k1_s7/cycles.csv", header + "1,0.05,1e-4\n2,0.1,2e-4\n3,0.15,3e-4\n");
  write(d / "k1_s7/summary.txt", "result = valid\ncycles = 3\n");
  write(d / "k2_s7/cycles.csv", header + "1,0.05,1e-4\n2,0.1");
  s = check_tasks(d, read_manifest(d));
  EXPECT_EQ(state(s, "sample_7").kind, TaskState::ok);
  EXPECT_EQ(state(s, "k1_s7").kind, TaskState::ok);
  EXPECT_EQ(state(s, "k2_s7").kind, TaskState::unfinished);
  EXPECT_EQ(state(s, "k2_s7").cycles_done, 1);
  EXPECT_EQ(state(s, "k2_s7").why, "1 of 3 cycles");
  // GNU parallel says the second run exited 1: failed, whatever its files
  write(d / "joblog.txt", "Seq\tHost\tStarttime\tJobRuntime\tSend\tReceive\tExitval\tSignal\tCommand\n2\t:\t1\t1\t0\t0\t1\t0\t" +
                              command_line(p.runs[1]) + "\n");
  s = check_tasks(d, read_manifest(d));
  EXPECT_EQ(state(s, "k2_s7").kind, TaskState::failed);
  EXPECT_EQ(state(s, "k2_s7").why, "exit status 1 after 1 cycles");
  // an impossible result is a failure even with every cycle
  write(d / "k1_s7/summary.txt", "result = impossible: cycle 3: ...\ncycles = 3\n");
  EXPECT_EQ(state(check_tasks(d, read_manifest(d)), "k1_s7").kind, TaskState::failed);
  // a failed preparation: its runs without cycles are "not run"
  fs::remove(d / "sample_7/sample.nscd");
  fs::remove_all(d / "k1_s7");
  write(d / "joblog_prepare.txt", "Seq\tHost\tStarttime\tJobRuntime\tSend\tReceive\tExitval\tSignal\tCommand\n1\t:\t1\t1\t0\t0\t2\t0\t" +
                                      command_line(p.prepare[0]) + "\n");
  s = check_tasks(d, read_manifest(d));
  EXPECT_EQ(state(s, "sample_7").kind, TaskState::failed);
  EXPECT_EQ(state(s, "sample_7").why, "exit status 2");
  EXPECT_EQ(state(s, "k1_s7").kind, TaskState::not_run);
  EXPECT_EQ(state(s, "k1_s7").why, "not run: sample_7 failed");
  EXPECT_EQ(report_tasks(s), 3);
}
