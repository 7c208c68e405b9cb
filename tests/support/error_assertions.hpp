// tests/support/error_assertions.hpp — assertions on nscd's error messages, shared by the unit
// tests and the validation cases.
#pragma once

#include <gtest/gtest.h>

#include <exception>
#include <string>

#include "nscd/core/error.hpp"

namespace nscd::testing_support {

/// The message of the nscd::Error that f throws (a test failure if it throws nothing or
/// another exception type).
template <class F>
std::string error_message(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw a std::exception that is not nscd::Error: " << e.what();
    return {};
  }
  ADD_FAILURE() << "did not throw";
  return {};
}

/// Success when `text` contains `part`, with both in the failure message otherwise.
inline ::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "message \"" << text << "\" does not contain \"" << part << "\"";
}

}  // namespace nscd::testing_support
