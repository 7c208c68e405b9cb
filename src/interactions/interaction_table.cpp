// nscd/interactions/interaction_table.cpp — see interaction_table.hpp.
#include "nscd/interactions/interaction_table.hpp"

#include <string>

#include "nscd/core/error.hpp"
#include "nscd/interactions/round_pairs.hpp"

namespace nscd {
namespace {

using K = ContactorKind;

ConvexView polygon_view(const Registry& reg, const PlplxDetector& det, std::uint32_t p) {
  const std::uint32_t f = reg.polyg.first_vertex[p];
  return {&det.world_vertex[f], &det.world_normal[f], reg.polyg.vertex_count[p]};
}

// The narrow phases on the detector's world geometry (round_pairs.hpp has the exact geometry).
PairContacts dkdk(const Registry&, const PlplxDetector& d, std::uint32_t an, std::uint32_t cd, double alert) {
  return dkdkx(d.disk[an], d.disk[cd], alert);
}
PairContacts dkkd(const Registry&, const PlplxDetector& d, std::uint32_t an, std::uint32_t cd, double alert) {
  return dkkdx(d.ring[an], d.disk[cd], alert);
}
PairContacts dkpl(const Registry& r, const PlplxDetector& d, std::uint32_t an, std::uint32_t cd, double alert) {
  return dkplx(polygon_view(r, d, an), d.disk[cd], alert);
}
PairContacts dkjc(const Registry&, const PlplxDetector& d, std::uint32_t an, std::uint32_t cd, double alert) {
  return dkjcx(d.jonc[an], d.disk[cd], alert);
}
PairContacts plkd(const Registry& r, const PlplxDetector& d, std::uint32_t an, std::uint32_t cd, double alert) {
  return plkdx(d.ring[an], polygon_view(r, d, cd), alert);
}
PairContacts pljc(const Registry& r, const PlplxDetector& d, std::uint32_t an, std::uint32_t cd, double alert) {
  return pljcx(d.jonc[an], polygon_view(r, d, cd), alert);
}

struct Entry {
  std::string_view name;
  ContactorKind candidate, antagonist;
  Collide collide;  ///< null: handled elsewhere (named in the comment)
};

// THE table: one line per interaction kind.
constexpr Entry kInteractions[] = {
    {"PLPLx", K::POLYG, K::POLYG, nullptr},  // shadow overlap, its own path: plplx.cpp
    {"DKDKx", K::DISKx, K::DISKx, dkdk},
    {"DKKDx", K::DISKx, K::xKSID, dkkd},
    {"DKPLx", K::DISKx, K::POLYG, dkpl},
    {"DKJCx", K::DISKx, K::JONCx, dkjc},
    {"PLJCx", K::POLYG, K::JONCx, pljc},
    {"PLKDx", K::POLYG, K::xKSID, plkd},
    {"PTPT2", K::PT2Dx, K::PT2Dx, nullptr},  // spring links, not detected: ptpt2.cpp
};

constexpr std::size_t row(ContactorKind k) { return static_cast<std::size_t>(k); }

constexpr std::array<std::array<Collide, kTouchingKinds>, kTouchingKinds> build_collide() {
  std::array<std::array<Collide, kTouchingKinds>, kTouchingKinds> t{};
  for (const Entry& e : kInteractions)
    if (e.collide != nullptr) t[row(e.candidate)][row(e.antagonist)] = e.collide;
  return t;
}

// Each pair of kinds has one line at most, in one direction: the roles are never ambiguous.
constexpr bool one_line_per_pair() {
  for (const Entry& a : kInteractions)
    for (const Entry& b : kInteractions)
      if (&a != &b && ((a.candidate == b.candidate && a.antagonist == b.antagonist) ||
                       (a.candidate == b.antagonist && a.antagonist == b.candidate)))
        return false;
  return true;
}
static_assert(one_line_per_pair(), "kInteractions: two lines for the same pair of contactor kinds");

}  // namespace

const std::array<std::array<Collide, kTouchingKinds>, kTouchingKinds> kCollide = build_collide();

InteractionKind parse_interaction_kind(std::string_view name, std::string_view what) {
  for (const Entry& e : kInteractions)
    if (e.name == name) return {e.candidate, e.antagonist};
  std::string msg = "unknown " + std::string(what) + " name '" + std::string(name) + "'; valid names:";
  for (const Entry& e : kInteractions) msg += " " + std::string(e.name);
  throw Error(msg);
}

std::string_view name_of(InteractionKind k) {
  for (const Entry& e : kInteractions)
    if (e.candidate == k.candidate && e.antagonist == k.antagonist) return e.name;
  return "?";
}

}  // namespace nscd
