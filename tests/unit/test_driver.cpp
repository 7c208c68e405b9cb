// tests/unit/test_driver.cpp — the drivers' toolkit (shared/driver/): the option table (command
// line, --config, precedence, unknown keys, bad values, switches), the stored key → value map
// round-trip through a checkpoint and the refusal of changed options, run_main's exit statuses
// and messages, settle()'s stopping rules on a tiny scene, and the summary writer.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "error_assertions.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/run_main.hpp"
#include "nscd/shared/driver/settle.hpp"
#include "nscd/shared/driver/summary.hpp"
#include "nscd/shared/samples.hpp"

namespace {

namespace fs = std::filesystem;
namespace driver = nscd::driver;
using nscd::testing_support::Contains;

struct Cfg {
  std::uint64_t seed = 7;
  double dt = 2e-4;
  int cycles = 30;
  std::int64_t grains = 0;
  std::string output = "out/x";
  bool overwrite = false;   // a switch
  bool guided = false;      // "--guided" alone means true
  double cap = -1.0;        // no default: set from `given`
};

const driver::OptionTable<Cfg>& table() {
  static const driver::OptionTable<Cfg> t("toy", "a toy driver",
                                          {{"seed", &Cfg::seed, "seed", driver::Kind::Scene},
                                           {"dt", &Cfg::dt, "time step (s)", driver::Kind::Run},
                                           {"cycles", &Cfg::cycles, "cycles", driver::Kind::Free},
                                           {"grains", &Cfg::grains, "grains", driver::Kind::Scene},
                                           {"output", &Cfg::output, "output folder"},
                                           {"overwrite", &Cfg::overwrite, "replace", driver::Kind::Free, driver::kSwitch},
                                           {"guided", &Cfg::guided, "guided", driver::Kind::Run, driver::kImplicit},
                                           {"cap", &Cfg::cap, "cap (s)", driver::Kind::Free, driver::kNoDefault}});
  return t;
}

struct TempDir {
  TempDir() : path(fs::temp_directory_path() / ("nscd_driver_" + std::to_string(::getpid()) + "_" +
                                                 ::testing::UnitTest::GetInstance()->current_test_info()->name())) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  fs::path path;
};

void write(const fs::path& f, const std::string& text) {
  std::ofstream(f) << text;
}

/// Parses `args` (without the program name) into c; returns parse's result.
bool parse(std::vector<std::string> args, Cfg& c, std::set<std::string>* given = nullptr) {
  args.insert(args.begin(), "toy");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  return table().parse(static_cast<int>(argv.size()), argv.data(), c, given);
}

/// The message of the InputError that parse throws ("" and a failure if none).
std::string parse_error(std::vector<std::string> args) {
  Cfg c;
  try {
    parse(std::move(args), c);
  } catch (const driver::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

// More threads than the cores the run may use: a warning that names both; none up to them.
TEST(DriverOptions, MoreThreadsThanCoresAreWarnedOf) {
  const int cores = driver::usable_cores();
  ASSERT_GE(cores, 1);
  EXPECT_EQ(driver::threads_warning("deposit", 1), "");
  EXPECT_EQ(driver::threads_warning("deposit", cores), "");
  const std::string w = driver::threads_warning("deposit", cores + 1);
  EXPECT_NE(w.find("deposit: warning: --threads " + std::to_string(cores + 1)), std::string::npos) << w;
  EXPECT_NE(w.find(std::to_string(cores) + " core(s)"), std::string::npos) << w;
}

TEST(DriverOptions, DefaultsAndCommandLine) {
  Cfg c;
  std::set<std::string> given;
  ASSERT_TRUE(parse({}, c, &given));
  EXPECT_EQ(c.seed, 7u);
  EXPECT_EQ(c.cap, -1.0);  // no default applied
  EXPECT_TRUE(given.empty());
  ASSERT_TRUE(parse({"--seed", "11", "--dt=1e-4", "--overwrite", "--guided", "--cap", "2.5"}, c, &given));
  EXPECT_EQ(c.seed, 11u);
  EXPECT_EQ(c.dt, 1e-4);
  EXPECT_TRUE(c.overwrite);
  EXPECT_TRUE(c.guided);
  EXPECT_EQ(c.cap, 2.5);
  EXPECT_EQ(given, (std::set<std::string>{"seed", "dt", "overwrite", "guided", "cap"}));
}

TEST(DriverOptions, ConfigFileAndPrecedence) {
  TempDir d;
  const fs::path cfg = d.path / "run.cfg";
  write(cfg, "# a comment\nseed = 5\ncycles = 12   # trailing comment\noverwrite = true\nguided = false\n");
  Cfg c;
  std::set<std::string> given;
  ASSERT_TRUE(parse({"--config", cfg.string(), "--seed", "9"}, c, &given));
  EXPECT_EQ(c.seed, 9u);      // the command line wins
  EXPECT_EQ(c.cycles, 12);    // the file gives the rest
  EXPECT_TRUE(c.overwrite);   // a switch: "key = true" in a file
  EXPECT_FALSE(c.guided);
  EXPECT_TRUE(given.count("cycles") && given.count("seed") && !given.count("config"));
  // a switch set to false in a file is not given
  write(cfg, "overwrite = false\n");
  Cfg c2;
  ASSERT_TRUE(parse({"--config", cfg.string()}, c2, &given));
  EXPECT_FALSE(c2.overwrite);
  EXPECT_FALSE(given.count("overwrite"));
}

TEST(DriverOptions, BadInputNamesTheOptionAndTheLine) {
  TempDir d;
  const fs::path cfg = d.path / "bad.cfg";
  EXPECT_TRUE(Contains(parse_error({"--no-such-option"}), "--no-such-option"));
  EXPECT_TRUE(Contains(parse_error({"--cycles", "many"}), "cycles"));
  EXPECT_TRUE(Contains(parse_error({"--seed", "1%value%"}), "'%'"));  // never reaches Boost (it would loop)
  write(cfg, "seed = 1\nspeed = 3\n");
  const std::string unknown = parse_error({"--config", cfg.string()});
  EXPECT_TRUE(Contains(unknown, "config file '" + cfg.string() + "', line 2"));
  EXPECT_TRUE(Contains(unknown, "speed"));
  write(cfg, "dt = fast\n");
  EXPECT_TRUE(Contains(parse_error({"--config", cfg.string()}), "line 1"));
  write(cfg, "overwrite = maybe\n");
  EXPECT_TRUE(Contains(parse_error({"--config", cfg.string()}), "line 1"));
  write(cfg, "config = other.cfg\n");
  EXPECT_TRUE(Contains(parse_error({"--config", cfg.string()}), "cannot be given in a config file"));
  EXPECT_TRUE(Contains(parse_error({"--config", (d.path / "missing.cfg").string()}), "missing.cfg"));
  Cfg c;
  c.dt = std::numeric_limits<double>::infinity();
  EXPECT_THROW(table().require_finite(c), driver::InputError);
}

TEST(DriverOptions, HelpPrintsTheTableAndStops) {
  Cfg c;
  ::testing::internal::CaptureStdout();
  const bool go_on = parse({"--help"}, c);
  const std::string out = ::testing::internal::GetCapturedStdout();
  EXPECT_FALSE(go_on);
  EXPECT_TRUE(Contains(out, "toy — a toy driver"));
  EXPECT_TRUE(Contains(out, "--dt arg (=2e-04)"));  // reals shown exactly (nscd::exact)
  EXPECT_TRUE(Contains(out, "--config FILE"));
}

TEST(DriverOptions, StoredMapRoundTripsThroughACheckpoint) {
  TempDir d;
  Cfg c;
  c.seed = 42;
  c.dt = 0.1;  // not a short decimal in binary: must come back bit for bit
  c.grains = 1234567890123;
  c.guided = true;
  c.cycles = 99;  // Free: not stored
  const auto all = table().to_map(c, false);
  EXPECT_EQ(all, (std::map<std::string, std::string>{{"seed", "42"}, {"dt", "0.1"}, {"grains", "1234567890123"}, {"guided", "1"}}));
  EXPECT_EQ(table().to_map(c, true), (std::map<std::string, std::string>{{"seed", "42"}, {"grains", "1234567890123"}}));
  nscd::scenes::SampleOptions so;
  so.grains = 3;
  nscd::scenes::Scene s = nscd::scenes::paper_sample(so);
  auto extra = all;
  extra["state.cycles_done"] = "3";  // a run's state beside the options: skipped by from_map
  nscd::save_checkpoint(d.path / "cp.nscd", s.reg, {}, extra);
  Cfg back;
  table().from_map(nscd::load_checkpoint(d.path / "cp.nscd").extra, back, "checkpoint");
  EXPECT_EQ(back.seed, 42u);
  EXPECT_EQ(back.dt, 0.1);
  EXPECT_EQ(back.grains, 1234567890123);
  EXPECT_TRUE(back.guided);
  EXPECT_EQ(back.cycles, 30);
  // strict reading: the whole value, in range; the error names the source and the key
  try {
    table().from_map({{"dt", "0.1x"}}, back, "checkpoint 'cp.nscd'");
    ADD_FAILURE() << "no error";
  } catch (const driver::InputError& e) {
    EXPECT_TRUE(Contains(e.what(), "checkpoint 'cp.nscd', key 'dt'"));
  }
  EXPECT_THROW(table().from_map({{"seed", "-1"}}, back, "x"), driver::InputError);
}

TEST(DriverOptions, RefusesChangedOptions) {
  Cfg cli;
  std::set<std::string> given;
  ASSERT_TRUE(parse({"--dt", "1e-4", "--seed", "7", "--cycles", "50"}, cli, &given));
  const std::map<std::string, std::string> stored = {{"seed", "7"}, {"dt", "0.0002"}};
  try {
    table().refuse_changes(cli, given, stored, false, "the resumed run's checkpoint");
    ADD_FAILURE() << "no error";
  } catch (const driver::InputError& e) {
    EXPECT_TRUE(Contains(e.what(), "--dt 1e-04 differs from the resumed run's checkpoint (dt = 0.0002)"));
  }
  // scene_only: the Run option dt is free; the Free option cycles always is
  EXPECT_NO_THROW(table().refuse_changes(cli, given, stored, true, "the sample"));
  // an option the stored map does not record cannot be checked
  ASSERT_TRUE(parse({"--grains", "5"}, cli, &given));
  EXPECT_THROW(table().refuse_changes(cli, given, stored, true, "the sample"), driver::InputError);
}

// ---- run_main ----------------------------------------------------------------------------

struct Outcome {
  int status;
  std::string err;
};

Outcome run_main_with(const std::function<bool(int, char**)>& parse_fn, const std::function<int()>& run_fn) {
  std::string a0 = "toy";
  char* argv[] = {a0.data(), nullptr};
  ::testing::internal::CaptureStderr();
  const int status = driver::run_main("toy", 1, argv, parse_fn, run_fn);
  return {status, ::testing::internal::GetCapturedStderr()};
}

TEST(DriverRunMain, ExitStatuses) {
  auto ok_parse = [](int, char**) { return true; };
  EXPECT_EQ(run_main_with(ok_parse, [] { return 0; }).status, driver::kExitOk);
  EXPECT_EQ(run_main_with([](int, char**) { return false; }, [] { return 1; }).status, driver::kExitOk);  // --help
  // bad options
  const Outcome bad = run_main_with([](int, char**) -> bool { throw driver::InputError("--dt must be > 0"); }, [] { return 0; });
  EXPECT_EQ(bad.status, driver::kExitBadInput);
  EXPECT_EQ(bad.err, "toy: --dt must be > 0 (see --help)\n");
  // a library error while building the scene from the options: bad input too
  const Outcome scene = run_main_with(ok_parse, []() -> int { throw nscd::Error("POLYG of body 0: vertices are clockwise"); });
  EXPECT_EQ(scene.status, driver::kExitBadInput);
  EXPECT_TRUE(Contains(scene.err, "toy: POLYG of body 0"));
  // the same error once the input is accepted: an error of the run
  const Outcome run = run_main_with(ok_parse, []() -> int {
    driver::input_accepted();
    throw nscd::Error("step 12 refused");
  });
  EXPECT_EQ(run.status, driver::kExitRunError);
  EXPECT_EQ(run.err, "toy: error: step 12 refused\n");
  // InputError stays bad input in any phase; the phase starts over with each run_main
  EXPECT_EQ(run_main_with(ok_parse, []() -> int {
              driver::input_accepted();
              throw driver::InputError("--cycles below the cycles done");
            }).status,
            driver::kExitBadInput);
  EXPECT_EQ(run_main_with(ok_parse, []() -> int { throw std::runtime_error("x"); }).status, driver::kExitBadInput);
  EXPECT_EQ(run_main_with(ok_parse, [] { return driver::kExitImpossible; }).status, 3);
  const Outcome stop = run_main_with(ok_parse, []() -> int { throw driver::Interrupted("SIGINT after cycle 4"); });
  EXPECT_EQ(stop.status, driver::kExitInterrupted);
  EXPECT_TRUE(Contains(stop.err, "toy: interrupted: SIGINT after cycle 4"));
}

// ---- settle ------------------------------------------------------------------------------

// A few grains in the paper's box; dt = 1/4096 s so that the simulated times add up exactly.
struct Tiny {
  explicit Tiny(bool gravity) : scene(nscd::scenes::paper_sample(options())), mj(scene.reg, nscd::StepperOptions{}) {
    scene.reg.params.dt = 1.0 / 4096.0;
    if (!gravity) scene.reg.params.gravity = {0.0, 0.0};
  }
  static nscd::scenes::SampleOptions options() {
    nscd::scenes::SampleOptions o;
    o.grains = 6;
    return o;
  }
  driver::SettleResult settle(const driver::SettleRule& rule, std::vector<double>* speeds = nullptr) {
    return driver::settle(scene.reg, scene.grains, rule, [&] { return mj.step(); },
                          [&](const driver::SettleStep& s) {
                            if (speeds) speeds->push_back(s.rms_speed);
                          });
  }
  nscd::scenes::Scene scene;
  nscd::MoreauJean mj;
};

TEST(DriverSettle, AtRestAfterMinTimeAndWindow) {
  Tiny t(false);  // no gravity: the grains never move
  driver::SettleRule rule;
  rule.min_time = 64.0 / 4096.0;  // counted from step 64 on ...
  rule.window = 16.0 / 4096.0;    // ... 16 steps in a row: the 79th step ends it
  const driver::SettleResult r = t.settle(rule);
  EXPECT_TRUE(r.at_rest);
  EXPECT_EQ(r.steps, 79);
  EXPECT_EQ(r.elapsed, 79.0 / 4096.0);
  EXPECT_EQ(r.rms_speed, 0.0);
}

TEST(DriverSettle, FallingGrainsStopAtTheLimits) {
  Tiny t(true);  // the grains fall: never at rest in a few steps
  driver::SettleRule rule;
  rule.max_time = 32.0 / 4096.0;
  std::vector<double> v;
  const driver::SettleResult r = t.settle(rule, &v);
  EXPECT_FALSE(r.at_rest);
  EXPECT_EQ(r.steps, 32);
  ASSERT_EQ(v.size(), 32u);
  EXPECT_GT(v.back(), v.front());  // falling faster and faster
  EXPECT_EQ(r.rms_speed, v.back());
  driver::SettleRule steps;
  steps.max_steps = 10;
  EXPECT_EQ(t.settle(steps).steps, 10);
  // a threshold above the fall's speed: "at rest" after min_time + window
  driver::SettleRule loose;
  loose.speed = 1e3;
  loose.window = 4.0 / 4096.0;
  EXPECT_EQ(t.settle(loose).steps, 4);
  // without the rest rule only the limit stops it
  Tiny still(false);
  driver::SettleRule fixed;
  fixed.stop_at_rest = false;
  fixed.max_steps = 25;
  const driver::SettleResult f = still.settle(fixed);
  EXPECT_FALSE(f.at_rest);
  EXPECT_EQ(f.steps, 25);
}

TEST(DriverSettle, RefusesRulesOutOfRange) {
  Tiny t(false);
  driver::SettleRule no_limit;
  no_limit.stop_at_rest = false;
  EXPECT_THROW(t.settle(no_limit), nscd::Error);
  driver::SettleRule negative;
  negative.window = -1.0;
  EXPECT_THROW(t.settle(negative), nscd::Error);
  EXPECT_EQ(t.scene.reg.step, 0);  // refused before any step
}

// ---- summary -----------------------------------------------------------------------------

TEST(DriverSummary, FormatsAsTheDriversDidAndWritesAtomically) {
  TempDir d;
  driver::Summary s;
  s.add("result", "valid").add("steps", std::int64_t{420}).add("dt", 2e-4).add("mean", 1.0 / 3.0).lines("alert_skip_steps = 0\n");
  const std::string expected = "result = valid\nsteps = 420\ndt = 0.00020000000000000001\nmean = 0.33333333333333331\nalert_skip_steps = 0\n";
  EXPECT_EQ(s.str(), expected);
  s.write(d.path / "summary.txt");
  std::ifstream in(d.path / "summary.txt");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), expected);
  EXPECT_FALSE(fs::exists(d.path / "summary.txt.tmp"));
  fs::create_directories(d.path / "taken" / "x");
  EXPECT_THROW(s.write(d.path / "taken"), nscd::Error);
}

}  // namespace
