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

/// The sample size options of both studies, passed to the preparations when given.
inline constexpr const char* kSampleSizeOptions[] = {"grading-fraction", "box-width", "pads", "sleeper-width", "pad-height"};

}  // namespace study
