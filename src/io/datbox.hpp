// nscd/io/datbox.hpp — LMGC90's DATBOX folder, its 2D rigid subset (issue #39): read into a
// Registry, and written back so that LMGC90 reads it.
//
// Files (formats: LMGC90's Fortran readers mod_RBDY2.f90, mod_a_BDARY_*.f90, mod_bulk_behav.f90,
// mod_tact_behav.f90, mod_a_DOF.f90, mod_DKDKx.f90 …, and the pre-processor's writers
// pylmgc90/pre/IO/*2File.py; see docs/user-guide.md §8 for what is read and how):
//   BODIES.DAT      RBDY2 bodies: PLAIN (behav, avrd, gyrd), NO3xx (coo1..3), contactors
//                   DISKx (byrd), JONCx (axe1, axe2), xKSID (byrd), PT2Dx (coo1, coo2),
//                   POLYG (nb_vertex, then coo1, coo2 per vertex) with their colours;
//   BULK_BEHAV.DAT  gravity ($gravy) and RIGID materials (Umas);
//   TACT_BEHAV.DAT  IQS_CLB, GAP_SGR_CLB (fric), RST_CLB (rstn, rstt, fric) and the see table;
//   DRV_DOF.DAT     imposed velocities (vlocy) and forces (force), [CT + AMP cos(OMEGA t + PHI)]
//                   · min(1, RAMPI + RAMP t) or 'evolution FILE' (two columns t, f(t));
//   DOF.INI         displacements X(1..3) from the NO3xx coordinates and velocities V(1..3)
//                   (optional);
//   Vloc_Rloc.INI   contact impulses of DKDKx, DKJCx, DKKDx, DKPLx, PLJCx, PLPLx (optional); a
//                   GAP_SGR_CLB contact has one more line, its internal variable.
// The numbers are fixed-column D14.7 fields, read where LMGC90 reads them; written as
// pylmgc90 writes them (%14.7E): 8 significant digits.
//
// What nscd cannot represent is refused with nscd::Error "DATBOX file '<file>', line <n>: …":
// another body type (RBDY3: 3D, MAILx: a deformable mesh), another contactor (DISKb, …), a law
// other than the three above, a body whose contactors have different colours, a see-table entry
// for a contactor or body nscd does not have, two laws for one pair of colours, a malformed or
// truncated line. Nothing is skipped silently: what is read but not used (a bulk law no RBDY2
// uses, a contact law no see entry uses, see entries with different alert distances — nscd has
// one alert, the largest is taken) is listed in Datbox::notes.
//
// Mapping: each (bulk behaviour, colour) pair used by a body is one nscd material named
// "behav:color"; the see table's (colour, colour) → law becomes the law of every pair of such
// materials. A body's mass is LMGC90's: Umas · π · avrd², its inertia mass · gyrd² (whatever its
// contactors). Contactors are placed relative to the body's node, as given; the body's reference
// configuration (BodyTable::x0, y0, angle0) is the node's coo1..3 and its position the node plus
// DOF.INI's X.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "nscd/core/math.hpp"
#include "nscd/registry/registry.hpp"

namespace nscd {

/// A DRV_DOF.DAT drive as written: the six coefficients, or an evolution file's table.
struct DatboxDrive {
  bool evolution = false;
  double ct = 0.0, amp = 0.0, omega = 0.0, phi = 0.0, rampi = 1.0, ramp = 0.0;  ///< predefined
  std::string file;                 ///< evolution: the file's name in the DATBOX folder
  std::vector<double> t, value;     ///< evolution: its table (t increasing)
  double operator()(double time) const;
};

/// One contact of Vloc_Rloc.INI, its contactors resolved (the file's body and contactor numbers
/// are those of BODIES.DAT; datbox_number gives them back).
struct DatboxContact {
  std::string type;            ///< DKDKx, DKJCx, DKKDx, DKPLx, PLJCx, PLPLx
  ContactorId cd, an;          ///< candidate, antagonist
  int cd_vertex = 0, an_segment = 0;  ///< PLJCx/PLPLx CDVER, PLPLx ANSEG (0: none)
  std::string behav, status;
  double rlt = 0.0, rln = 0.0;  ///< impulse / H (mean force over the step), tangential and normal
  double vlt = 0.0, vln = 0.0, gap = 0.0;
  Vec2 normal, point;
  double internal = 0.0;  ///< GAP_SGR_CLB's one internal variable (LMGC90 reads a line for it)
};

/// A DATBOX read into nscd.
struct Datbox {
  Registry reg;
  /// What the registry alone does not keep and the writer needs to give the same files back:
  /// the laws' names (per ContactLawTable::laws index) and the drives (by body and dof).
  std::vector<std::string> law_name;
  std::map<std::pair<std::uint32_t, std::uint8_t>, DatboxDrive> drives;
  std::vector<DatboxContact> contacts;  ///< Vloc_Rloc.INI (empty without one)
  std::int64_t step = 0;                ///< DOF.INI's $steps
  std::vector<std::string> notes;       ///< what was read but not used (see the file comment)
};

/// Reads the folder (BODIES.DAT, BULK_BEHAV.DAT, TACT_BEHAV.DAT required; DRV_DOF.DAT, DOF.INI,
/// Vloc_Rloc.INI optional). Throws nscd::Error naming the file and the line.
Datbox read_datbox(const std::filesystem::path& dir);

/// What write_datbox adds to the registry: names, drives and contacts as a Datbox holds them
/// (all optional: a scene nscd built gets generated names "law01", …).
struct DatboxExtras {
  const std::vector<std::string>* law_name = nullptr;
  const std::map<std::pair<std::uint32_t, std::uint8_t>, DatboxDrive>* drives = nullptr;
  const std::vector<DatboxContact>* contacts = nullptr;  ///< written to Vloc_Rloc.INI
  std::int64_t step = 0;
};

/// Writes BODIES.DAT, BULK_BEHAV.DAT, TACT_BEHAV.DAT, DRV_DOF.DAT, DOF.INI, Vloc_Rloc.INI (and
/// the evolution files) into `dir` (created). Throws nscd::Error on what a DATBOX cannot hold:
/// a drive given as a lambda without its DatboxDrive, a cosine drive that starts late, a body
/// without a material or with a non-positive density.
void write_datbox(const std::filesystem::path& dir, const Registry& reg, const DatboxExtras& extras = {});

/// The Vloc_Rloc.INI records of the registry's current contacts (forces rn, rt as rl/H), for
/// write_datbox: one per contact point between contactors of kinds LMGC90 pairs.
std::vector<DatboxContact> datbox_contacts(const Registry& reg);

/// The 1-based LMGC90 numbers of a contactor: its body and its rank among that body's contactors
/// in the order BODIES.DAT lists them (write_datbox's order: POLYG, DISKx, JONCx, xKSID, PT2Dx).
std::pair<int, int> datbox_number(const Registry& reg, ContactorId c);

}  // namespace nscd
