// nscd/shared/progress.hpp — formatting for the progress lines of long runs (drivers print
// elapsed time and an ETA).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace nscd::scenes {

/// A duration in seconds as "12.3s", "4m05s" or "2h07m"; "?" when it is not finite.
inline std::string format_duration(double s) {
  char b[32];
  if (!std::isfinite(s)) return "?";
  if (s >= 3600) std::snprintf(b, sizeof b, "%dh%02dm", int(s / 3600), int(std::fmod(s, 3600) / 60));
  else if (s >= 60) std::snprintf(b, sizeof b, "%dm%02ds", int(s / 60), int(std::fmod(s, 60)));
  else std::snprintf(b, sizeof b, "%.1fs", s);
  return b;
}

}  // namespace nscd::scenes
