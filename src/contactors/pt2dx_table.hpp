// nscd/contactors/pt2dx_table.hpp — the PT2Dx table: points attached to bodies (the anchors of
// spring links). The functions are in pt2dx.hpp.
#pragma once

#include <vector>

#include "nscd/core/ids.hpp"
#include "nscd/core/math.hpp"

namespace nscd {

using PointId = Id<struct PointTag>;  ///< a PT2Dx point contactor (spring anchor)

/// PT2Dx: point contactors attached to bodies, in the body frame.
struct Pt2dxTable {
  std::vector<BodyId> body;
  std::vector<Vec2> point;  ///< body frame (origin = centre of mass)
  std::size_t size() const { return body.size(); }
  bool empty() const { return body.empty(); }
};

}  // namespace nscd
