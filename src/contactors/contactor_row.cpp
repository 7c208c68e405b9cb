// nscd/contactors/contactor_row.cpp — see contactor_row.hpp: the table of the built-in kinds, and
// the kinds and interactions a scene adds.
#include "nscd/contactors/contactor_row.hpp"

#include <string>

#include "nscd/registry/registry.hpp"

namespace nscd {

// Each built-in kind's row is defined in its own file.
extern const ContactorKindRow kPolygRow;  // polyg.cpp
extern const ContactorKindRow kDiskxRow;  // diskx_kind.cpp
extern const ContactorKindRow kJoncxRow;  // joncx_kind.cpp
extern const ContactorKindRow kXksidRow;  // xksid_kind.cpp
extern const ContactorKindRow kPt2dxRow;  // pt2dx.cpp

namespace {

// THE table of the built-in kinds, in ContactorKind order: one line per kind.
constexpr const ContactorKindRow* kBuiltin[] = {&kPolygRow, &kDiskxRow, &kJoncxRow, &kXksidRow, &kPt2dxRow};
static_assert(std::size(kBuiltin) == kFirstAddedKind, "kBuiltin: one row per built-in ContactorKind");

std::string kind_text(std::uint8_t k) { return std::to_string(static_cast<int>(k)); }

}  // namespace

std::span<const ContactorKindRow* const> builtin_kind_rows() { return kBuiltin; }

const ContactorKindRow* kind_row(const Registry& reg, std::uint8_t k) {
  if (k < kFirstAddedKind) return kBuiltin[k];
  const std::size_t a = k - kFirstAddedKind;
  return a < reg.added.size() ? reg.added.row[a] : nullptr;
}

std::size_t kind_count(const Registry& reg) { return kFirstAddedKind + reg.added.size(); }

std::string_view kind_name(const Registry& reg, std::uint8_t k) {
  const ContactorKindRow* r = kind_row(reg, k);
  return r != nullptr ? r->name : std::string_view("?");
}

ContactorKind add_contactor_kind(Registry& reg, const ContactorKindRow& row) {
  const std::string who = "add_contactor_kind '" + std::string(row.name) + "'";
  if (row.count == nullptr || row.body == nullptr || row.new_table == nullptr)
    throw Error(who + ": the row needs count, body and new_table");
  if (row.save != nullptr && row.load == nullptr) throw Error(who + ": a row that saves must also load");
  for (std::size_t k = 0; k < kind_count(reg); ++k)
    if (kind_name(reg, static_cast<std::uint8_t>(k)) == row.name) throw Error(who + ": the name is taken");
  if (kind_count(reg) >= kKindSlots)
    throw Error(who + ": a scene holds at most " + std::to_string(kKindSlots - kFirstAddedKind) + " added kinds");
  reg.added.row.push_back(&row);
  reg.added.table.push_back(row.new_table());
  return static_cast<ContactorKind>(kind_count(reg) - 1);
}

void add_interaction(Registry& reg, const AddedInteraction& line) {
  const std::string who = "add_interaction '" + std::string(line.name) + "'";
  const auto cd = static_cast<std::uint8_t>(line.candidate), an = static_cast<std::uint8_t>(line.antagonist);
  for (std::uint8_t k : {cd, an})
    if (kind_row(reg, k) == nullptr || k == static_cast<std::uint8_t>(ContactorKind::PT2Dx))
      throw Error(who + ": kind " + kind_text(k) + " is not a kind of contactor that touches");
  if (cd < kFirstAddedKind && an < kFirstAddedKind)
    throw Error(who + ": both kinds are built in; their interactions are the built-in table's");
  if (line.collide == nullptr) throw Error(who + ": no narrow phase");
  for (const AddedInteraction& o : reg.added.interactions) {
    if (o.name == line.name) throw Error(who + ": the name is taken");
    if ((o.candidate == line.candidate && o.antagonist == line.antagonist) ||
        (o.candidate == line.antagonist && o.antagonist == line.candidate))
      throw Error(who + ": " + std::string(o.name) + " is already the interaction of these two kinds");
  }
  reg.added.interactions.push_back(line);
}

std::any& added_table_any(Registry& reg, ContactorKind k) {
  return const_cast<std::any&>(added_table_any(static_cast<const Registry&>(reg), k));
}

const std::any& added_table_any(const Registry& reg, ContactorKind k) {
  const auto n = static_cast<std::uint8_t>(k);
  if (n < kFirstAddedKind || static_cast<std::size_t>(n - kFirstAddedKind) >= reg.added.size())
    throw Error("added_table: kind " + kind_text(n) + " is not a kind this scene added");
  return reg.added.table[n - kFirstAddedKind];
}

}  // namespace nscd
