// nscd/io/checkpoint_format.hpp — the first line of a checkpoint file, shared by the writer
// (checkpoint.cpp) and the reader (checkpoint_read.cpp); not part of the library's interface.
#pragma once

namespace nscd::checkpoint_format {

inline constexpr const char* kMagic = "nscd-checkpoint";
// Version 3 adds each POLYG's is_big flag and each PTPT2 link's length and normal at its last
// detection, so that a reload gives every table bit for bit (and a link squeezed to zero
// length can be reloaded). Version 2 files are still read: their links take the length and
// normal of the saved configuration, their polygons is_big = 0 (both are recomputed by the
// next step's detection).
// Version 4 adds the round contactors (DISKx, JONCx, xKSID: a "round" section after the
// polygons) and is written only by scenes that hold some: a polygon scene's file stays version 3,
// byte for byte. Warm-start pair keys are ContactorIds (a POLYG's is its index, as before).
// Version 5 adds the contactor kinds a scene added (a "kinds" section after the round one, each
// kind by name with its records) and is written only by scenes that added some.
inline constexpr int kVersion = 5;
inline constexpr int kOldestVersion = 2;

}  // namespace nscd::checkpoint_format
