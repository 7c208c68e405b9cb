// nscd/interactions/round_detection.cpp — see round_detection.hpp.
#include "nscd/interactions/round_detection.hpp"

#include <algorithm>
#include <vector>

#include "nscd/core/error.hpp"
#include "nscd/interactions/interaction_table.hpp"

namespace nscd {
namespace {

constexpr std::uint8_t kPL = static_cast<std::uint8_t>(ContactorKind::POLYG);
constexpr std::uint8_t kDK = static_cast<std::uint8_t>(ContactorKind::DISKx);
constexpr std::uint8_t kJC = static_cast<std::uint8_t>(ContactorKind::JONCx);
constexpr std::uint8_t kKD = static_cast<std::uint8_t>(ContactorKind::xKSID);

// Which kind is the candidate when two kinds meet (the row of kCollide that has the entry).
bool candidate_first(std::uint8_t a, std::uint8_t b) { return kCollide[a][b] != nullptr; }

bool kinematic(const BodyTable& b, std::size_t i) {
  return b.inv_mass_x[i] == 0.0 && b.inv_mass_y[i] == 0.0 && b.inv_inertia[i] == 0.0;
}

}  // namespace

ContactorId contactor_of_box(const Registry& reg, std::uint32_t b) {
  const auto P = static_cast<std::uint32_t>(reg.polyg.size()), D = static_cast<std::uint32_t>(reg.diskx.size()),
             J = static_cast<std::uint32_t>(reg.joncx.size());
  if (b < P) return make_contactor(kPL, b);
  if (b < P + D) return make_contactor(kDK, b - P);
  if (b < P + D + J) return make_contactor(kJC, b - P - D);
  return make_contactor(kKD, b - P - D - J);
}

BodyId body_of(const Registry& reg, ContactorId c) {
  const std::uint32_t i = contactor_index(c);
  switch (contactor_kind_bits(c)) {
    case kPL: return reg.polyg.body[i];
    case kDK: return reg.diskx.body[i];
    case kJC: return reg.joncx.body[i];
    case kKD: return reg.xksid.body[i];
    default: throw Error("body_of: contactor id " + std::to_string(c.value) + " has no contactor kind");
  }
}

void round_world_geometry(const Registry& reg, PlplxDetector& det, const Configuration& q) {
  const double half_alert = 0.5 * reg.params.alert;
  const std::size_t P = reg.polyg.size();
  det.box.resize(P);  // the polygons' boxes are in place (world_geometry)
  det.is_big.assign(reg.polyg.is_big.begin(), reg.polyg.is_big.end());
  if (det.grain_median_count != P + reg.diskx.size()) {  // recomputed only when contactors are added
    det.grain_median = grain_median_radius(reg);
    det.grain_median_count = P + reg.diskx.size();
  }
  const double big = det.big_ratio * det.grain_median;
  auto place = [&](BodyId body, Vec2 offset) {
    const std::size_t b = body.index();
    return std::pair{Vec2{q.x[b], q.y[b]} + Rot2::of(q.angle[b]).apply(offset), Rot2::of(q.angle[b])};
  };
  auto push_box = [&](Vec2 lo, Vec2 hi, bool is_big) {
    det.box.push_back({lo.x - half_alert, lo.y - half_alert, hi.x + half_alert, hi.y + half_alert});
    det.is_big.push_back(is_big ? 1 : 0);
  };
  auto push_circle = [&](Vec2 c, double r, bool is_big) { push_box({c.x - r, c.y - r}, {c.x + r, c.y + r}, is_big); };
  const DiskxTable& dk = reg.diskx;
  det.disk.resize(dk.size());
  for (std::size_t k = 0; k < dk.size(); ++k) {
    det.disk[k] = {place(dk.body[k], dk.offset[k]).first, dk.radius[k]};
    push_circle(det.disk[k].centre, dk.radius[k], big > 0.0 && dk.radius[k] > big);
  }
  const JoncxTable& jc = reg.joncx;
  det.jonc.resize(jc.size());
  for (std::size_t k = 0; k < jc.size(); ++k) {
    const auto [c, R] = place(jc.body[k], jc.offset[k]);
    const JoncView j{c, R.apply(jc.axis[k]), jc.half_length[k], jc.half_thickness[k]};
    det.jonc[k] = j;
    const Vec2 e = j.half_length * j.axis;
    const double b = j.half_thickness;
    push_box({std::min(c.x - e.x, c.x + e.x) - b, std::min(c.y - e.y, c.y + e.y) - b},
             {std::max(c.x - e.x, c.x + e.x) + b, std::max(c.y - e.y, c.y + e.y) + b},
             big > 0.0 && j.half_length + b > big);
  }
  const XksidTable& kd = reg.xksid;
  det.ring.resize(kd.size());
  for (std::size_t k = 0; k < kd.size(); ++k) {
    det.ring[k] = {place(kd.body[k], kd.offset[k]).first, kd.radius[k]};
    push_circle(det.ring[k].centre, kd.radius[k], true);  // the whole drum: never in the grid
  }
}

PairContacts collide_round(const Registry& reg, const PlplxDetector& det, std::uint32_t i, std::uint32_t j,
                           ContactorId& antagonist, ContactorId& candidate) {
  const ContactorId a = contactor_of_box(reg, i), b = contactor_of_box(reg, j);
  const std::uint8_t ka = contactor_kind_bits(a), kb = contactor_kind_bits(b);
  const std::size_t ba = body_of(reg, a).index(), bb = body_of(reg, b).index();
  if (ba == bb || (kinematic(reg.bodies, ba) && kinematic(reg.bodies, bb))) return {};
  if (ka == kb) {  // two disks (two polygons never come here): the big one, else box i, is the antagonist
    const bool swap = det.is_big[j] && !det.is_big[i];
    antagonist = swap ? b : a;
    candidate = swap ? a : b;
  } else if (candidate_first(ka, kb)) {
    candidate = a, antagonist = b;
  } else {
    candidate = b, antagonist = a;
  }
  const Collide f = kCollide[contactor_kind_bits(candidate)][contactor_kind_bits(antagonist)];  // one line of the table
  if (f == nullptr) return {};
  return f(reg, det, contactor_index(antagonist), contactor_index(candidate), reg.params.alert);
}

}  // namespace nscd
