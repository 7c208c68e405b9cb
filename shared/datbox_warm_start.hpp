// nscd/shared/datbox_warm_start.hpp — a DATBOX's Vloc_Rloc.INI as the stepper's warm start
// (issue #39). io reads the file (io/datbox.hpp) but sees no solver; this detects the contacts of
// the read scene once (a copy of it, one MoreauJean detection) and gives each Vloc_Rloc contact's
// force (rl/H) to the detected contact of the same contactor pair nearest to its point.
#pragma once

#include <cstddef>
#include <span>

#include "nscd/interactions/contact_history.hpp"
#include "nscd/io/datbox.hpp"

namespace nscd::scenes {

/// The warm-start memory (MoreauJean::set_warm_start_memory) of `contacts`; `matched` gets how
/// many of them found a contact (the others are left out: their pair is not in alert distance).
ContactHistory datbox_warm_start(const Registry& reg, std::span<const DatboxContact> contacts, std::size_t* matched = nullptr);

}  // namespace nscd::scenes
