// nscd/interactions/interaction_kind.cpp — the names of the interaction kinds (contact_table.hpp).
#include "nscd/core/name_table.hpp"
#include "nscd/interactions/contact_table.hpp"

namespace nscd {
namespace {

constexpr NameTable<InteractionKind, 7> kInteractions{{{"PLPLx", InteractionKind::PLPLx},
                                                       {"PTPT2", InteractionKind::PTPT2},
                                                       {"DKDKx", InteractionKind::DKDKx},
                                                       {"DKKDx", InteractionKind::DKKDx},
                                                       {"DKPLx", InteractionKind::DKPLx},
                                                       {"DKJCx", InteractionKind::DKJCx},
                                                       {"PLJCx", InteractionKind::PLJCx}}};

}  // namespace

InteractionKind parse_interaction_kind(std::string_view n, std::string_view w) { return parse_name(kInteractions, n, w); }
std::string_view name_of(InteractionKind k) { return name_in(kInteractions, k); }

}  // namespace nscd
