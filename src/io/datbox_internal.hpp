// nscd/io/datbox_internal.hpp — what the DATBOX reader's parts hand each other (internal:
// datbox_reader.cpp parses, datbox_build.cpp builds the registry, datbox_drives.cpp reads
// DRV_DOF.DAT and Vloc_Rloc.INI).
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "nscd/io/datbox.hpp"

namespace nscd::datbox {

struct BulkBehav {
  std::string name, law;
  double density = 0.0;  ///< RIGID's Umas
  std::size_t line = 0;
};

struct TactRec {
  std::string kind, colour;
  double a = 0.0, b = 0.0;   ///< byrd; axe1, axe2; coo1, coo2
  std::vector<Vec2> vertices;
  std::size_t line = 0;
};

struct BodyRec {
  std::string behav;
  double avrd = 0.0, gyrd = 0.0;
  std::array<double, 3> coo{}, X{}, V{};
  std::vector<TactRec> tacts;
  std::size_t line = 0, behav_line = 0;
  bool nominal_mass = false;  ///< an xKSID alone with avrd 0: allowed only if every dof is driven
};

struct LawRec {
  std::string name, law;
  LawSpec spec;
  bool known = false;  ///< one of IQS_CLB, GAP_SGR_CLB, RST_CLB
  std::size_t line = 0;
};

struct SeeRec {
  std::string cdbdy, cdtac, cdcol, behav, anbdy, antac, ancol;
  double alert = 0.0, halo = -1.0;  ///< halo: the '+' line's second alert (−1: none)
  std::size_t line = 0;
};

struct Parsed {
  Vec2 gravity{0.0, -9.81};
  std::map<std::string, BulkBehav> behavs;
  std::vector<BodyRec> bodies;
  std::map<std::string, LawRec> laws;
  std::vector<SeeRec> see;
  /// Filled by build_registry: each body's contactors in BODIES.DAT's order.
  std::vector<std::vector<ContactorId>> tact_ids;
};

/// "DATBOX file '<file>', line <n>: <what>".
[[noreturn]] void fail_at(const std::filesystem::path& file, std::size_t line, const std::string& what);

void build_registry(Parsed& p, const std::filesystem::path& bodies_file, const std::filesystem::path& tact_file,
                    Datbox& d);
void read_drives(const std::filesystem::path& dir, Datbox& d);
void read_contacts(const std::filesystem::path& dir, const Parsed& p, Datbox& d);

/// The LMGC90 interaction of a candidate and an antagonist kind ("DKJCx"), "" if LMGC90 has none
/// in that order.
std::string interaction_name(ContactorKind cd, ContactorKind an);

/// Each body's contactors in the order write_datbox lists them (POLYG, DISKx, JONCx, xKSID,
/// PT2Dx; within a kind, by row).
std::vector<std::vector<ContactorId>> contactors_by_body(const Registry& reg);

}  // namespace nscd::datbox
