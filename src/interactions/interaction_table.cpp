// nscd/interactions/interaction_table.cpp — see interaction_table.hpp.
#include "nscd/interactions/interaction_table.hpp"

#include <string>

#include "nscd/core/error.hpp"
#include "nscd/interactions/round_pairs.hpp"

namespace nscd {
namespace {

using K = ContactorKind;

ConvexView polygon_at(const Registry& reg, const PlplxDetector& det, std::uint32_t p) {
  return polygon_view(reg, det, p);
}
const DiskView& disk_at(const Registry&, const PlplxDetector& det, std::uint32_t k) { return disk_view(det, k); }
const JoncView& jonc_at(const Registry&, const PlplxDetector& det, std::uint32_t k) { return jonc_view(det, k); }
const RingView& ring_at(const Registry&, const PlplxDetector& det, std::uint32_t k) { return ring_view(det, k); }

// A narrow phase on views (round_pairs.hpp: narrow(antagonist view, candidate view, alert)) as a
// Collide: the antagonist's and the candidate's views fetched by their kinds' getters.
template <auto Narrow, auto AntagonistView, auto CandidateView>
PairContacts on_views(const Registry& r, const PlplxDetector& d, std::uint32_t an, std::uint32_t cd, double alert) {
  return Narrow(AntagonistView(r, d, an), CandidateView(r, d, cd), alert);
}

struct Entry {
  std::string_view name;
  ContactorKind candidate, antagonist;
  Collide collide;  ///< null: handled elsewhere (named in the comment)
};

// THE table: one line per interaction kind.
constexpr Entry kInteractions[] = {
    {"PLPLx", K::POLYG, K::POLYG, nullptr},  // shadow overlap, its own path: plplx.cpp
    {"DKDKx", K::DISKx, K::DISKx, on_views<dkdkx, disk_at, disk_at>},
    {"DKKDx", K::DISKx, K::xKSID, on_views<dkkdx, ring_at, disk_at>},
    {"DKPLx", K::DISKx, K::POLYG, on_views<dkplx, polygon_at, disk_at>},
    {"DKJCx", K::DISKx, K::JONCx, on_views<dkjcx, jonc_at, disk_at>},
    {"PLJCx", K::POLYG, K::JONCx, on_views<pljcx, jonc_at, polygon_at>},
    {"PLKDx", K::POLYG, K::xKSID, on_views<plkdx, ring_at, polygon_at>},
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

// Not constinit: under -fsanitize=undefined GCC does not fold a function pointer's comparison
// with null, so the table is then built at start-up; only detection reads it, after main starts.
const std::array<std::array<Collide, kTouchingKinds>, kTouchingKinds> kCollide = build_collide();

InteractionKind parse_interaction_kind(std::string_view name, std::string_view what) {
  for (const Entry& e : kInteractions)
    if (e.name == name) return {e.candidate, e.antagonist};
  std::string msg = "unknown " + std::string(what) + " name '" + std::string(name) + "'; valid names:";
  for (const Entry& e : kInteractions) msg += " " + std::string(e.name);
  throw Error(msg);
}

std::span<const std::string_view> interaction_names() {
  static constexpr auto kNames = [] {
    std::array<std::string_view, std::size(kInteractions)> n{};
    for (std::size_t i = 0; i < n.size(); ++i) n[i] = kInteractions[i].name;
    return n;
  }();
  return kNames;
}

int interaction_number(InteractionKind k) {
  for (std::size_t i = 0; i < std::size(kInteractions); ++i)
    if (kInteractions[i].candidate == k.candidate && kInteractions[i].antagonist == k.antagonist)
      return static_cast<int>(i);
  return -1;
}

ConvexView polygon_view(const Registry& reg, const PlplxDetector& det, std::uint32_t p) {
  const std::uint32_t f = reg.polyg.first_vertex[p];
  return {&det.world_vertex[f], &det.world_normal[f], reg.polyg.vertex_count[p]};
}

std::array<std::array<Collide, kKindSlots>, kKindSlots> scene_collide(const Registry& reg) {
  std::array<std::array<Collide, kKindSlots>, kKindSlots> t{};
  for (std::size_t i = 0; i < kTouchingKinds; ++i)
    for (std::size_t j = 0; j < kTouchingKinds; ++j) t[i][j] = kCollide[i][j];
  for (const AddedInteraction& a : reg.added.interactions) t[row(a.candidate)][row(a.antagonist)] = a.collide;
  return t;
}

std::vector<std::string_view> interaction_names(const Registry& reg) {
  const auto builtin = interaction_names();
  std::vector<std::string_view> names(builtin.begin(), builtin.end());
  for (const AddedInteraction& a : reg.added.interactions) names.push_back(a.name);
  return names;
}

int interaction_number(const Registry& reg, InteractionKind k) {
  if (const int n = interaction_number(k); n >= 0) return n;
  const auto& added = reg.added.interactions;
  for (std::size_t i = 0; i < added.size(); ++i)
    if (added[i].candidate == k.candidate && added[i].antagonist == k.antagonist)
      return static_cast<int>(std::size(kInteractions) + i);
  return -1;
}

std::string_view name_of(const Registry& reg, InteractionKind k) {
  const int n = interaction_number(reg, k);
  return n < 0 ? std::string_view("?") : interaction_names(reg)[static_cast<std::size_t>(n)];
}

std::string_view name_of(InteractionKind k) {
  for (const Entry& e : kInteractions)
    if (e.candidate == k.candidate && e.antagonist == k.antagonist) return e.name;
  return "?";
}

}  // namespace nscd
