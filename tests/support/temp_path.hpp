// tests/support/temp_path.hpp — temporary file and folder names that no other test can share.
//
// ctest runs the tests of one binary in parallel processes, and the sanitized copy of the suite
// runs beside the plain one: a fixed name such as /tmp/nscd_test.dat is written, read and removed
// by several tests at once. The name below holds the process id and the running test's suite and
// name, so two tests (or two copies of one test) never meet.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace nscd::testing_support {

/// temp_directory_path()/nscd_<tag>_<pid>_<suite>_<test>: unique to this test in this process.
inline std::filesystem::path unique_temp_path(const std::string& tag) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = "nscd_" + tag + "_" + std::to_string(::getpid());
  if (info != nullptr) name += std::string("_") + info->test_suite_name() + "_" + info->name();
  for (char& c : name)
    if (c == '/') c = '_';  // parameterised tests' names hold '/'
  return std::filesystem::temp_directory_path() / name;
}

}  // namespace nscd::testing_support
