// tests/ballast/test_ballast_long_run_cfg.cpp — examples/long_run/long_run.cfg is the default
// run made longer (issue #11): every option that defines the sample or the loading (the load,
// its phase, the time step, the solver, ...) reads back bit for bit as the driver's default, so
// its first cycles are the default run's. Only the options that set the run's length and its
// outputs differ. The phase was once written with 15 digits (-3.14159265358979, not -pi), which
// shifted the load of every step.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "ballast_study.hpp"

namespace {

bool parse_cfg_args(std::vector<std::string> args, ballast::Config& c) {
  args.insert(args.begin(), "ballast");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  return ballast::parse(static_cast<int>(argv.size()), argv.data(), c);
}

TEST(BallastLongRunConfig, DefinesTheDefaultRunBitForBit) {
  ballast::Config cfg, def;
  ASSERT_TRUE(parse_cfg_args({"--config", std::string(NSCD_SOURCE_DIR) + "/examples/long_run/long_run.cfg"}, cfg));
  ASSERT_TRUE(parse_cfg_args({}, def));
  // options that only set how long the run is and what it writes
  const std::set<std::string> length_and_output = {"cycles", "checkpoint-every", "steps-every", "vtk-every", "progress-every",
                                                   "output"};
  const std::map<std::string, std::string> a = ballast::to_map(cfg), b = ballast::to_map(def);
  ASSERT_EQ(a.size(), b.size());
  int compared = 0;
  for (const auto& [key, value] : b) {
    if (length_and_output.count(key)) continue;
    ASSERT_TRUE(a.count(key)) << key;
    EXPECT_EQ(a.at(key), value) << "long_run.cfg sets '" << key << "' differently from the default run";
    ++compared;
  }
  EXPECT_GT(compared, 30);
  EXPECT_EQ(cfg.phase, def.phase);  // the one that drifted, compared as doubles too
  EXPECT_EQ(cfg.cycles, 20000);
}

}  // namespace
