// nscd/interactions/round_detection.cpp — see round_detection.hpp.
#include "nscd/interactions/round_detection.hpp"

#include <algorithm>
#include <vector>

#include "nscd/contactors/contactor_row.hpp"
#include "nscd/core/error.hpp"
#include "nscd/interactions/interaction_table.hpp"

namespace nscd {
namespace {

bool kinematic(const BodyTable& b, std::size_t i) {
  return b.inv_mass_x[i] == 0.0 && b.inv_mass_y[i] == 0.0 && b.inv_inertia[i] == 0.0;
}

}  // namespace

ContactorId contactor_of_box(const PlplxDetector& det, std::uint32_t b) {
  std::uint8_t k = 0;
  while (static_cast<std::size_t>(k) + 1 < kKindSlots && b >= det.first_box[k + 1]) ++k;
  return make_contactor(k, b - det.first_box[k]);
}

BodyId body_of(const Registry& reg, ContactorId c) {
  const ContactorKindRow* row = kind_row(reg, contactor_kind_bits(c));
  if (row == nullptr) throw Error("body_of: contactor id " + std::to_string(c.value) + " has no contactor kind");
  return row->body(reg, contactor_index(c));
}

// Each kind's row places its contactors and pushes their boxes, kind after kind.
void round_world_geometry(const Registry& reg, PlplxDetector& det, const Configuration& q) {
  const std::size_t P = reg.polyg.size();
  det.box.resize(P);  // the polygons' boxes are in place (world_geometry)
  det.is_big.assign(reg.polyg.is_big.begin(), reg.polyg.is_big.end());
  if (det.grain_median_count != P + reg.diskx.size()) {  // recomputed only when contactors are added
    det.grain_median = grain_median_radius(reg);
    det.grain_median_count = P + reg.diskx.size();
  }
  KindBoxes boxes{det.box, det.is_big, 0.5 * reg.params.alert, det.big_ratio * det.grain_median};
  det.first_box.fill(static_cast<std::uint32_t>(P));
  det.first_box[0] = 0;
  det.box_body.resize(P);
  for (std::size_t p = 0; p < P; ++p) det.box_body[p] = reg.polyg.body[p].value;
  const std::size_t kinds = kind_count(reg);
  for (std::size_t k = 1; k < kKindSlots; ++k) {
    const ContactorKindRow* row = k < kinds ? kind_row(reg, static_cast<std::uint8_t>(k)) : nullptr;
    if (row != nullptr && row->world != nullptr) {
      row->world(reg, q, det.views[k], boxes);
      for (std::uint32_t i = 0, n = static_cast<std::uint32_t>(row->count(reg)); i < n; ++i)
        det.box_body.push_back(row->body(reg, i).value);
    }
    det.first_box[k + 1] = static_cast<std::uint32_t>(det.box.size());
  }
  if (det.box_body.size() != det.box.size())
    throw Error("round_world_geometry: a kind's row must push one box per contactor");
  det.collide = scene_collide(reg);
}

PairContacts collide_round(const Registry& reg, const PlplxDetector& det, std::uint32_t i, std::uint32_t j,
                           ContactorId& antagonist, ContactorId& candidate) {
  const ContactorId a = contactor_of_box(det, i), b = contactor_of_box(det, j);
  const std::uint8_t ka = contactor_kind_bits(a), kb = contactor_kind_bits(b);
  const std::size_t ba = det.box_body[i], bb = det.box_body[j];
  if (ba == bb || (kinematic(reg.bodies, ba) && kinematic(reg.bodies, bb))) return {};
  if (ka == kb) {  // two of a kind (two polygons never come here): the big one, else box i, is the antagonist
    const bool swap = det.is_big[j] && !det.is_big[i];
    antagonist = swap ? b : a;
    candidate = swap ? a : b;
  } else if (det.collide[ka][kb] != nullptr) {  // the kind whose row of the table has the line is the candidate
    candidate = a, antagonist = b;
  } else {
    candidate = b, antagonist = a;
  }
  const Collide f = det.collide[contactor_kind_bits(candidate)][contactor_kind_bits(antagonist)];
  if (f == nullptr) return {};
  return f(reg, det, contactor_index(antagonist), contactor_index(candidate), reg.params.alert);
}

}  // namespace nscd
