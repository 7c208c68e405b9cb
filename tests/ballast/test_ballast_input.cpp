// tests/ballast/test_ballast_input.cpp — what the ballast driver refuses (issue #9): options a
// run cannot honour (scene options with --sample, changed options with --resume), output
// folders holding an earlier run, out-of-range options and stored options, bad config files,
// bad sample files, and results that are physically impossible; the step checks' options.
#include <gtest/gtest.h>

#include <initializer_list>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "ballast_test_support.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/checkpoint.hpp"

namespace {

using namespace ballast_test;

// The tiny sample's options as command-line arguments (tiny_config), plus `more`.
std::vector<std::string> tiny_args(const fs::path& out, std::vector<std::string> more) {
  std::vector<std::string> a = {"--load-mean", "-100", "--load-amplitude", "-50", "--vtk-every", "0", "--steps-every", "1",
                                "--progress-every", "1e9", "--output", out.string()};
  a.insert(a.end(), more.begin(), more.end());
  return a;
}
const std::vector<std::string> kTinyScene = {"--grading-fraction", "0.05", "--box-width", "0.2", "--pads", "10",
                                             "--sleeper-width", "0.06"};

bool parse_args(std::vector<std::string> args, ballast::Config& c) {
  args.insert(args.begin(), "ballast");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  return ballast::parse(static_cast<int>(argv.size()), argv.data(), c);
}

/// Parses and runs; returns the message of the exception that ends it ("" if none), and the
/// exit status in `status` (-1 when it threw).
std::string run_args(const std::vector<std::string>& args, int* status = nullptr) {
  if (status) *status = -1;
  try {
    ballast::Config c;
    parse_args(args, c);
    const int s = ballast::run(c);
    if (status) *status = s;
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// A prepared tiny sample (shared by the tests of this file; prepared once).
const fs::path& tiny_sample() {
  static TempDir dir("input_sample");
  static const bool ready = [] {
    std::vector<std::string> a = tiny_args(dir.path(), {"--prepare-only", "--cycles", "0"});
    a.insert(a.end(), kTinyScene.begin(), kTinyScene.end());
    return run_args(a).empty();
  }();
  EXPECT_TRUE(ready);
  static const fs::path file = dir / "sample.nscd";
  return file;
}

/// `text` with the line that starts with `start` replaced by `line`.
std::string replace_line(const std::string& text, const std::string& start, const std::string& line) {
  const auto at = text.find("\n" + start);
  EXPECT_NE(at, std::string::npos) << "no line starting with " << start;
  if (at == std::string::npos) return text;
  const auto end = text.find('\n', at + 1);
  return text.substr(0, at + 1) + line + text.substr(end);
}

void write_text(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

/// The message of the InputError that parsing `args` into a fresh Config throws ("(accepted)"
/// if none): parse takes the Config's values as the defaults.
std::string parse_error(const std::vector<std::string>& args) {
  try {
    ballast::Config fresh;
    parse_args(args, fresh);
  } catch (const std::invalid_argument& e) {
    return std::string(e.what());
  }
  return std::string("(accepted)");
}

/// Rewrites a checkpoint as one written before `keys` existed: their "x" lines removed from its
/// extra section and the section's count lowered to match.
void erase_stored_options(const fs::path& cp_file, std::initializer_list<const char*> keys) {
  std::string text = read_text(cp_file);
  for (const char* key : keys) {
    const auto at = text.find("\nx \"" + std::string(key) + "\" ");
    ASSERT_NE(at, std::string::npos) << key;
    text.erase(at, text.find('\n', at + 1) - at);
  }
  const auto extra = text.find("\nextra ");
  ASSERT_NE(extra, std::string::npos);
  const auto extra_end = text.find('\n', extra + 1);
  const int n = std::stoi(text.substr(extra + 7, extra_end - extra - 7));
  text.replace(extra + 7, extra_end - extra - 7, std::to_string(n - static_cast<int>(keys.size())));
  write_text(cp_file, text);
}

TEST(BallastOptions, SceneOptionsWithASampleAreRefusedUnlessTheyMatchIt) {
  const fs::path sample = tiny_sample();
  TempDir out("scene_opts");
  // issue #9: each of these was silently ignored, and the checkpoint recorded the ignored value
  for (const auto& [opt, value] : std::vector<std::pair<std::string, std::string>>{
           {"mu", "0.2"}, {"k", "8000"}, {"nu", "10"}, {"pads", "50"}, {"box-width", "1"}, {"seed", "7"}, {"sleeper-width", "0.1"}, {"bars", "1"}}) {
    const std::string m = run_args(tiny_args(out.path(), {"--sample", sample.string(), "--cycles", "1", "--" + opt, value}));
    EXPECT_TRUE(has(m, "--" + opt + " " + value + " differs from the sample '" + sample.string() + "'")) << m;
    EXPECT_TRUE(fs::is_empty(out.path()));
  }
  // the sample's own values are accepted (the stiffness study gives --seed with --sample), and
  // the checkpoint and the summary record what the sample is
  int status = -1;
  std::vector<std::string> a = tiny_args(out.path(), {"--sample", sample.string(), "--cycles", "1", "--seed", "2006"});
  a.insert(a.end(), kTinyScene.begin(), kTinyScene.end());
  EXPECT_EQ(run_args(a, &status), "");
  EXPECT_EQ(status, 0);
  const nscd::Checkpoint cp = nscd::load_checkpoint(out / "checkpoint.nscd");
  EXPECT_EQ(cp.extra.at("pads"), "10");
  EXPECT_EQ(cp.extra.at("k"), "4100");
  EXPECT_EQ(cp.extra.at("state.sample"), sample.string());
  const auto sum = read_summary(out / "summary.txt");
  EXPECT_EQ(sum.at("pads"), "10");
  EXPECT_EQ(sum.at("sample"), sample.string());
  EXPECT_EQ(sum.at("result"), "valid");
}

TEST(BallastOptions, ResumeRefusesChangedOptions) {
  TempDir out("resume_opts");
  std::vector<std::string> a = tiny_args(out.path(), {"--cycles", "1"});
  a.insert(a.end(), kTinyScene.begin(), kTinyScene.end());
  ASSERT_EQ(run_args(a), "");
  const std::string before = read_text(out / "checkpoint.nscd");
  const std::string r = out.path().string();
  EXPECT_TRUE(has(run_args({"--resume", r, "--cycles", "2", "--dt", "1e-4"}), "--dt 1e-04 differs from the resumed run's checkpoint"));
  EXPECT_TRUE(has(run_args({"--resume", r, "--cycles", "2", "--mu", "0.3"}), "--mu 0.3 differs"));
  EXPECT_TRUE(has(run_args({"--resume", r, "--cycles", "2", "--k-factor", "100"}), "--k-factor 100 differs"));
  EXPECT_TRUE(has(run_args({"--resume", r, "--cycles", "2", "--frequency", "25"}), "--frequency 25 differs"));
  EXPECT_TRUE(has(run_args({"--resume", r, "--cycles", "2", "--overwrite"}), "--overwrite and --resume cannot go together"));
  EXPECT_TRUE(has(run_args({"--resume", r, "--cycles", "2", "--output", "elsewhere"}), "cannot go with --resume"));
  EXPECT_TRUE(has(run_args({"--resume", r, "--cycles", "0"}), "--cycles 0"));
  EXPECT_EQ(read_text(out / "checkpoint.nscd"), before);
  // the stored values themselves, and the cycles, are fine
  int status = -1;
  EXPECT_EQ(run_args({"--resume", r, "--cycles", "2", "--dt", "2e-4", "--progress-every", "1e9"}, &status), "");
  EXPECT_EQ(status, 0);
  EXPECT_EQ(read_summary(out / "summary.txt").at("cycles"), "2");
}

TEST(BallastOptions, BadStoredOptionsNameTheFileAndTheKey) {
  TempDir out("stored_opts");
  std::vector<std::string> a = tiny_args(out.path(), {"--cycles", "1"});
  a.insert(a.end(), kTinyScene.begin(), kTinyScene.end());
  ASSERT_EQ(run_args(a), "");
  const fs::path cp = out / "checkpoint.nscd";
  const std::string good = read_text(cp);
  auto with = [&](const std::string& key, const std::string& value) {
    write_text(cp, replace_line(good, "x \"" + key + "\" ", "x \"" + key + "\" \"" + value + "\""));
    return run_args({"--resume", out.path().string(), "--cycles", "2"});
  };
  // issue #9: steps-every 0 was a SIGFPE, frequency 0 gave -nan rows, max-sweeps 1.5 or 1e9
  // were read as 1, malformed values ended with just "stoi"
  for (const auto& [key, value, rule] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"steps-every", "0", "--steps-every must be >= 1"},
           {"frequency", "0", "--frequency must be > 0"},
           {"max-sweeps", "1.5", "key 'max-sweeps': '1.5' is not an integer"},
           {"max-sweeps", "1e9", "key 'max-sweeps': '1e9' is not an integer"},
           {"dt", "fast", "key 'dt': bad number 'fast'"},
           {"seed", "-1", "key 'seed': '-1' is not an unsigned integer"},
           {"guided-sleeper", "yes", "key 'guided-sleeper': 'yes' is not a boolean"},
           {"state.cycles_done", "1x", "key 'state.cycles_done': '1x' is not an integer"},
           {"state.y_ref", "inf", "key 'state.y_ref': bad number 'inf'"}}) {
    const std::string m = with(key, value);
    EXPECT_TRUE(has(m, cp.string())) << key << ": " << m;
    EXPECT_TRUE(has(m, rule)) << key << ": " << m;
  }
}

TEST(BallastOptions, OutputFolderIsNeverMixedWithAnEarlierRun) {
  TempDir out("folder");
  std::vector<std::string> a = tiny_args(out.path(), {"--cycles", "1"});
  a.insert(a.end(), kTinyScene.begin(), kTinyScene.end());
  ASSERT_EQ(run_args(a), "");
  const std::string before = read_text(out / "checkpoint.nscd");
  // issue #9: a new run into the folder, killed before its first checkpoint, then --resume,
  // resumed the old run; the new run is refused now, before it writes anything
  const std::string m = run_args(a);
  EXPECT_TRUE(has(m, "the output folder '" + out.path().string() + "' is not empty")) << m;
  EXPECT_TRUE(has(m, "--overwrite")) << m;
  EXPECT_EQ(read_text(out / "checkpoint.nscd"), before);
  // --overwrite replaces the run: its files (a stale vtk/ included) go, other files stay
  fs::create_directories(out / "vtk");
  write_text(out / "vtk" / "stale.vtu", "old");
  write_text(out / "notes.md", "mine");
  a.push_back("--overwrite");
  ASSERT_EQ(run_args(a), "");
  EXPECT_FALSE(fs::exists(out / "vtk"));
  EXPECT_TRUE(fs::exists(out / "notes.md"));
  EXPECT_EQ(read_csv(out / "cycles.csv").rows.size(), 1u);
  // a log file alone (a redirected output) is not an earlier run
  TempDir logged("folder_log");
  write_text(logged / "log.txt", "ballast: ...\n");
  std::vector<std::string> b = tiny_args(logged.path(), {"--sample", tiny_sample().string(), "--cycles", "1"});
  EXPECT_EQ(run_args(b), "");
}

TEST(BallastOptions, OutOfRangeOptionsAreRefusedBeforeAnyWork) {
  TempDir out("ranges");
  // issue #9: --cycles 0 prepared a whole sample first
  EXPECT_TRUE(has(parse_error({"--cycles", "0"}), "--cycles 0 runs no loading cycle: give --prepare-only"));
  EXPECT_TRUE(has(parse_error({"--dt", "1e9"}), "--dt 1e+09 s is too long for --alert 0.00125 m"));
  EXPECT_TRUE(has(parse_error({"--mu", "inf"}), "--mu must be a finite number, got inf"));
  EXPECT_TRUE(has(parse_error({"--theta", "0.4999999"}), "--theta must lie in [0.5, 1], got 0.4999999"));
  EXPECT_TRUE(has(parse_error({"--max-sweeps", "1.5"}), "max-sweeps"));
  EXPECT_TRUE(has(parse_error({"--min-sweeps", "20", "--max-sweeps", "10"}), "--min-sweeps"));
  EXPECT_TRUE(has(parse_error({"--sample", "a", "--resume", "b"}), "--sample and --resume cannot go together"));
  EXPECT_TRUE(has(parse_error({"--sample", "a", "--prepare-only"}), "--prepare-only prepares a new sample"));
  // issue #9: --load-mean -1e12 gave a settlement of 37 km; refused before the preparation
  std::vector<std::string> a = tiny_args(out.path(), {"--cycles", "1"});
  a.insert(a.end(), kTinyScene.begin(), kTinyScene.end());
  a[1] = "-1e12";  // --load-mean
  const std::string m = run_args(a);
  EXPECT_TRUE(has(m, "the load |load-mean| + |load-amplitude| = 1000000000050 N/m exceeds what the sublayer can carry")) << m;
  EXPECT_TRUE(has(m, "= 4100 N/m, the springs")) << m;  // 10 springs x 4100 N/m x 1 x 0.1 m (per metre of thickness)
  EXPECT_FALSE(fs::exists(out / "sample.nscd"));
}

TEST(BallastOptions, StepChecksAreParsedCheckedAndKeptOnResume) {
  // issue #9: the step guard's options (StepperOptions) on the ballast command line, as in deposit
  ballast::Config c;
  ASSERT_TRUE(parse_args({"--strict-alert", "--residual-check-every", "7", "--residual-flag", "1e-4", "--residual-limit", "0.5"}, c));
  EXPECT_TRUE(c.strict_alert);
  EXPECT_EQ(c.residual_check_every, 7);
  EXPECT_EQ(c.residual_flag, 1e-4);
  EXPECT_EQ(c.residual_limit, 0.5);
  EXPECT_TRUE(has(parse_error({"--residual-check-every", "-1"}), "--residual-check-every must be >= 0 (0: never), got -1"));
  EXPECT_TRUE(has(parse_error({"--residual-check-every", "1.5"}), "residual-check-every"));
  EXPECT_TRUE(has(parse_error({"--residual-flag", "0"}), "--residual-flag must be > 0, got 0"));
  EXPECT_TRUE(has(parse_error({"--residual-limit", "-1"}), "--residual-limit must be >= 0 (0: never), got -1"));
  EXPECT_TRUE(has(parse_error({"--residual-limit", "nan"}), "--residual-limit must be a finite number, got nan"));
  // they define the run: stored in its checkpoint, kept by --resume, a different value refused
  TempDir out("step_checks");
  const std::string r = out.path().string();
  ASSERT_EQ(run_args(tiny_args(out.path(), {"--sample", tiny_sample().string(), "--cycles", "1", "--strict-alert", "--residual-check-every", "5"})), "");
  const fs::path cp_file = out / "checkpoint.nscd";
  const nscd::Checkpoint cp = nscd::load_checkpoint(cp_file);
  EXPECT_EQ(cp.extra.at("strict-alert"), "1");
  EXPECT_EQ(cp.extra.at("residual-check-every"), "5");
  EXPECT_EQ(cp.extra.at("residual-flag"), "0.001");
  EXPECT_EQ(cp.extra.at("residual-limit"), "0");
  EXPECT_TRUE(has(run_args({"--resume", r, "--cycles", "2", "--residual-limit", "0.5"}), "--residual-limit 0.5 differs from the resumed run's checkpoint"));
  EXPECT_TRUE(has(run_args({"--resume", r, "--cycles", "2", "--strict-alert=false"}), "--strict-alert 0 differs"));
  int status = -1;
  EXPECT_EQ(run_args({"--resume", r, "--cycles", "2", "--strict-alert", "--progress-every", "1e9"}, &status), "");
  EXPECT_EQ(status, 0);
  // this process ran one cycle of 250 steps: 50 checked steps with the stored 5 (5 with the default 50)
  EXPECT_EQ(read_summary(out / "summary.txt").at("residual_checks"), "50");
  // a checkpoint written before these options existed resumes with their defaults
  erase_stored_options(cp_file, {"strict-alert", "residual-check-every", "residual-flag", "residual-limit"});
  EXPECT_EQ(run_args({"--resume", r, "--cycles", "3", "--progress-every", "1e9"}, &status), "");
  EXPECT_EQ(status, 0);
  EXPECT_EQ(read_summary(out / "summary.txt").at("residual_checks"), "5");
  EXPECT_EQ(nscd::load_checkpoint(cp_file).extra.at("residual-check-every"), "50");
}

TEST(BallastOptions, SweepOrderAndRelaxationReachTheSolverAndAreKeptOnResume) {
  // issue #8: the NLGS sweep's order, relaxation and threads on the ballast command line, as in
  // deposit; out-of-range values refused at once, naming the option
  ballast::Config c;
  ASSERT_TRUE(parse_args({"--order", "colored", "--relaxation", "1.3", "--threads", "2"}, c));
  EXPECT_EQ(c.order, "colored");
  EXPECT_EQ(c.relaxation, 1.3);
  EXPECT_EQ(c.threads, 2);
  EXPECT_TRUE(has(
      parse_error({"--order", "random"}),
      "--order: unknown sweep order 'random'; valid: fixed reversed shuffled alternating colored colored-rows colored-cells"));
  EXPECT_TRUE(has(parse_error({"--relaxation", "2"}), "--relaxation must lie in (0, 2), got 2"));
  EXPECT_TRUE(has(parse_error({"--relaxation", "0"}), "--relaxation must lie in (0, 2), got 0"));
  EXPECT_TRUE(has(parse_error({"--order", "fixed", "--threads", "2"}), "--threads 2 needs --order colored"));
  EXPECT_TRUE(has(parse_error({"--order", "colored", "--threads", "0"}), "--threads must lie in [1, 256], got 0"));
  EXPECT_TRUE(has(parse_error({"--relaxation", "1.3", "--check-every", "1"}), "--relaxation 1.3 needs --check-every >= 2"));
  // they reach the solver: the same cycle over-relaxed takes another number of sweeps; the
  // summary and the checkpoint record them
  TempDir plain("sweep_plain"), relaxed("sweep_relaxed"), colored1("sweep_colored1"), colored2("sweep_colored2");
  const std::string sample = tiny_sample().string();
  ASSERT_EQ(run_args(tiny_args(plain.path(), {"--sample", sample, "--cycles", "1", "--order", "fixed", "--relaxation", "1"})), "");
  ASSERT_EQ(run_args(tiny_args(relaxed.path(), {"--sample", sample, "--cycles", "1", "--order", "fixed", "--relaxation", "1.3"})), "");
  const auto s_plain = read_summary(plain / "summary.txt"), s_relaxed = read_summary(relaxed / "summary.txt");
  EXPECT_EQ(s_plain.at("order"), "fixed");
  EXPECT_EQ(s_plain.at("relaxation"), "1");
  EXPECT_EQ(s_relaxed.at("relaxation"), "1.3");
  EXPECT_NE(s_plain.at("mean_sweeps"), s_relaxed.at("mean_sweeps"));
  EXPECT_EQ(nscd::load_checkpoint(relaxed / "checkpoint.nscd").extra.at("relaxation"), "1.3");
  EXPECT_EQ(nscd::load_checkpoint(plain / "checkpoint.nscd").extra.at("order"), "fixed");
  // threads is this process's choice: never stored. The tiny sample (< 8192 contacts) is swept
  // on one thread whatever --threads says (theory §9.5), so this checks the plumbing; that the
  // numbers do not depend on the threads is NlgsColored.AShortDepositHasTheSameHashOnOneAndTwoThreads
  ASSERT_EQ(run_args(tiny_args(colored1.path(), {"--sample", sample, "--cycles", "1", "--order", "colored"})), "");
  ASSERT_EQ(run_args(tiny_args(colored2.path(), {"--sample", sample, "--cycles", "1", "--order", "colored", "--threads", "2"})), "");
  const auto s1 = read_summary(colored1 / "summary.txt"), s2 = read_summary(colored2 / "summary.txt");
  for (const char* key : {"final_settlement", "mean_sweeps", "max_overlap", "cumulated_overlap"}) EXPECT_EQ(s1.at(key), s2.at(key)) << key;
  EXPECT_EQ(nscd::load_checkpoint(colored2 / "checkpoint.nscd").extra.count("threads"), 0u);
  // the rows of cells: another order, stored as such, the same numbers on two threads
  TempDir rows1("sweep_rows1"), rows2("sweep_rows2");
  ASSERT_EQ(run_args(tiny_args(rows1.path(), {"--sample", sample, "--cycles", "1", "--order", "colored-rows"})), "");
  ASSERT_EQ(run_args(tiny_args(rows2.path(), {"--sample", sample, "--cycles", "1", "--order", "colored-rows", "--threads", "2"})), "");
  const auto r1 = read_summary(rows1 / "summary.txt"), r2 = read_summary(rows2 / "summary.txt");
  EXPECT_EQ(r1.at("order"), "colored-rows");
  EXPECT_EQ(nscd::load_checkpoint(rows1 / "checkpoint.nscd").extra.at("order"), "colored-rows");
  for (const char* key : {"final_settlement", "mean_sweeps", "max_overlap", "cumulated_overlap"}) EXPECT_EQ(r1.at(key), r2.at(key)) << key;
  // a resumed run keeps its order and relaxation: another value is refused, the same accepted
  const std::string r = relaxed.path().string();
  EXPECT_TRUE(has(run_args({"--resume", r, "--cycles", "2", "--relaxation", "1"}), "--relaxation 1 differs from the resumed run's checkpoint"));
  EXPECT_TRUE(has(run_args({"--resume", r, "--cycles", "2", "--order", "reversed"}), "--order reversed differs"));
  int status = -1;
  EXPECT_EQ(run_args({"--resume", r, "--cycles", "2", "--relaxation", "1.3", "--progress-every", "1e9"}, &status), "");
  EXPECT_EQ(status, 0);
  EXPECT_EQ(read_summary(relaxed / "summary.txt").at("relaxation"), "1.3");
  // --threads on resume: free for a colored run (its order comes from the checkpoint), refused
  // with the stored order named for another order
  const std::string c1 = colored1.path().string();
  EXPECT_EQ(run_args({"--resume", c1, "--cycles", "2", "--threads", "2", "--progress-every", "1e9"}, &status), "");
  EXPECT_EQ(status, 0);
  EXPECT_TRUE(has(
      run_args({"--resume", r, "--cycles", "3", "--threads", "2"}),
      "--threads 2 needs --order colored, colored-rows or colored-cells, and the resumed run sweeps in order fixed"));
  // a checkpoint written before these options existed resumes with the paper's fixed order, ω = 1
  const fs::path cp_file = plain / "checkpoint.nscd";
  erase_stored_options(cp_file, {"order", "relaxation"});
  EXPECT_EQ(run_args({"--resume", plain.path().string(), "--cycles", "2", "--progress-every", "1e9"}, &status), "");
  EXPECT_EQ(status, 0);
  const auto s_old = read_summary(plain / "summary.txt");
  EXPECT_EQ(s_old.at("order"), "fixed");
  EXPECT_EQ(s_old.at("relaxation"), "1");
}

TEST(BallastOptions, ConfigFileErrorsNameTheFileAndTheLine) {
  TempDir dir("config");
  auto error_of = [&](const std::string& text) {
    write_text(dir / "run.cfg", text);
    try {
      ballast::Config c;
      parse_args({"--config", (dir / "run.cfg").string()}, c);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  const std::string where = "config file '" + (dir / "run.cfg").string() + "', line ";
  EXPECT_TRUE(has(error_of("# a run\ndt = 2e-4\nmu = abc\n"), where + "3: ")) << error_of("dt = 2e-4\nmu = abc\n");
  EXPECT_TRUE(has(error_of("mu = 0.4\n\nmu = 0.5\n"), where + "3: 'mu' is given twice (first on line 1)"));
  EXPECT_TRUE(has(error_of("cycles = 3\nno-such-key = 1\n"), where + "2: "));
  EXPECT_TRUE(has(error_of("cycles 3\n"), where + "1: expected 'key = value'"));
  EXPECT_TRUE(has(error_of("max-sweeps = 1e9\n"), where + "1: "));
  EXPECT_TRUE(has(error_of("frequency = 0\n"), "--frequency must be > 0"));
  // the command line wins over the file
  write_text(dir / "run.cfg", "cycles = 3\nmu = 0.25\n");
  ballast::Config c;
  ASSERT_TRUE(parse_args({"--config", (dir / "run.cfg").string(), "--cycles", "5"}, c));
  EXPECT_EQ(c.cycles, 5);
  EXPECT_EQ(c.mu, 0.25);
}

TEST(BallastOptions, BadSampleFilesAreRefusedNotRun) {
  const std::string good = read_text(tiny_sample());
  TempDir dir("bad_sample");
  const fs::path bad = dir / "bad.nscd";
  auto run_sample = [&](const std::string& text) {
    write_text(bad, text);
    fs::remove_all(dir / "out");
    return run_args(tiny_args(dir / "out", {"--sample", bad.string(), "--cycles", "1"}));
  };
  // issue #9: an infinite warm-start force crashed (SIGSEGV); -2^1000 ran to a settlement of -1e288
  const auto w = good.find("\nw ");
  ASSERT_NE(w, std::string::npos);
  std::istringstream wl(good.substr(w + 1, good.find('\n', w + 1) - w - 1));
  std::string tag, pair, feature;
  wl >> tag >> pair >> feature;
  const std::string inf = run_sample(replace_line(good, "w " + pair + " " + feature + " ", "w " + pair + " " + feature + " inf 0x0p+0"));
  EXPECT_TRUE(has(inf, bad.string()) && has(inf, "normal force: bad number 'inf'")) << inf;
  const std::string huge =
      run_sample(replace_line(good, "w " + pair + " " + feature + " ", "w " + pair + " " + feature + " -0x1p+1000 0x0p+0"));
  EXPECT_TRUE(has(huge, "normal force -1.0715086071862673e+301 is out of range")) << huge;
  // a run's checkpoint is not a sample (its load is already on the sleeper)
  TempDir run_dir("bad_sample_run");
  ASSERT_EQ(run_args(tiny_args(run_dir.path(), {"--sample", tiny_sample().string(), "--cycles", "1"})), "");
  const std::string m = run_args(tiny_args(dir / "out2", {"--sample", (run_dir / "checkpoint.nscd").string(), "--cycles", "1"}));
  EXPECT_TRUE(has(m, "is the checkpoint of a run")) << m;
}

TEST(BallastOptions, PhysicallyImpossibleResultEndsWithANonZeroExit) {
  // a grain moved outside the box (left of the left wall, x = -0.25 m) in the sample
  const std::string good = read_text(tiny_sample());
  const auto at = good.find("\nb \"grain 0\" ");
  ASSERT_NE(at, std::string::npos);
  const std::string line = good.substr(at + 1, good.find('\n', at + 1) - at - 1);
  std::vector<std::string> t;
  std::istringstream ls(line);
  for (std::string x; ls >> x;) t.push_back(x);
  ASSERT_EQ(t.size(), 15u);  // b, "grain, 0", material, mass, inertia, x0, y0, a0, x, y, angle, vx, vy, spin
  t[9] = "-0x1p-2";
  std::string edited;
  for (const auto& x : t) edited += (edited.empty() ? "" : " ") + x;
  TempDir dir("impossible");
  write_text(dir / "s.nscd", replace_line(good, "b \"grain 0\" ", edited));
  int status = -1;
  EXPECT_EQ(run_args(tiny_args(dir / "out", {"--sample", (dir / "s.nscd").string(), "--cycles", "2"}), &status), "");
  EXPECT_EQ(status, 3);
  const auto sum = read_summary(dir / "out" / "summary.txt");
  EXPECT_TRUE(has(sum.at("result"), "impossible: cycle 1: grain 'grain 0' at (-0.")) << sum.at("result");
  EXPECT_TRUE(has(sum.at("result"), "is outside the box")) << sum.at("result");
  EXPECT_FALSE(fs::exists(dir / "out" / "checkpoint.nscd"));
}

}  // namespace
