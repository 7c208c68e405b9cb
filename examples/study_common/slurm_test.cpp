// examples/study_common/slurm_test.cpp — the Slurm job-array scripts (slurm.hpp) checked by
// their content (no Slurm here: `sbatch --test-only` cannot run), and the cost model's arithmetic.
#include "slurm.hpp"

#include "ballast_args.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <thread>

namespace fs = std::filesystem;
using namespace study;

namespace {

std::string read_script(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

Plan plan_in(const fs::path& dir, int runs) {
  Plan p;
  p.dir = dir;
  p.study = "stiffness_study";
  p.grains = 724;
  p.steps_per_cycle = 250;
  p.prepare.push_back(Job{"sample_1", {"/b/ballast", "--prepare-only", "true"}, dir / "sample_1", "", 0, {}, false});
  for (int i = 0; i < runs; ++i)
    p.runs.push_back(Job{"r" + std::to_string(i), {"/b/ballast", "--continue"}, dir / ("r" + std::to_string(i)), "sample_1", 3000, {}, true});
  return p;
}

}  // namespace

TEST(Slurm, TimeIsRoundedUpToTheMinute) {
  EXPECT_EQ(slurm_time(1), "0-00:01:00");
  EXPECT_EQ(slurm_time(60), "0-00:01:00");
  EXPECT_EQ(slurm_time(61), "0-00:02:00");
  EXPECT_EQ(slurm_time(3600 * 25 + 30), "1-01:01:00");
}

TEST(Slurm, RequestIsTheModelTimesTheSafetyFactor) {
  CostModel m;
  m.cycle_seconds_per_step_grain = 1e-6;
  m.prepare_seconds_per_grain = 0.5;
  m.memory_mib_base = 100;
  m.memory_mib_per_grain = 0.5;
  m.time_safety = 3;
  m.memory_safety = 2;
  // 3000 cycles x 250 steps x 1000 grains x 1e-6 s = 750 s, x 3
  const TaskRequest r = request_for(m, 1000, 250, 3000);
  EXPECT_DOUBLE_EQ(r.seconds, 2250.0);
  EXPECT_DOUBLE_EQ(r.mib, 2 * (100 + 500.0));
  EXPECT_DOUBLE_EQ(request_for(m, 1000, 250, 0).seconds, 1500.0);  // a preparation: 0.5 s per grain x 3
  EXPECT_DOUBLE_EQ(request_for(m, 10, 250, 1).seconds, m.min_seconds);
  EXPECT_THROW(request_for(m, 0, 250, 1), std::invalid_argument);
}

TEST(Slurm, MeasuredModelIsFilledIn) {
  const CostModel m = measured_cost_model();
  EXPECT_GT(m.cycle_seconds_per_step_grain, 0.0);
  EXPECT_GT(m.prepare_seconds_per_grain, 0.0);
  EXPECT_GT(m.memory_mib_base + m.memory_mib_per_grain, 0.0);
  EXPECT_GE(m.time_safety, 1.0);
  EXPECT_GE(m.memory_safety, 1.0);
}

TEST(Slurm, RunArrayReadsItsLineAndIsRequeuedWithAppend) {
  const fs::path d = fs::temp_directory_path() / "nscd_study_common_slurm";
  fs::remove_all(d);
  const Plan p = plan_in(d, 24);
  write_slurm(p, measured_cost_model());
  const std::string s = read_script(d / "slurm.sbatch");
  EXPECT_EQ(s.rfind("#!/bin/bash\n", 0), 0u);
  EXPECT_TRUE(has(s, "\n#SBATCH --array=1-24\n")) << s;
  EXPECT_TRUE(has(s, "\n#SBATCH --requeue\n"));
  EXPECT_TRUE(has(s, "\n#SBATCH --open-mode=append\n"));
  EXPECT_TRUE(has(s, "\n#SBATCH --ntasks=1\n"));
  EXPECT_TRUE(has(s, "\n#SBATCH --output=" + (d / "slurm" / "stiffness_study_%a.out").string() + "\n"));
  const TaskRequest r = request_for(measured_cost_model(), 724, 250, 3000);
  EXPECT_TRUE(has(s, "\n#SBATCH --time=" + slurm_time(r.seconds) + "\n")) << s;
  EXPECT_TRUE(has(s, "\n#SBATCH --mem=" + std::to_string(static_cast<long long>(r.mib)) + "M\n")) << s;
  EXPECT_TRUE(has(s, "line=$(sed -n \"${SLURM_ARRAY_TASK_ID}p\" " + (d / "commands.txt").string() + ")\n")) << s;
  EXPECT_TRUE(has(s, "\nexec bash -c \"$line\"\n"));
  EXPECT_TRUE(fs::is_directory(d / "slurm"));  // Slurm does not create the output folder
  // every #SBATCH line comes before the first command (sbatch stops reading them there)
  const auto last_directive = s.rfind("#SBATCH"), first_command = s.find("\nset -eu\n");
  EXPECT_LT(last_directive, first_command);
  // the preparations: their own array, over prepare.txt
  const std::string prep = read_script(d / "slurm_prepare.sbatch");
  EXPECT_TRUE(has(prep, "\n#SBATCH --array=1-1\n"));
  EXPECT_TRUE(has(prep, (d / "prepare.txt").string()));
  // the submission: the runs wait for every preparation to succeed
  const std::string submit = read_script(d / "submit_slurm.sh");
  EXPECT_TRUE(has(submit, "prep=$(sbatch --parsable slurm_prepare.sbatch)"));
  EXPECT_TRUE(has(submit, "sbatch --parsable --dependency=afterok:$prep slurm.sbatch"));
  EXPECT_TRUE(fs::status(d / "slurm.sbatch").permissions() != fs::perms::none);
}

TEST(Slurm, NoPreparationsNoPrepareArray) {
  const fs::path d = fs::temp_directory_path() / "nscd_study_common_slurm_noprep";
  fs::remove_all(d);
  Plan p = plan_in(d, 2);
  p.prepare.clear();
  write_slurm(p, measured_cost_model());
  EXPECT_FALSE(fs::exists(d / "slurm_prepare.sbatch"));
  const std::string submit = read_script(d / "submit_slurm.sh");
  EXPECT_FALSE(has(submit, "dependency"));
  EXPECT_TRUE(has(submit, "runs=$(sbatch --parsable slurm.sbatch)"));
}

TEST(Slurm, ARunOnThreadsAsksForItsCores) {
  const fs::path d = fs::temp_directory_path() / "nscd_study_common_slurm_threads";
  fs::remove_all(d);
  Plan p = plan_in(d, 2);
  EXPECT_TRUE(has((write_slurm(p, measured_cost_model()), read_script(d / "slurm.sbatch")), "\n#SBATCH --cpus-per-task=1\n"));
  p.threads = 4;
  write_slurm(p, measured_cost_model());
  EXPECT_TRUE(has(read_script(d / "slurm.sbatch"), "\n#SBATCH --cpus-per-task=4\n"));
  EXPECT_TRUE(has(read_script(d / "slurm.sbatch"), "export OMP_NUM_THREADS=${SLURM_CPUS_PER_TASK:-1}"));
}

TEST(SplitMachine, ThreadsGoToEveryRunAndJobsTimesThreadsStayWithinTheCores) {
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (cores < 2) GTEST_SKIP() << "one core: no room for threads";
  std::vector<std::string> args{"--dt", "1e-4"};
  int jobs = 0;
  split_machine(jobs, false, 1, true, args);  // one thread: the cores are the jobs, no --threads
  EXPECT_EQ(jobs, cores);
  EXPECT_EQ(args, (std::vector<std::string>{"--dt", "1e-4"}));
  split_machine(jobs, false, cores, true, args);  // all the cores to one run's threads
  EXPECT_EQ(jobs, 1);
  EXPECT_EQ(args, (std::vector<std::string>{"--dt", "1e-4", "--threads", std::to_string(cores)}));
  std::vector<std::string> more;
  jobs = 2;
  EXPECT_THROW(split_machine(jobs, true, cores, true, more), std::invalid_argument);  // 2 x cores threads here
  EXPECT_NO_THROW(split_machine(jobs, true, cores, false, more));                   // a plan for other hosts
  std::vector<std::string> twice{"--threads", "2"};
  EXPECT_THROW(split_machine(jobs, true, 1, false, twice), std::invalid_argument);  // --ballast-option threads=2
  EXPECT_THROW(split_machine(jobs, true, 0, false, more), std::invalid_argument);
}
