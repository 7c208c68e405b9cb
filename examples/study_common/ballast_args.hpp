// examples/study_common/ballast_args.hpp — what the batch drivers (stiffness_study,
// accuracy_study) need to write ballast commands: the ballast executable and their
// --ballast-option KEY=VALUE strings as ballast arguments.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace study {

/// The ballast executable the batch drivers run: `given` (their --ballast) if not empty,
/// else next to the running program (the same directory when installed, ../ballast/ballast
/// in the build tree). Absolute. Throws std::invalid_argument saying how to give it.
std::filesystem::path find_ballast(const std::string& given);

/// Their --ballast-option KEY=VALUE strings as ballast arguments ("--KEY", "VALUE", ...);
/// throws std::invalid_argument on a string that is not KEY=VALUE.
std::vector<std::string> ballast_option_args(const std::vector<std::string>& key_values);

/// Splits a machine between ballast runs and their threads (issue #37): with `threads` > 1 every
/// ballast command gets `--threads threads` (appended to `args`), `jobs` not given defaults to
/// cores / threads, and a study run here (`local`) whose jobs × threads passes the cores is
/// refused (a plan for other hosts is not). Throws std::invalid_argument, naming the options.
void split_machine(int& jobs, bool jobs_given, int threads, bool local, std::vector<std::string>& args);

/// The sample size options of both studies, passed to the preparations when given.
inline constexpr const char* kSampleSizeOptions[] = {"grading-fraction", "box-width", "pads", "sleeper-width", "pad-height"};

}  // namespace study
