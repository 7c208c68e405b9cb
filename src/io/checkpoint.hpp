// nscd/io/checkpoint.hpp — a scene's complete state in one text file, to save a prepared sample
// and reuse it, or to resume a killed run bit for bit.
//
// The file holds the parameters, time and step counter, materials, the contact-law table,
// every body (mass, inertia, reference and current configuration, velocity, name, material),
// its boundary conditions, every POLYG's vertices (and big flag), the PT2Dx points and PTPT2
// spring links (with their last forces and frames), and optionally the stepper's warm-start
// memory and a driver's key → value state. The contact points (Registry::plplx) are not saved:
// the next step's detection rebuilds them. Floating-point values are written in hexadecimal
// (std::hexfloat), so a reload gives the very same bits. Files are written atomically: to
// "<file>.tmp", then renamed, so a run killed while writing leaves the previous checkpoint
// intact.
//
// Boundary conditions given by a user lambda (TimeFunction::lambda) cannot be saved: the
// save throws nscd::Error naming the body; re-impose them after loading.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "nscd/core/registry.hpp"
#include "nscd/interactions/contact_history.hpp"

namespace nscd {

struct Checkpoint {
  Registry reg;
  ContactHistory warm_start;                           ///< empty if none was saved
  std::map<std::string, std::string> extra;            ///< a driver's own state (key → value)
};

/// Saves the registry (and the warm-start memory and a driver's key → value state if given).
/// Throws nscd::Error on I/O errors.
void save_checkpoint(const std::filesystem::path& file, const Registry& reg,
                     const ContactHistory& warm_start = {},
                     const std::map<std::string, std::string>& extra = {});

/// Loads a checkpoint (format version 3, or 2). Throws nscd::Error naming the file, the line and
/// what is at fault: a malformed or truncated file, an unsupported version, or data the registry
/// refuses (an unknown id, an invalid polygon, a value out of range).
Checkpoint load_checkpoint(const std::filesystem::path& file);

}  // namespace nscd
