// tests/unit/test_added_kind.cpp — a contactor kind defined outside src/ (issue #38): HALFP, an
// infinite half-plane, and its interactions with DISKx (DKHPx) and POLYG (PLHPx), added to a
// scene at run time through its row (contactors/contactor_row.hpp). A disk and a square fall on
// it and come to rest on its line, the VTK files draw it and name its interactions, and a
// checkpoint round-trips it and resumes bit for bit — with no file of src/ naming the kind.
#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/contactor_row.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/contactors/round_shapes.hpp"
#include "nscd/contactors/round_views.hpp"
#include "nscd/core/error.hpp"
#include "nscd/interactions/interaction_table.hpp"
#include "nscd/interactions/plplx.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/io/vtk_writer.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "temp_path.hpp"

namespace nscd {
namespace added_kind_test {

namespace fs = std::filesystem;

// ---- the kind: its table, its views, its row -------------------------------------------------

/// HALFP contactors: the half-plane behind a line through `point` whose unit `normal` points to
/// the free side, in the body frame; `width` is how wide VTK draws it (and its box).
struct HalfPlaneTable {
  std::vector<BodyId> body;
  std::vector<Vec2> point, normal;
  std::vector<double> width;
};
struct HalfPlaneView {
  Vec2 point, normal;
};

ContactorKind g_halfp{};  // the kind number of the scene being built (every scene adds it first)

const HalfPlaneTable& table(const Registry& reg) { return added_table<HalfPlaneTable>(reg, g_halfp); }

void attach_halfplane(Registry& reg, BodyId body, Vec2 point, Vec2 normal, double width) {
  if (!(std::abs(norm(normal) - 1.0) < 1e-12)) throw Error("HALFP: the normal must be a unit vector");
  if (!(width > 0.0)) throw Error("HALFP: the width must be > 0");
  HalfPlaneTable& t = added_table<HalfPlaneTable>(reg, g_halfp);
  t.body.push_back(body), t.point.push_back(point), t.normal.push_back(normal), t.width.push_back(width);
}

std::size_t hp_count(const Registry& reg) { return table(reg).body.size(); }
BodyId hp_body(const Registry& reg, std::uint32_t i) { return table(reg).body[i]; }

void hp_world(const Registry& reg, const Configuration& q, KindViews& views, KindBoxes& boxes) {
  const HalfPlaneTable& t = table(reg);
  auto& v = views.reset<HalfPlaneView>();
  for (std::size_t k = 0; k < t.body.size(); ++k) {
    const std::size_t b = t.body[k].index();
    const Vec2 p = world_point(q.x[b], q.y[b], q.angle[b], t.point[k]);
    const Vec2 n = Rot2::of(q.angle[b]).apply(t.normal[k]), e = t.width[k] * perp(n);
    v.push_back({p, n});
    const Vec2 c[4] = {p + e, p - e, p + e - t.width[k] * n, p - e - t.width[k] * n};
    Vec2 lo = c[0], hi = c[0];
    for (const Vec2 x : c) lo = {std::min(lo.x, x.x), std::min(lo.y, x.y)}, hi = {std::max(hi.x, x.x), std::max(hi.y, x.y)};
    boxes.push(lo, hi, true);  // a wall: out of the grid
  }
}

void hp_draw(const Registry& reg, std::uint32_t i, KindOutline& out) {
  const HalfPlaneTable& t = table(reg);
  const Vec2 p = t.point[i], n = t.normal[i], e = t.width[i] * perp(n), d = 0.1 * t.width[i] * n;
  for (const Vec2 x : {p - e, p + e, p + e - d, p - e - d}) out.put(x);
  out.end_cell();
}

constexpr std::string_view kParams[] = {"point x", "point y", "normal x", "normal y", "width"};
void hp_save(const Registry& reg, std::uint32_t i, double* n) {
  const HalfPlaneTable& t = table(reg);
  n[0] = t.point[i].x, n[1] = t.point[i].y, n[2] = t.normal[i].x, n[3] = t.normal[i].y, n[4] = t.width[i];
}
void hp_load(Registry& reg, BodyId b, const double* n) { attach_halfplane(reg, b, {n[0], n[1]}, {n[2], n[3]}, n[4]); }

const ContactorKindRow kHalfPlaneRow{.name = "HALFP", .tag = "hp", .params = kParams, .count = hp_count,
                                     .body = hp_body, .world = hp_world, .draw = hp_draw, .save = hp_save,
                                     .load = hp_load, .new_table = [] { return std::any(HalfPlaneTable{}); }};

// ---- its narrow phases (the conventions of interactions/round_pairs.hpp) ---------------------

const HalfPlaneView& hp_view(const PlplxDetector& det, std::uint32_t k) {
  return det.views[static_cast<std::size_t>(g_halfp)].get<HalfPlaneView>()[k];
}

// A disk on the half-plane: g = (c − p)·n − r, the point halfway between the two boundaries.
ShadowOverlapResult dkhpx(const Registry&, const PlplxDetector& det, std::uint32_t an, std::uint32_t cd, double alert) {
  const HalfPlaneView& h = hp_view(det, an);
  const DiskView& d = disk_view(det, cd);
  const double g = dot(d.centre - h.point, h.normal) - d.radius;
  ShadowOverlapResult r;
  if (g > alert) return r;
  r.count = 1;
  r.points[0] = {g, h.normal, d.centre - (d.radius + 0.5 * g) * h.normal, 0};
  return r;
}

// A polygon on the half-plane touches by vertices: the deepest, and the one farthest from it
// along the line (an edge lying on it gives both its ends).
ShadowOverlapResult plhpx(const Registry& reg, const PlplxDetector& det, std::uint32_t an, std::uint32_t cd, double alert) {
  const HalfPlaneView& h = hp_view(det, an);
  const ConvexView poly = polygon_view(reg, det, cd);
  int deep = -1, far = -1;
  for (std::uint32_t i = 0; i < poly.count; ++i)
    if (dot(poly.vertex[i] - h.point, h.normal) <= alert &&
        (deep < 0 || dot(poly.vertex[i] - h.point, h.normal) < dot(poly.vertex[deep] - h.point, h.normal)))
      deep = static_cast<int>(i);
  ShadowOverlapResult r;
  if (deep < 0) return r;
  const Vec2 t = perp(h.normal);
  for (std::uint32_t i = 0; i < poly.count; ++i)
    if (static_cast<int>(i) != deep && dot(poly.vertex[i] - h.point, h.normal) <= alert &&
        (far < 0 || std::abs(dot(poly.vertex[i] - poly.vertex[deep], t)) > std::abs(dot(poly.vertex[far] - poly.vertex[deep], t))))
      far = static_cast<int>(i);
  for (int i : {deep, far}) {
    if (i < 0) continue;
    const Vec2 v = poly.vertex[i];
    const double g = dot(v - h.point, h.normal);
    r.points[r.count++] = {g, h.normal, v - 0.5 * g * h.normal,
                           make_feature(FeatureKind::CandidateVertexOnAntagonistEdge, static_cast<std::uint32_t>(i), 0)};
  }
  return r;
}

// ---- a scene: a fixed, tilted half-plane, a disk and a square dropped on it ------------------

constexpr double kTilt = 0.1;  // rad: the line through the origin, normal (−sin, cos)

struct Scene {
  Registry reg;
  BodyId ground, disk, square;
};

Scene make_scene() {
  Scene s;
  g_halfp = add_contactor_kind(s.reg, kHalfPlaneRow);
  add_interaction(s.reg, {"DKHPx", ContactorKind::DISKx, g_halfp, dkhpx});
  add_interaction(s.reg, {"PLHPx", ContactorKind::POLYG, g_halfp, plhpx});
  const MaterialId m = add_material(s.reg, "stone", 2500.0);
  set_default_contact_law(s.reg, LawSpec{LawKind::IQS_CLB, 0.8});  // μ > tan(kTilt): both stay
  RigidBodySpec ground;
  ground.name = "ground";
  ground.material = m;
  ground.mass = 1.0;
  ground.inertia = 1.0;
  s.ground = add_body(s.reg, ground);
  attach_halfplane(s.reg, s.ground, {0.0, 0.0}, {-std::sin(kTilt), std::cos(kTilt)}, 2.0);
  fix_body(s.reg, s.ground);
  s.disk = add_disk_body(s.reg, 0.05, m, {-0.3, 0.03}, "disk");
  s.square = add_polygon_body(s.reg, rectangle(0.1, 0.1), m, {0.3, 0.11}, kTilt, "square");
  s.reg.params.dt = 1e-3;
  return s;
}

// The distance of a point from the tilted line.
double height(Vec2 p) { return dot(p, {-std::sin(kTilt), std::cos(kTilt)}); }

TEST(AddedKind, ADiskAndASquareComeToRestOnAHalfPlaneDefinedOutsideSrc) {
  Scene s = make_scene();
  MoreauJean mj(s.reg);
  for (int n = 0; n < 600; ++n) mj.step();
  const BodyTable& b = s.reg.bodies;
  const auto d = s.disk.index(), q = s.square.index();
  // on the line: the disk's centre at its radius, the square's at its half side; the square
  // still (μ > tan kTilt), the disk rolling down the slope
  const Vec2 n{-std::sin(kTilt), std::cos(kTilt)};
  EXPECT_NEAR(height({b.x[d], b.y[d]}), 0.05, 2e-4);
  EXPECT_NEAR(height({b.x[q], b.y[q]}), 0.05, 2e-4);
  EXPECT_NEAR(dot({b.vx[d], b.vy[d]}, n), 0.0, 1e-3);
  const double down = dot({b.vx[d], b.vy[d]}, perp(n));  // perp(n) points down the slope
  EXPECT_GT(down, 0.3);  // (2/3) g sin(kTilt) = 0.65 m/s² over the half second after landing
  EXPECT_NEAR(std::abs(b.spin[d]) * 0.05, down, 0.01 * down);  // rolling, not sliding
  EXPECT_NEAR(std::hypot(b.vx[q], b.vy[q]), 0.0, 1e-3);
  // the line carries their weight: along the normal, 1 point under the disk, 2 under the square
  std::set<std::string> names;
  double push_disk = 0.0, push_square = 0.0;
  int square_points = 0;
  const ContactTable& c = s.reg.contacts;
  for (std::size_t k = 0; k < c.size(); ++k) {
    names.insert(std::string(name_of(s.reg, interaction_of(c.candidate[k], c.antagonist[k]))));
    ASSERT_EQ(c.an_body[k], s.ground);
    (c.cd_body[k] == s.disk ? push_disk : push_square) += c.rn[k];  // N/m
    square_points += c.cd_body[k] == s.square;
  }
  EXPECT_EQ(names, (std::set<std::string>{"DKHPx", "PLHPx"}));
  EXPECT_EQ(square_points, 2);
  const double g = std::abs(s.reg.params.gravity.y) * std::cos(kTilt);
  EXPECT_NEAR(push_disk, b.mass[d] * g, 1e-3 * b.mass[d] * g);
  EXPECT_NEAR(push_square, b.mass[q] * g, 1e-3 * b.mass[q] * g);
}

TEST(AddedKind, VtkDrawsTheHalfPlaneAndNamesItsInteractions) {
  Scene s = make_scene();
  MoreauJean mj(s.reg);
  for (int n = 0; n < 100; ++n) mj.step();
  const fs::path dir = nscd::testing_support::unique_temp_path("added_kind_vtk");
  fs::remove_all(dir);
  {
    VtkWriter w(dir);
    w.write_frame(s.reg);
  }
  auto read = [&](const char* name) {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName((dir / name).string().c_str());
    r->Update();
    return r;
  };
  const auto bodies = read("bodies_000000.vtp");
  vtkPolyData* pd = bodies->GetOutput();
  ASSERT_EQ(pd->GetNumberOfCells(), 3);  // the square, the disk, the half-plane (kind after kind)
  vtkDataArray* kind = pd->GetCellData()->GetArray("contactor_kind");
  ASSERT_NE(kind, nullptr);
  EXPECT_EQ(kind->GetTuple1(2), static_cast<double>(g_halfp));
  EXPECT_EQ(pd->GetCell(2)->GetNumberOfPoints(), 4);
  const auto contacts = read("contacts_000000.vtp");
  vtkPolyData* cd = contacts->GetOutput();
  ASSERT_EQ(cd->GetNumberOfCells(), 3);
  auto* names = vtkStringArray::SafeDownCast(cd->GetFieldData()->GetAbstractArray("interaction_names"));
  vtkDataArray* inter = cd->GetCellData()->GetArray("interaction");
  ASSERT_NE(names, nullptr);
  ASSERT_NE(inter, nullptr);
  std::multiset<std::string> got;
  for (vtkIdType k = 0; k < 3; ++k) got.insert(names->GetValue(static_cast<vtkIdType>(inter->GetTuple1(k))));
  EXPECT_EQ(got, (std::multiset<std::string>{"DKHPx", "PLHPx", "PLHPx"}));
  fs::remove_all(dir);
}

TEST(AddedKind, ACheckpointRoundTripsTheKindAndResumesBitForBit) {
  Scene a = make_scene();
  MoreauJean mj(a.reg);
  for (int n = 0; n < 50; ++n) mj.step();
  const fs::path f = nscd::testing_support::unique_temp_path("added_kind").concat(".nscd");
  save_checkpoint(f, a.reg, mj.warm_start_memory());
  try {  // a loader that was not given the kind names it
    load_checkpoint(f);
    ADD_FAILURE() << "loaded a checkpoint with an unknown added kind";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'HALFP'"), std::string::npos) << e.what();
  }
  Checkpoint cp = load_checkpoint(f, a.reg.added.row);
  fs::remove(f);
  const HalfPlaneTable& t0 = added_table<HalfPlaneTable>(a.reg, g_halfp);
  const HalfPlaneTable& t1 = added_table<HalfPlaneTable>(cp.reg, g_halfp);
  EXPECT_EQ(t1.body, t0.body);
  EXPECT_EQ(t1.normal, t0.normal);
  EXPECT_EQ(t1.width, t0.width);
  add_interaction(cp.reg, {"DKHPx", ContactorKind::DISKx, g_halfp, dkhpx});  // interactions are code: the driver's
  add_interaction(cp.reg, {"PLHPx", ContactorKind::POLYG, g_halfp, plhpx});
  MoreauJean resumed(cp.reg);
  resumed.set_warm_start_memory(cp.warm_start);
  for (int n = 0; n < 50; ++n) {
    mj.step();
    resumed.step();
  }
  for (std::size_t i = 0; i < a.reg.bodies.size(); ++i) {
    EXPECT_EQ(a.reg.bodies.x[i], cp.reg.bodies.x[i]) << i;
    EXPECT_EQ(a.reg.bodies.y[i], cp.reg.bodies.y[i]) << i;
    EXPECT_EQ(a.reg.bodies.spin[i], cp.reg.bodies.spin[i]) << i;
  }
}

TEST(AddedKind, TheRegistryRefusesABadRowOrLine) {
  Registry reg;
  ContactorKindRow nameless = kHalfPlaneRow;
  nameless.new_table = nullptr;
  EXPECT_THROW(add_contactor_kind(reg, nameless), Error);
  const ContactorKind k = add_contactor_kind(reg, kHalfPlaneRow);
  EXPECT_EQ(static_cast<int>(k), kFirstAddedKind);
  EXPECT_EQ(kind_name(reg, kFirstAddedKind), "HALFP");
  EXPECT_THROW(add_contactor_kind(reg, kHalfPlaneRow), Error);  // the name is taken
  EXPECT_THROW(add_interaction(reg, {"DKPLy", ContactorKind::DISKx, ContactorKind::POLYG, dkhpx}), Error);  // built in
  add_interaction(reg, {"DKHPx", ContactorKind::DISKx, k, dkhpx});
  EXPECT_THROW(add_interaction(reg, {"HPDKx", k, ContactorKind::DISKx, dkhpx}), Error);  // the pair has a line
  EXPECT_THROW(add_interaction(reg, {"PTHPx", ContactorKind::PT2Dx, k, dkhpx}), Error);  // points never touch
  EXPECT_THROW(added_table<std::vector<int>>(reg, k), Error);
}

}  // namespace added_kind_test
}  // namespace nscd
