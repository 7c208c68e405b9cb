// nscd/core/registry.hpp — the central registry: one plain struct that owns every table of
// a scene (LMGC90's "model" in one place).
//
// The registry is data only. The behaviour lives in the module folders, which take the
// registry by reference: bodies/ (RBDY2), contactors/ (POLYG), interactions/ (PLPLx),
// laws/, solvers/, io/. There are no singletons and no self-registration: a driver builds a
// Registry, fills it through the module functions, and steps it.
//
// Tables are structures of arrays: the hot per-step state (positions, velocities, inverse
// masses, contact frames) sits in contiguous arrays, the cold data (names, vertices of
// the polygons in their own frame, boundary-condition descriptions) apart from it. A kind
// of contactor or interaction the scene does not use is an empty table and costs nothing:
// the step loops only over the kinds that hold something.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "nscd/core/ids.hpp"
#include "nscd/core/math.hpp"
#include "nscd/core/names.hpp"
#include "nscd/core/time_function.hpp"

namespace nscd {

/// Global parameters of a run. Units: SI (m, kg, s); 2D quantities are per unit thickness
/// (mass in kg/m, inertia in kg·m²/m, forces in N/m) — see docs/theory.md.
struct Parameters {
  double dt = 2e-4;             ///< time step h (s)
  double theta = 0.5;           ///< θ of the θ-method, in [0.5, 1]
  Vec2 gravity{0.0, -9.81};     ///< m/s²
  double alert = 1.25e-3;       ///< alert distance: pairs with gap <= alert are reported (m)
};

/// Degrees of freedom of an RBDY2 body, in the order of its velocity vector (vx, vy, ω).
enum class Dof : std::uint8_t { X = 0, Y = 1, Rot = 2 };

/// How a degree of freedom is driven. Free: gravity plus imposed forces; Fixed: velocity 0;
/// Velocity: velocity imposed as v(t); Force: an extra external force f(t) (moment for Rot).
enum class Drive : std::uint8_t { Free, Fixed, Velocity, Force };

struct DofDrive {
  BodyId body;
  Dof dof = Dof::X;
  Drive drive = Drive::Free;
  TimeFunction value;  ///< v(t) for Velocity, f(t) for Force; unused otherwise
};

/// RBDY2 bodies. Hot state indexed by BodyId::index(). The body frame's origin is the body's
/// centre of mass; `angle` rotates body-frame vectors into the world frame.
struct BodyTable {
  // hot: configuration and velocity at the beginning of the step (t_i)
  std::vector<double> x, y, angle;  ///< centre of mass and orientation
  std::vector<double> vx, vy, spin; ///< velocity of the centre of mass and angular velocity
  // hot: inverse mass seen by the contact solver per dof (0 for Fixed / Velocity dofs)
  std::vector<double> inv_mass_x, inv_mass_y, inv_inertia;
  // cold
  std::vector<double> mass, inertia;        ///< true mass and inertia about the centre of mass
  std::vector<double> x0, y0, angle0;       ///< reference configuration (for displacements)
  std::vector<MaterialId> material;
  std::vector<std::string> name;
  std::vector<std::uint8_t> is_driven;      ///< 1 if any dof has a Drive other than Free
  std::vector<DofDrive> drives;             ///< boundary conditions, few entries

  std::size_t size() const { return x.size(); }
  bool empty() const { return x.empty(); }
};

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

/// DISKx contactors: disks attached to bodies, centre given in the body frame.
struct DiskxTable {
  std::vector<BodyId> body;
  std::vector<Vec2> offset;     ///< the disk's centre in the body frame
  std::vector<double> radius;
  std::size_t size() const { return body.size(); }
  bool empty() const { return body.empty(); }
};

/// JONCx contactors (LMGC90's "jonc", walls): the segment offset ± half_length · axis in the
/// body frame, thickened by half_thickness (round ends).
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

struct MaterialTable {
  std::vector<std::string> name;
  std::vector<double> density;  ///< kg/m³ (times the unit thickness: kg/m² of section)
  std::size_t size() const { return name.size(); }
};

/// One contact law with its parameters (laws/ implements them).
struct LawSpec {
  LawKind kind = LawKind::IQS_CLB;
  double mu = 0.0;   ///< friction coefficient
  double e_n = 0.0;  ///< normal restitution (RST_CLB)
  double e_t = 0.0;  ///< tangential restitution (RST_CLB)
};

/// Which law applies to a pair of materials (LMGC90's "see table"): a symmetric dense
/// matrix of indices into `laws`, with `default_law` for pairs never set.
struct ContactLawTable {
  std::vector<LawSpec> laws;
  std::vector<std::int32_t> pair_law;  ///< n×n, -1 = default
  std::size_t n_materials = 0;
  std::int32_t default_law = -1;       ///< -1: no law, pairs of these materials never interact
};

/// Status of a contact point after the solve.
enum class ContactStatus : std::uint8_t { Open = 0, Stick = 1, SlipForward = 2, SlipBackward = 3 };

/// The contact table: every contact point found by detection at q_m, whatever the pair of
/// contactors (PLPLx, DKDKx, DKPLx, DKJCx, PLJCx, DKKDx; the kinds are in the ContactorIds).
/// n points from the antagonist toward the candidate; t = perp(n). The gap g is negative
/// for an overlap. Forces are in N/m (per unit thickness); the impulse over a step is h·R.
/// The points of one pair are consecutive.
struct PlplxTable {
  std::vector<ContactorId> candidate, antagonist;
  std::vector<BodyId> cd_body, an_body;
  std::vector<std::uint32_t> feature;      ///< which vertices / edges touch (warm-start key)
  std::vector<double> gap;
  std::vector<Vec2> normal, point;
  /// Lever arms projected on the frame: cross(r, n) and cross(r, t), r = point − centre.
  std::vector<double> cd_rn, cd_rt, an_rn, an_rt;
  std::vector<double> rn, rt;              ///< contact force components (N/m)
  std::vector<ContactStatus> status;
  std::vector<std::int32_t> law;           ///< index into ContactLawTable::laws
  std::vector<double> mu;                  ///< friction of this contact (may differ per contact)

  std::size_t size() const { return candidate.size(); }
  bool empty() const { return candidate.empty(); }
  void clear();
  void resize(std::size_t n);
};

/// PT2Dx: point contactors (anchors for springs) attached to bodies, in the body frame.
struct Pt2dxTable {
  std::vector<BodyId> body;
  std::vector<Vec2> point;  ///< body frame (origin = centre of mass)
  std::size_t size() const { return body.size(); }
  bool empty() const { return body.empty(); }
};

/// VOIGT_ROD: the visco-elastic spring of the sublayer (paper §2.9, eq. 17), strain
/// ε = (L − L0)/L0 − ε0. The force on the candidate along n (from the antagonist point to the
/// candidate point) is R_N = −k L0 ε − ν L0 ε̇ = −k (L − L0 (1 + ε0)) − ν L̇: k in N/m and ν in
/// N·s/m per unit thickness, the paper's calibration F = k δ. See docs/theory.md.
struct VoigtRod {
  double k = 0.0;     ///< stiffness (N/m), >= 0
  double nu = 0.0;    ///< viscosity (N·s/m), >= 0
  double L0 = 0.0;    ///< reference length (m), > 0
  double eps0 = 0.0;  ///< prestrain
};

/// PTPT2 links: one VOIGT_ROD spring between two PT2Dx points. Always active (bilateral);
/// the frame and forces are refreshed each step at q_m.
struct Ptpt2Table {
  std::vector<PointId> candidate, antagonist;
  std::vector<VoigtRod> law;
  std::vector<double> length;  ///< L at the last detection (q_m)
  std::vector<Vec2> normal;    ///< unit, from the antagonist point to the candidate point
  std::vector<double> rn;      ///< force along n on the candidate (N/m); < 0 pulls it back
  std::size_t size() const { return candidate.size(); }
  bool empty() const { return candidate.empty(); }
};

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
  PlplxTable plplx;  ///< the contact table (all contactor pairs; named after its first kind)
  Ptpt2Table links;
};

// ---- small helpers on the material and contact-law tables -------------------------------

/// Adds a material; throws on a duplicate name or a density that is not > 0.
MaterialId add_material(Registry& reg, const std::string& name, double density);
/// Looks a material up by name; throws if absent.
MaterialId find_material(const Registry& reg, const std::string& name);
/// The law for a pair of materials (symmetric). Validates the parameters (mu >= 0, e in [0,1]).
void set_contact_law(Registry& reg, MaterialId a, MaterialId b, const LawSpec& law);
/// The law for every pair not set explicitly.
void set_default_contact_law(Registry& reg, const LawSpec& law);
/// Index into contact_laws.laws for a material pair, -1 if none applies.
std::int32_t contact_law_index(const Registry& reg, MaterialId a, MaterialId b);
/// Throws nscd::Error if dt <= 0, theta outside [0.5, 1], alert < 0 or a non-finite value.
void validate(const Parameters& p);
/// Throws nscd::Error if mu < 0, e_n outside [0, 1], e_t outside [-1, 1] (a negative tangential
/// restitution is admissible in Moreau's impact law), or a non-finite value.
void validate(const LawSpec& law);

}  // namespace nscd
