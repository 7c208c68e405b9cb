// examples/stiffness_study/study_config.hpp — the stiffness study's options, its plan (one
// preparation per sample, one run per sample and k factor) and its gathering.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "../study_common/plan.hpp"

namespace stiffness {

struct Config {
  int samples = 8;
  std::uint64_t seed = 2006;
  std::string k_factors = "1,100,1000";
  int cycles = 3000;
  int jobs = 1;
  int threads = 1;                 ///< --threads of every ballast command
  std::string ballast;
  std::string output = "out/stiffness_study";
  std::string gather;              ///< --gather DIR: only gather the runs of the plan in DIR
  int vtk_every = 0;
  bool plan_only = false, dry_run = false, fresh = false, allow_missing = false;
  double grading_fraction = 1.0;   ///< for the cost model (the sample's grains)
  int steps_per_cycle = 250;       ///< for the cost model: 1/(f dt) with the ballast options given
  std::vector<std::string> prepare_args;  ///< the sample size options given, as ballast arguments
  std::vector<std::string> extra_args;    ///< --ballast-option KEY=VALUE, for every ballast command
  std::vector<double> k;                  ///< parsed k_factors
  std::string grading_fraction_arg, box_width, pads, sleeper_width, pad_height;  ///< passed through when given
  std::vector<std::string> ballast_options;  ///< --ballast-option KEY=VALUE, as given
};

/// Parses the command line and --config; returns false after --help; throws driver::InputError.
bool parse(int argc, char** argv, Config& c);

/// The study as a plan in c.output (absolute): sample_S preparations, k<F>_s<S> runs.
study::Plan make_plan(const Config& c, const std::filesystem::path& ballast);

/// Gathers the runs listed in DIR/manifest.csv into DIR/settlement_by_k.csv and
/// DIR/summary.txt and prints the table; `wall` (s, < 0: unknown) goes into the summary.
/// Returns the exit status: 0, or 1 when a task is not done (without --allow-missing, nothing
/// is averaged then) or a cycles.csv cannot be read.
int gather(const std::filesystem::path& dir, bool allow_missing, double wall);

}  // namespace stiffness
