// tests/ballast/test_ballast_resume.cpp — a run stopped and resumed from its checkpoint ends
// bit for bit where the same run done in one go ends: cycles.csv and steps.csv (all but the
// wall-clock columns) as text, the final checkpoints' registries as bits. Also after a kill
// that left rows (and a half-written row) beyond the checkpoint, after SIGTERM (a checkpoint at
// the end of the cycle), and through --continue (the batch studies' command lines).
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <thread>

#include "ballast_test_support.hpp"
#include "nscd/io/checkpoint.hpp"

using namespace ballast_test;

namespace {

constexpr int kCycles = 6;  // N of the uninterrupted run

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

// Complete rows of a CSV file being written (no gtest assertion: called from another thread).
int read_csv_rows(const fs::path& file) {
  std::ifstream in(file);
  int n = -1;
  for (std::string line; std::getline(in, line);)
    if (!in.eof()) ++n;
  return n;
}

ballast::Config resumable(const fs::path& out) {
  ballast::Config c = tiny_config(out, kCycles);
  c.checkpoint_every = 2;
  return c;
}

/// The final checkpoints of two runs hold the same state, bit for bit (the "output" option
/// names each run's own directory and is the one allowed difference).
void expect_same_checkpoint(const fs::path& a_file, const fs::path& b_file) {
  const nscd::Checkpoint a = nscd::load_checkpoint(a_file);
  const nscd::Checkpoint b = nscd::load_checkpoint(b_file);
  EXPECT_EQ(bits(a.reg.time), bits(b.reg.time));
  EXPECT_EQ(a.reg.step, b.reg.step);
  const nscd::BodyTable& ba = a.reg.bodies;
  const nscd::BodyTable& bb = b.reg.bodies;
  ASSERT_EQ(ba.size(), bb.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < ba.size(); ++i) {
    const bool same = bits(ba.x[i]) == bits(bb.x[i]) && bits(ba.y[i]) == bits(bb.y[i]) &&
                      bits(ba.angle[i]) == bits(bb.angle[i]) && bits(ba.vx[i]) == bits(bb.vx[i]) &&
                      bits(ba.vy[i]) == bits(bb.vy[i]) && bits(ba.spin[i]) == bits(bb.spin[i]);
    if (!same && differing++ < 5)
      ADD_FAILURE() << "body " << i << " (" << ba.name[i] << "): y " << ba.y[i] << " vs " << bb.y[i] << ", vy " << ba.vy[i]
                    << " vs " << bb.vy[i];
  }
  EXPECT_EQ(differing, 0u) << "bodies whose position or velocity differ";
  ASSERT_EQ(a.reg.links.size(), b.reg.links.size());
  for (std::size_t k = 0; k < a.reg.links.size(); ++k) {
    EXPECT_EQ(bits(a.reg.links.rn[k]), bits(b.reg.links.rn[k])) << "spring " << k;
    EXPECT_EQ(bits(a.reg.links.law[k].k), bits(b.reg.links.law[k].k)) << "spring " << k;
    EXPECT_EQ(bits(a.reg.links.law[k].eps0), bits(b.reg.links.law[k].eps0)) << "spring " << k;
  }
  ASSERT_EQ(a.warm_start.size(), b.warm_start.size());
  for (std::size_t k = 0; k < a.warm_start.size(); ++k) {
    EXPECT_EQ(a.warm_start[k].pair, b.warm_start[k].pair);
    EXPECT_EQ(a.warm_start[k].feature, b.warm_start[k].feature);
    EXPECT_EQ(bits(a.warm_start[k].rn), bits(b.warm_start[k].rn));
    EXPECT_EQ(bits(a.warm_start[k].rt), bits(b.warm_start[k].rt));
  }
  auto ea = a.extra, eb = b.extra;
  ea.erase("output");
  eb.erase("output");
  ea.erase("state.cpu_seconds");  // processor time: measured, not computed
  eb.erase("state.cpu_seconds");
  ea.erase("state.sample");  // where the sample came from: a file, or prepared by the run
  eb.erase("state.sample");
  // the options and the run state (cycles done, t0, sums of sweeps, overlaps…), key by key
  for (const auto& [key, value] : ea)
    EXPECT_EQ(value, eb.count(key) ? eb.at(key) : "(none)") << "the checkpoints' " << key;
  for (const auto& [key, value] : eb)
    if (!ea.count(key)) ADD_FAILURE() << "the checkpoints' " << key << ": only in " << b_file;
  EXPECT_EQ(ea.at("state.cycles_done"), std::to_string(kCycles));
}

void compare_outputs(const fs::path& a, const fs::path& b);

/// Resumes `b` to N cycles and compares its outputs with the uninterrupted run `a`.
void resume_and_compare(const fs::path& a, const fs::path& b) {
  ballast::Config r;
  r.resume = b.string();
  r.cycles = kCycles;
  r.progress_every = 1e9;
  ASSERT_EQ(ballast::run(r), 0);
  compare_outputs(a, b);
}

/// The outputs of `b`, resumed to N cycles, equal those of the uninterrupted run `a`.
void compare_outputs(const fs::path& a, const fs::path& b) {
  const Csv ca = read_csv(a / "cycles.csv").untimed();
  const Csv cb = read_csv(b / "cycles.csv").untimed();
  ASSERT_EQ(ca.rows.size(), static_cast<std::size_t>(kCycles));
  // the POSTPRO series (issue #11) are compared too: the cumulative dissipation goes on across
  // the resume (carried by the checkpoint), and it is not zero
  for (const char* col : {"kinetic_energy", "contact_dissipation", "damper_dissipation", "coordination_number", "status_stick"})
    EXPECT_GT(ca.value(kCycles - 1, col), 0.0) << col;
  EXPECT_EQ(ca.columns, cb.columns);
  ASSERT_EQ(ca.rows.size(), cb.rows.size());
  for (std::size_t i = 0; i < ca.rows.size(); ++i) EXPECT_EQ(ca.rows[i], cb.rows[i]) << "cycles.csv row " << i + 1;

  // (timings, and the threads a step ran on: not results)
  const Csv sa = read_csv(a / "steps.csv").untimed();
  const Csv sb = read_csv(b / "steps.csv").untimed();
  ASSERT_EQ(sa.rows.size(), static_cast<std::size_t>(kCycles) * 250u);
  EXPECT_EQ(sa.columns, sb.columns);
  ASSERT_EQ(sa.rows.size(), sb.rows.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < sa.rows.size(); ++i)
    if (sa.rows[i] != sb.rows[i] && differing++ < 3) ADD_FAILURE() << "steps.csv row " << i + 1 << " differs";
  EXPECT_EQ(differing, 0u);

  EXPECT_EQ(read_summary(a / "summary.txt").at("final_settlement"), read_summary(b / "summary.txt").at("final_settlement"));
  EXPECT_EQ(read_summary(a / "summary.txt").at("mean_sweeps"), read_summary(b / "summary.txt").at("mean_sweeps"));
  EXPECT_EQ(read_summary(a / "summary.txt").at("cumulated_overlap"), read_summary(b / "summary.txt").at("cumulated_overlap"));
  EXPECT_EQ(read_summary(a / "summary.txt").at("max_sweeps"), read_summary(b / "summary.txt").at("max_sweeps"));
  expect_same_checkpoint(a / "checkpoint.nscd", b / "checkpoint.nscd");
}

// 2a. Stopped after 3 cycles (not a multiple of checkpoint_every = 2: the driver writes its
// final checkpoint at the stop), then resumed to N = 6.
TEST(BallastResume, StopAndResumeIsBitIdentical) {
  TempDir a("resume_a"), b("resume_b");
  ASSERT_EQ(ballast::run(resumable(a.path())), 0);
  ballast::Config cb = resumable(b.path());
  cb.stop_after_cycles = 3;
  ASSERT_EQ(ballast::run(cb), 0);
  ASSERT_EQ(read_csv(b / "cycles.csv").rows.size(), 3u);
  ASSERT_EQ(nscd::load_checkpoint(b / "checkpoint.nscd").extra.at("state.cycles_done"), "3");
  resume_and_compare(a.path(), b.path());
}

// 2b. Killed after its checkpoint at cycle 2 while it had written more: full rows of cycle 3
// and beyond, and a half-written last row (the streams are flushed in blocks, so a kill can cut
// a row anywhere; here it is cut inside the step number, which then reads as a small number).
TEST(BallastResume, RowsWrittenAfterTheCheckpointAreDropped) {
  TempDir a("kill_a"), b("kill_b");
  ASSERT_EQ(ballast::run(resumable(a.path())), 0);
  ballast::Config cb = resumable(b.path());
  cb.stop_after_cycles = 2;
  ASSERT_EQ(ballast::run(cb), 0);

  const Csv steps = read_csv(b / "steps.csv");
  ASSERT_EQ(steps.rows.size(), 500u);
  const long last_step = std::stol(steps.rows.back()[0]);
  std::string garbage_cycles, garbage_steps;
  for (int cycle = 3; cycle <= 4; ++cycle) garbage_cycles += std::to_string(cycle) + ",9,9,9,9,9,9,9,9,9,9\n";
  garbage_cycles += "5,1.04";  // cut inside the time column
  for (long k = last_step + 1; k <= last_step + 40; ++k) garbage_steps += std::to_string(k) + ",9,9,9,9,9,9,9,9,9,9,9,9,9,9\n";
  garbage_steps += std::to_string(last_step + 41).substr(0, 2);  // e.g. "42" of step 4248
  append_text(b / "cycles.csv", garbage_cycles);
  append_text(b / "steps.csv", garbage_steps);
  resume_and_compare(a.path(), b.path());
}

// 2c. --continue, as the batch studies' command lines give it: the first call starts the run
// (stopped after 3 cycles, as a killed job), the same call again resumes it from its checkpoint
// to the end, bit-identically, and once more finds it finished and touches nothing.
TEST(BallastResume, ContinueStartsResumesAndThenDoesNothing) {
  TempDir a("continue_a"), b("continue_b");
  ASSERT_EQ(ballast::run(resumable(a.path())), 0);
  ballast::Config cb = resumable(b.path());
  cb.continue_run = true;
  cb.stop_after_cycles = 3;
  ASSERT_EQ(ballast::run(cb), 0);
  ASSERT_EQ(read_csv(b / "cycles.csv").rows.size(), 3u);
  cb.stop_after_cycles = 0;
  ASSERT_EQ(ballast::run(cb), 0);
  compare_outputs(a.path(), b.path());
  EXPECT_EQ(read_summary(b / "summary.txt").at("cycles"), std::to_string(kCycles));
  const auto written = fs::last_write_time(b / "summary.txt");
  ASSERT_EQ(ballast::run(cb), 0);  // finished: nothing to do
  EXPECT_EQ(fs::last_write_time(b / "summary.txt"), written);
  compare_outputs(a.path(), b.path());
}

// 2d. SIGTERM during the cycles (a scheduler's notice, GNU parallel stopping its jobs): the run
// ends its cycle, writes its checkpoint, exits 143; resumed, it ends as the uninterrupted run.
TEST(BallastResume, SigtermStopsAtTheCycleEndWithACheckpoint) {
  TempDir a("sigterm_a"), b("sigterm_b");
  ballast::Config ca = resumable(a.path());
  ca.checkpoint_every = 0;  // as b's (a stored option): b's checkpoint comes from SIGTERM alone
  ASSERT_EQ(ballast::run(ca), 0);
  // a late signal (the run already over) must not kill the test program
  struct sigaction ignore {}, old {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  sigaction(SIGTERM, &ignore, &old);
  std::thread sender([&] {
    // once the first cycle is written, as a kill from outside would come
    for (int i = 0; i < 20000 && read_csv_rows(b / "cycles.csv") < 1; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    kill(getpid(), SIGTERM);
  });
  ballast::Config cb = resumable(b.path());
  cb.checkpoint_every = 0;
  const int rc = ballast::run(cb);
  sender.join();
  sigaction(SIGTERM, &old, nullptr);
  ASSERT_EQ(rc, 143);
  const int done = std::stoi(nscd::load_checkpoint(b / "checkpoint.nscd").extra.at("state.cycles_done"));
  EXPECT_GE(done, 1);
  EXPECT_LT(done, kCycles);
  EXPECT_EQ(read_csv(b / "cycles.csv").rows.size(), static_cast<std::size_t>(done));
  resume_and_compare(a.path(), b.path());
}

// 2e. A long run moved to a machine with more cores: stopped after 3 cycles on one thread, then
// resumed on two, every part of the step on them: it ends as the run done on one thread in one
// go, its cycles and steps bit for bit (eight and sixteen threads: NlgsColored's unit tests).
// The sample is larger than the tiny one (108 grains): enough contacts for the solve's strips to
// be shared among the threads, which the solve profile checks.
TEST(BallastResume, ResumedOnMoreThreadsEndsAsOnOne) {
  const auto config = [](const fs::path& out) {
    ballast::Config c = resumable(out);
    c.grading_fraction = 0.15;
    c.box_width = 0.3;
    c.pads = 15;
    c.sleeper_width = 0.08;
    c.load_mean = -200.0;
    c.load_amplitude = -100.0;
    return c;
  };
  TempDir a("threads_a");
  ASSERT_EQ(ballast::run(config(a.path())), 0);
  for (const int t : {2}) {
    TempDir b("threads_b" + std::to_string(t));
    ballast::Config cb = config(b.path());
    cb.sample = (a / "sample.nscd").string();  // the same sample, not prepared again
    cb.stop_after_cycles = 3;
    ASSERT_EQ(ballast::run(cb), 0);
    ballast::Config r;
    r.resume = b.path().string();
    r.cycles = kCycles;
    r.progress_every = 1e9;
    r.threads = r.solve_threads = r.loop_threads = t;
    r.solve_profile = true;
    ASSERT_EQ(ballast::run(r), 0);
    // the resumed cycles' solves ran their region on more than one thread
    const auto summary = read_summary(b / "summary.txt");
    EXPECT_GT(std::stod(summary.at("solve_thread_seconds")) / std::stod(summary.at("solve_region_seconds")), 1.5)
        << t << " threads";
    compare_outputs(a.path(), b.path());
  }
}

// 2f. A long run moved to another machine (a fresh one each session, a cluster job's scratch
// folder) with only its checkpoint and its cycles.csv: resumed there, its cycles and its final
// state are the run done in one go; steps.csv starts again at the checkpoint's step.
TEST(BallastResume, MovedWithItsCheckpointAndCyclesAlone) {
  TempDir a("moved_a"), b("moved_b"), c("moved_c");
  ASSERT_EQ(ballast::run(resumable(a.path())), 0);
  ballast::Config cb = resumable(b.path());
  cb.stop_after_cycles = 3;
  ASSERT_EQ(ballast::run(cb), 0);
  for (const char* f : {"checkpoint.nscd", "cycles.csv"}) fs::copy_file(b / f, c / f);
  ballast::Config r;
  r.resume = c.path().string();
  r.cycles = kCycles;
  r.progress_every = 1e9;
  ASSERT_EQ(ballast::run(r), 0);
  const Csv ca = read_csv(a / "cycles.csv").untimed();
  const Csv cc = read_csv(c / "cycles.csv").untimed();
  EXPECT_EQ(ca.columns, cc.columns);
  ASSERT_EQ(ca.rows.size(), cc.rows.size());
  for (std::size_t i = 0; i < ca.rows.size(); ++i) EXPECT_EQ(ca.rows[i], cc.rows[i]) << "cycles.csv row " << i + 1;
  const Csv sa = read_csv(a / "steps.csv").untimed();
  const Csv sc = read_csv(c / "steps.csv").untimed();
  ASSERT_EQ(sc.rows.size(), static_cast<std::size_t>(kCycles - 3) * 250u);
  for (std::size_t i = 0; i < sc.rows.size(); ++i)
    ASSERT_EQ(sc.rows[i], sa.rows[i + 3 * 250]) << "steps.csv row " << i + 1 << " of the moved run";
  EXPECT_EQ(read_summary(a / "summary.txt").at("final_settlement"),
            read_summary(c / "summary.txt").at("final_settlement"));
  EXPECT_EQ(read_summary(a / "summary.txt").at("mean_sweeps"), read_summary(c / "summary.txt").at("mean_sweeps"));
  expect_same_checkpoint(a / "checkpoint.nscd", c / "checkpoint.nscd");
}

}  // namespace
