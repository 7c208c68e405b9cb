// tests/support/threads.hpp — whether this build can run the library's loops on several threads.
//
// A test that compares one thread with two compares one thread with itself when the library is
// built without OpenMP (NSCD_USE_OPENMP=OFF, or no OpenMP found), or when the OpenMP runtime is
// limited to one thread (OMP_THREAD_LIMIT=1): it would pass whatever the parallel code does. Such
// a test skips, with NSCD_SKIP_WITHOUT_THREADS(), rather than pass vacuously. The unit tests are
// compiled with OpenMP exactly when the library is (tests/CMakeLists.txt).
//
// ctest gives both cores (PROCESSORS 2) to the tests whose name says Thread (tests/CMakeLists.txt):
// two threads beside a third test wait for each other several times longer. The macro fails a
// test that runs threads without saying so in its name, so that no such test slips out of it.
#pragma once

#include <gtest/gtest.h>

#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace nscd::testing_support {

/// True when a parallel region asked for two threads can get them.
inline bool threads_run_in_parallel() {
#ifdef _OPENMP
  return omp_get_thread_limit() >= 2;
#else
  return false;
#endif
}

/// Fails the running test unless its full name (suite.test) says Thread.
inline void expect_thread_in_name() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string name = std::string(info->test_suite_name()) + "." + info->name();
  if (name.find("Thread") == std::string::npos)
    ADD_FAILURE() << name
                  << " runs two threads, but its name does not say Thread: ctest would not give it both "
                     "cores (tests/CMakeLists.txt)";
}

}  // namespace nscd::testing_support

/// Skips the rest of the running test (what it checked so far still counts) when one thread
/// would be compared with itself; fails it when its name does not say Thread.
#define NSCD_SKIP_WITHOUT_THREADS()                                                                               \
  do {                                                                                                            \
    ::nscd::testing_support::expect_thread_in_name();                                                             \
    if (!::nscd::testing_support::threads_run_in_parallel())                                                      \
      GTEST_SKIP() << "one thread only (built without OpenMP, or OMP_THREAD_LIMIT=1): comparing it with several " \
                      "threads would compare it with itself";                                                     \
  } while (false)
