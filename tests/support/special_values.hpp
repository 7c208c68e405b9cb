// tests/support/special_values.hpp — the IEEE special values the tests feed to the checks.
// One definition for every test file, so that the files compile together in a unity build
// (tests/CMakeLists.txt, nscd_test_build_settings).
#pragma once

#include <limits>

namespace nscd::testing_support {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace nscd::testing_support
