// nscd/interactions/contact_history.hpp — what a contact remembers from one step to the next:
// its force, keyed by the contactor pair and the touching features (the warm-start memory).
//
// It belongs to the interactions, not to a solver: any solver starts from it (NLGS applies
// it before sweeping, NEWTON_AC takes it as its first iterate), the stepper refreshes it at
// the end of every step, and checkpoints save it so that a resumed run continues bit for bit.
#pragma once

#include <cstdint>
#include <vector>

#include "nscd/core/ids.hpp"

namespace nscd {

/// One remembered contact: forces (N per unit thickness) of the pair's contact at `feature`.
struct ContactMemory {
  std::uint64_t pair = 0;     ///< candidate ContactorId << 32 | antagonist ContactorId
  std::uint32_t feature = 0;  ///< which vertices / edges touch (ContactTable::feature)
  double rn = 0.0, rt = 0.0;
  bool operator<(const ContactMemory& o) const { return pair != o.pair ? pair < o.pair : feature < o.feature; }
};

/// The memory of a whole step, sorted by (pair, feature) for binary search.
using ContactHistory = std::vector<ContactMemory>;

inline std::uint64_t contact_pair_key(ContactorId candidate, ContactorId antagonist) {
  return (std::uint64_t(candidate.value) << 32) | antagonist.value;
}

}  // namespace nscd
