// nscd/registry/registry.hpp — the central registry: one plain struct that owns every table of
// a scene (LMGC90's "model" in one place).
//
// Each module declares its own tables next to its functions — bodies/body_table.hpp (RBDY2,
// materials), contactors/polyg_table.hpp, round_tables.hpp and pt2dx_table.hpp (POLYG, DISKx,
// JONCx, xKSID, PT2Dx), laws/law_table.hpp (contact laws, the see table), interactions/
// contact_table.hpp and ptpt2_table.hpp (the one contact table, the PTPT2 links) — and this
// aggregate only gathers them: core knows no contactor, law or interaction by name. The module
// functions take the registry by reference; there are no singletons and no self-registration: a
// driver builds a Registry, fills it through the module functions, and steps it.
//
// Tables are structures of arrays: the hot per-step state in contiguous arrays, the cold data
// apart. A kind of contactor or interaction the scene does not use is an empty table and costs
// nothing: the step loops only over the kinds that hold something.
//
// Adding a contactor kind: its row (contactors/contactor_row.hpp) and its table; a built-in kind's
// table is a member here, a scene's own kind is added at run time (add_contactor_kind) and its
// table lives in `added`. Adding an interaction between two kinds: its narrow-phase function and
// one line of the interaction table (interactions/interaction_table.cpp), or add_interaction for a
// scene's own; the stepper, the solvers, VTK, checkpoints and the analysis do not change.
#pragma once

#include <cstdint>
#include <span>

#include "nscd/bodies/body_table.hpp"
#include "nscd/contactors/contactor_kind.hpp"
#include "nscd/contactors/kind_table.hpp"
#include "nscd/contactors/polyg_table.hpp"
#include "nscd/contactors/pt2dx_table.hpp"
#include "nscd/contactors/round_tables.hpp"
#include "nscd/core/parameters.hpp"
#include "nscd/interactions/contact_table.hpp"
#include "nscd/interactions/ptpt2_table.hpp"
#include "nscd/laws/law_table.hpp"
#include "nscd/laws/material_pairs.hpp"

namespace nscd {

/// The central registry of a scene.
struct Registry {
  Parameters params;
  double time = 0.0;
  std::int64_t step = 0;

  MaterialTable materials;
  ContactLawTable contact_laws;
  BodyTable bodies;
  PolygTable polyg;
  DiskxTable diskx;
  JoncxTable joncx;
  XksidTable xksid;
  Pt2dxTable points;
  ContactTable contacts;  ///< every contact point, all contactor pairs
  Ptpt2Table links;
  AddedKinds added;  ///< the contactor kinds and interactions this scene adds (kind_table.hpp)
};

/// A configuration of all bodies (centre of mass and angle); by default the registry's.
struct Configuration {
  std::span<const double> x, y, angle;
  static Configuration of(const Registry& reg) { return {reg.bodies.x, reg.bodies.y, reg.bodies.angle}; }
};

}  // namespace nscd
