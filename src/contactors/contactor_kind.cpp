// nscd/contactors/contactor_kind.cpp — see contactor_kind.hpp.
#include "nscd/contactors/contactor_kind.hpp"

#include "nscd/core/name_table.hpp"

namespace nscd {
namespace {

constexpr NameTable<ContactorKind, 5> kContactors{{{"POLYG", ContactorKind::POLYG},
                                                   {"DISKx", ContactorKind::DISKx},
                                                   {"JONCx", ContactorKind::JONCx},
                                                   {"xKSID", ContactorKind::xKSID},
                                                   {"PT2Dx", ContactorKind::PT2Dx}}};

}  // namespace

ContactorKind parse_contactor_kind(std::string_view n, std::string_view w) { return parse_name(kContactors, n, w); }
std::string_view name_of(ContactorKind k) { return name_in(kContactors, k); }

}  // namespace nscd
