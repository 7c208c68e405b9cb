// nscd/core/own_line.hpp — a value on cache lines of its own, for arrays of per-thread values.
#pragma once

namespace nscd {

/// One thread's list or counts among the other threads' in an array, alone on its cache lines,
/// so that a thread writing its own never writes a line another thread writes: two vectors'
/// headers side by side share a line, and each push_back would take it from the other core.
template <class T>
struct alignas(64) OwnLine {
  T v;
};

}  // namespace nscd
