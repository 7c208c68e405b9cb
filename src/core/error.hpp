// nscd/core/error.hpp — the one exception type nscd throws on bad input.
//
// Every message names the object at fault (a body, a contactor, an option) and the defect,
// so a researcher can fix the input without reading the source.
#pragma once

#include <stdexcept>
#include <string>

namespace nscd {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace nscd
