// nscd/contactors/polyg_table.hpp — the POLYG table: convex polygons attached to bodies.
// The functions are in polyg.hpp.
#pragma once

#include <cstdint>
#include <vector>

#include "nscd/core/ids.hpp"
#include "nscd/core/math.hpp"

namespace nscd {

using PolygId = Id<struct PolygTag>;  ///< a POLYG contactor (its ContactorId has the same value)

/// POLYG contactors: convex polygons attached to bodies, vertices counter-clockwise in the
/// body frame (origin = the body's centre of mass).
struct PolygTable {
  std::vector<BodyId> body;
  std::vector<std::uint32_t> first_vertex;  ///< offset into the vertex arrays
  std::vector<std::uint32_t> vertex_count;
  std::vector<double> radius;               ///< max distance of a vertex from the body's centre of mass
  std::vector<std::uint8_t> is_big;         ///< 1: handled outside the grid broad phase (walls)
  std::vector<double> area;
  std::vector<Vec2> centre;                 ///< centroid of the polygon in the body frame
  // vertex arrays (body frame), and the outward unit normal of edge k = (v_k, v_{k+1})
  std::vector<Vec2> vertex;
  std::vector<Vec2> edge_normal;

  std::size_t size() const { return body.size(); }
  bool empty() const { return body.empty(); }
};

}  // namespace nscd
