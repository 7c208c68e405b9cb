// nscd/contactors/contactor_kind.cpp — see contactor_kind.hpp: the names are the rows'
// (contactor_row.cpp).
#include "nscd/contactors/contactor_kind.hpp"

#include <string>

#include "nscd/contactors/contactor_row.hpp"
#include "nscd/core/error.hpp"

namespace nscd {

ContactorKind parse_contactor_kind(std::string_view n, std::string_view w) {
  const auto rows = builtin_kind_rows();
  for (std::size_t k = 0; k < rows.size(); ++k)
    if (rows[k]->name == n) return static_cast<ContactorKind>(k);
  std::string msg = "unknown " + std::string(w) + " name '" + std::string(n) + "'; valid names:";
  for (const ContactorKindRow* r : rows) msg += " " + std::string(r->name);
  throw Error(msg);
}

std::string_view name_of(ContactorKind k) {
  const auto rows = builtin_kind_rows();
  const auto i = static_cast<std::size_t>(k);
  return i < rows.size() ? rows[i]->name : std::string_view("?");
}

}  // namespace nscd
