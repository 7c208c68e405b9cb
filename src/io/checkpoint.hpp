// nscd/io/checkpoint.hpp — a scene's complete state in one text file, to save a prepared sample
// and reuse it, or to resume a killed run bit for bit.
//
// The file holds the parameters, time and step counter, materials, the contact-law table,
// every body (mass, inertia, reference and current configuration, velocity, name, material),
// its boundary conditions, every POLYG's vertices (and big flag), the PT2Dx points and PTPT2
// spring links (with their last forces and frames), and optionally the stepper's warm-start
// memory and a driver's key → value state. The contact points (Registry::contacts) are not saved:
// the next step's detection rebuilds them. Floating-point values are written in hexadecimal
// (std::hexfloat), so a reload gives the very same bits. Files are written atomically: to
// "<file>.tmp", then renamed, so a run killed while writing leaves the previous checkpoint
// intact.
//
// Boundary conditions given by a user lambda (TimeFunction::lambda) cannot be saved: the
// save throws nscd::Error naming the body; re-impose them after loading.
//
// What the reader accepts (anything else is refused with the file, the line and the rule,
// always as nscd::Error; nothing in a file can crash the program):
//   * one record per line: its tag, then exactly its fields (a missing or an extra field is a
//     wrong count); the sections in the writer's order, each once; nothing after "end";
//   * numbers read whole and strictly (text_reader.hpp): finite, and within the limits below
//     (so that no later product or square overflows); integers and indices within range, ids
//     naming existing materials, bodies, POLYGs and points;
//   * what the registry itself refuses (mass or inertia <= 0, a non-convex polygon, dt <= 0,
//     θ outside [0.5, 1], μ < 0, ...), named with the line it came from;
//   * the warm-start memory sorted by (pair, feature), each entry once, its POLYGs existing.
// save_checkpoint refuses (nscd::Error, nothing written) a state that the reader would refuse:
// a NaN or an infinite value anywhere, a value beyond the limits.
#pragma once

#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "nscd/registry/registry.hpp"
#include "nscd/interactions/contact_history.hpp"

namespace nscd {

/// Limits of the values in a checkpoint (SI units): beyond them a state is refused as
/// out of range, whatever produced it.
inline constexpr double kMaxMagnitude = 1e100;  ///< any real (densities, masses, stiffnesses, ...)
inline constexpr double kMaxLength = 1e9;       ///< m: positions, vertices, points, lengths
inline constexpr double kMaxAngle = 1e12;       ///< rad (an angle accumulates over turns)
inline constexpr double kMaxSpeed = 1e6;        ///< m/s
inline constexpr double kMaxSpin = 1e9;         ///< rad/s
inline constexpr double kMaxForce = 1e15;       ///< N/m: contact forces of the warm start, spring forces
inline constexpr double kMaxTime = 1e15;        ///< s
inline constexpr double kMinMass = 1e-30;       ///< kg/m and kg·m²/m: masses and inertias (1/m must stay finite)

struct Checkpoint {
  Registry reg;
  ContactHistory warm_start;                           ///< empty if none was saved
  std::map<std::string, std::string> extra;            ///< a driver's own state (key → value)
};

/// Saves the registry (and the warm-start memory and a driver's key → value state if given).
/// Throws nscd::Error on I/O errors and on a state the reader would refuse (see above).
void save_checkpoint(const std::filesystem::path& file, const Registry& reg,
                     const ContactHistory& warm_start = {},
                     const std::map<std::string, std::string>& extra = {});

/// Loads a checkpoint (format version 2 to 5). Throws nscd::Error naming the file, the line and
/// what is at fault: a malformed or truncated file, an unsupported version, or data the registry
/// refuses (an unknown id, an invalid polygon, a value out of range).
/// A checkpoint of a scene that added contactor kinds (version 5) loads when `kinds` holds their
/// rows, in the order the scene added them (Registry::added.row); a missing one is named.
Checkpoint load_checkpoint(const std::filesystem::path& file, std::span<const ContactorKindRow* const> kinds = {});

/// The same on a checkpoint's text (the fuzzers, tests); `name` stands for the file in errors.
Checkpoint load_checkpoint_text(const std::string& text, const std::string& name,
                                std::span<const ContactorKindRow* const> kinds = {});

}  // namespace nscd
