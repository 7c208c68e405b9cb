// examples/settle_demo/main.cpp — a driver on one page: N grains of the paper's grading dropped
// in a box and stepped until at rest, on the drivers' toolkit (shared/driver/). It is the
// example of docs/user-guide.md §4.3, quoted there whole (a ctest keeps the two the same).
//   build/examples/settle_demo/settle_demo --grains 100 --output out/settle_demo
//   build/examples/settle_demo/settle_demo --help
#include <cstdio>
#include <string>

#include "nscd/shared/analysis.hpp"
#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/run_main.hpp"
#include "nscd/shared/driver/settle.hpp"
#include "nscd/shared/driver/summary.hpp"
#include "nscd/shared/driver_checks.hpp"
#include "nscd/shared/samples.hpp"
#include "nscd/solvers/moreau_jean.hpp"

using namespace nscd;

struct Config {  // every parameter, with its default
  std::int64_t grains = 100;
  std::uint64_t seed = 2006;
  double dt = 2e-4;
  double speed = 1e-3;     // at rest: rms speed below this (m/s) ...
  double window = 0.05;    // ... for this long (s)
  double max_time = 2.0;   // simulated time limit (s)
  std::string output = "out/settle_demo";
  bool overwrite = false;
};

// One row per option: name, member, help; Kind::Scene/Run options would go into checkpoints.
const driver::OptionTable<Config> kOptions(
    "settle_demo", "grains of the paper's grading dropped in a box until at rest",
    {{"grains", &Config::grains, "number of grains, in [1, 10000]"},
     {"seed", &Config::seed, "random seed of the grading and orientations"},
     {"dt", &Config::dt, "time step (s)"},
     {"speed", &Config::speed, "at rest: rms grain speed below this (m/s)"},
     {"window", &Config::window, "... for this long (s)"},
     {"max-time", &Config::max_time, "simulated time limit (s)"},
     {"output", &Config::output, "output folder"},
     {"overwrite", &Config::overwrite, "replace an earlier run in --output", driver::Kind::Free, driver::kSwitch}});

bool parse(int argc, char** argv, Config& c) {
  if (!kOptions.parse(argc, argv, c)) return false;  // --help printed
  kOptions.require_finite(c);
  using driver::require;
  require(c.grains >= 1 && c.grains <= 10000, "--grains must lie in [1, 10000], got " + std::to_string(c.grains));
  require(c.dt > 0 && c.speed > 0 && c.window >= 0 && c.max_time > 0, "--dt, --speed, --max-time must be > 0, --window >= 0");
  return true;
}

int run(const Config& c) {
  scenes::claim_output_folder(c.output, {"summary.txt"}, c.overwrite, false);
  scenes::SampleOptions so;
  so.grains = static_cast<std::size_t>(c.grains);
  so.seed = c.seed;
  so.box_width = scenes::scaled_box_width(so.grains);
  scenes::Scene s = scenes::paper_sample(so);
  s.reg.params.dt = c.dt;
  MoreauJean mj(s.reg, StepperOptions{});
  driver::input_accepted();  // from here an error is the run's (exit 1), not bad input (exit 2)

  driver::SettleRule rule;
  rule.speed = c.speed;
  rule.window = c.window;
  rule.max_time = c.max_time;
  const driver::SettleResult r = driver::settle(s.reg, s.grains, rule, [&] { return mj.step(); });
  std::printf("settle_demo: %zu grains %s after %lld steps (%.3f s), rms speed %.2e m/s\n", s.grains.size(),
              r.at_rest ? "at rest" : "NOT at rest", static_cast<long long>(r.steps), r.elapsed, r.rms_speed);

  driver::Summary sum;
  sum.add("grains", s.grains.size()).add("at_rest", r.at_rest ? 1 : 0).add("steps", r.steps).add("simulated_time", r.elapsed);
  sum.add("rms_speed", r.rms_speed).add("coordination_number", scenes::contact_network(s.reg, s.grains).coordination_number);
  sum.write(c.output + "/summary.txt");
  return driver::kExitOk;  // (a result that cannot be would return driver::kExitImpossible, having said why)
}

int main(int argc, char** argv) { return driver::run_main("settle_demo", argc, argv, Config{}, parse, run); }
