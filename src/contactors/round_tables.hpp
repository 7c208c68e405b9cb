// nscd/contactors/round_tables.hpp — the tables of the round contactors: DISKx (disks), JONCx
// (LMGC90's "jonc": a thickened segment, for walls) and xKSID (the inside of a ring, for drums).
// The functions are in round_shapes.hpp.
#pragma once

#include <vector>

#include "nscd/core/ids.hpp"
#include "nscd/core/math.hpp"

namespace nscd {

using DiskxId = Id<struct DiskxTag>;  ///< a DISKx contactor
using JoncxId = Id<struct JoncxTag>;  ///< a JONCx contactor
using XksidId = Id<struct XksidTag>;  ///< an xKSID contactor

/// DISKx contactors: disks attached to bodies, centre given in the body frame.
struct DiskxTable {
  std::vector<BodyId> body;
  std::vector<Vec2> offset;     ///< the disk's centre in the body frame
  std::vector<double> radius;
  std::size_t size() const { return body.size(); }
  bool empty() const { return body.empty(); }
};

/// JONCx contactors (walls): the segment offset ± half_length · axis in the body frame,
/// thickened by half_thickness (round ends).
struct JoncxTable {
  std::vector<BodyId> body;
  std::vector<Vec2> offset;     ///< the segment's centre in the body frame
  std::vector<Vec2> axis;       ///< unit, in the body frame
  std::vector<double> half_length, half_thickness;
  std::size_t size() const { return body.size(); }
  bool empty() const { return body.empty(); }
};

/// xKSID contactors: the disk-shaped hole of a ring (a drum), centre in the body frame; what
/// touches it stays inside.
struct XksidTable {
  std::vector<BodyId> body;
  std::vector<Vec2> offset;
  std::vector<double> radius;   ///< inner radius
  std::size_t size() const { return body.size(); }
  bool empty() const { return body.empty(); }
};

}  // namespace nscd
