// tests/support/threads.hpp — whether this build can run the library's loops on several threads.
//
// A test that compares one thread with two compares one thread with itself when the library is
// built without OpenMP (NSCD_USE_OPENMP=OFF, or no OpenMP found), or when the OpenMP runtime is
// limited to one thread (OMP_THREAD_LIMIT=1): it would pass whatever the parallel code does. Such
// a test skips, with NSCD_SKIP_WITHOUT_THREADS(), rather than pass vacuously. The unit tests are
// compiled with OpenMP exactly when the library is (tests/CMakeLists.txt).
#pragma once

#include <gtest/gtest.h>

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

}  // namespace nscd::testing_support

/// Skips the rest of the running test (what it checked so far still counts) when one thread
/// would be compared with itself.
#define NSCD_SKIP_WITHOUT_THREADS()                                                                               \
  do {                                                                                                            \
    if (!::nscd::testing_support::threads_run_in_parallel())                                                      \
      GTEST_SKIP() << "one thread only (built without OpenMP, or OMP_THREAD_LIMIT=1): comparing it with several " \
                      "threads would compare it with itself";                                                     \
  } while (false)
