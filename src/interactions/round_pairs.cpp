// nscd/interactions/round_pairs.cpp — see round_pairs.hpp.
//
// Every pair reduces to "a boundary point of the antagonist, a boundary point of the
// candidate, and the unit normal between them": the closest points of two convex sets, one of
// which is a point thickened by a radius (a disk, a capsule's core segment or a polygon's
// vertex). record() turns them into a contact point with the common conventions.
#include "nscd/interactions/round_pairs.hpp"

#include <cmath>
#include <cstdint>
#include <initializer_list>

namespace nscd {
namespace {

constexpr std::uint32_t kind_bits(std::uint32_t kind, std::uint32_t index) {
  return (kind << 30) | (index & 0x3FFFFFFFu);
}

// Appends a point: antagonist boundary point pa, candidate boundary point pc = pa + gap · n.
void record(PairContacts& out, Vec2 pa, Vec2 n, double gap, std::uint32_t feature) {
  ContactPoint& p = out.points[out.count++];
  p.gap = gap;
  p.normal = n;
  p.point = pa + (0.5 * gap) * n;
  p.feature = feature;
}

// Closest point of the segment [p0, p1] to c, and its parameter s in [0, 1].
struct SegmentPoint {
  Vec2 q;
  double s;
};
SegmentPoint closest_on_segment(Vec2 p0, Vec2 p1, Vec2 c) {
  const Vec2 d = p1 - p0;
  const double dd = dot(d, d);
  double s = dd > 0.0 ? dot(c - p0, d) / dd : 0.0;
  s = s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
  return {p0 + s * d, s};
}

// The closest boundary point of the convex polygon P to c, the unit normal from P toward c
// and the signed distance (negative when c is inside), with the feature that holds the point.
struct PolygonPoint {
  Vec2 q, n;
  double distance;
  std::uint32_t feature;  // kind 1: edge k, kind 2: vertex k
};
PolygonPoint closest_on_polygon(const ConvexView& P, Vec2 c) {
  // the edge whose line is farthest from c on its outer side (the separating axis)
  std::uint32_t kmax = 0;
  double smax = -INFINITY;
  for (std::uint32_t k = 0; k < P.count; ++k) {
    const double s = dot(c - P.vertex[k], P.normal[k]);
    if (s > smax) smax = s, kmax = k;
  }
  if (smax <= 0.0)  // inside (or on the boundary): the nearest edge line, whose foot lies on the edge
    return {c - smax * P.normal[kmax], P.normal[kmax], smax, kind_bits(1, kmax)};
  // outside: the nearest point over the edges that face c
  PolygonPoint best{{}, {}, INFINITY, 0};
  for (std::uint32_t k = 0; k < P.count; ++k) {
    if (dot(c - P.vertex[k], P.normal[k]) <= 0.0) continue;
    const std::uint32_t k1 = k + 1 == P.count ? 0 : k + 1;
    const SegmentPoint sp = closest_on_segment(P.vertex[k], P.vertex[k1], c);
    const double d = norm(c - sp.q);
    if (d >= best.distance) continue;
    if (sp.s > 0.0 && sp.s < 1.0) {
      best = {sp.q, P.normal[k], d, kind_bits(1, k)};
    } else {
      const std::uint32_t v = sp.s <= 0.0 ? k : k1;
      best = {sp.q, (1.0 / d) * (c - sp.q), d, kind_bits(2, v)};
    }
  }
  return best;
}


// The core segment crosses the polygon with no vertex near it (a wall through a polygon: only
// after a violent step). Separating axes: the capsule's two face normals and the polygon's
// edge normals; the least penetrating one gives one point, so that the solver pushes them apart.
PairContacts crossing_contact(const JoncView& a, const ConvexView& c, double alert) {
  const double b = a.half_thickness;
  const Vec2 p0 = a.centre - a.half_length * a.axis, p1 = a.centre + a.half_length * a.axis;
  double best = -INFINITY;
  Vec2 pa, n;
  for (const Vec2 m : {perp(a.axis), -perp(a.axis)}) {  // the polygon on the +m side of a face
    std::uint32_t lo = 0;
    for (std::uint32_t i = 1; i < c.count; ++i)
      if (dot(c.vertex[i], m) < dot(c.vertex[lo], m)) lo = i;
    const double s = dot(c.vertex[lo] - a.centre, m) - b;
    if (s > best) best = s, n = m, pa = c.vertex[lo] - s * m;
  }
  for (std::uint32_t k = 0; k < c.count; ++k) {  // the capsule outside edge k of the polygon
    const double s0 = dot(p0 - c.vertex[k], c.normal[k]), s1 = dot(p1 - c.vertex[k], c.normal[k]);
    const Vec2 e = s0 <= s1 ? p0 : p1;
    const double s = std::min(s0, s1) - b;
    if (s > best) best = s, n = -c.normal[k], pa = e + b * n;
  }
  PairContacts out;
  if (best <= alert) record(out, pa, n, best, kind_bits(3, 0));
  return out;
}
}  // namespace

PairContacts dkdkx(const DiskView& a, const DiskView& c, double alert) {
  PairContacts out;
  const Vec2 d = c.centre - a.centre;
  const double dist = norm(d);
  const double gap = dist - a.radius - c.radius;
  if (gap > alert) return out;
  // concentric disks: any direction is a normal; +y keeps the result deterministic
  const Vec2 n = dist > 0.0 ? (1.0 / dist) * d : Vec2{0.0, 1.0};
  record(out, a.centre + a.radius * n, n, gap, 0);
  return out;
}

PairContacts dkkdx(const RingView& a, const DiskView& c, double alert) {
  PairContacts out;
  const Vec2 d = c.centre - a.centre;
  const double dist = norm(d);
  const double gap = a.radius - dist - c.radius;
  if (gap > alert) return out;
  // the nearest wall point lies on the ray from the ring's centre through the disk's centre
  const Vec2 u = dist > 0.0 ? (1.0 / dist) * d : Vec2{0.0, -1.0};
  record(out, a.centre + a.radius * u, -u, gap, 0);
  return out;
}

PairContacts dkplx(const ConvexView& a, const DiskView& c, double alert) {
  PairContacts out;
  const PolygonPoint pp = closest_on_polygon(a, c.centre);
  const double gap = pp.distance - c.radius;
  if (gap > alert) return out;
  record(out, pp.q, pp.n, gap, pp.feature);
  return out;
}

PairContacts dkjcx(const JoncView& a, const DiskView& c, double alert) {
  PairContacts out;
  const Vec2 p0 = a.centre - a.half_length * a.axis, p1 = a.centre + a.half_length * a.axis;
  const SegmentPoint sp = closest_on_segment(p0, p1, c.centre);
  const Vec2 d = c.centre - sp.q;
  const double dist = norm(d);
  const double gap = dist - a.half_thickness - c.radius;
  if (gap > alert) return out;
  const Vec2 face = perp(a.axis);
  std::uint32_t feature = sp.s <= 0.0 ? 2 : (sp.s >= 1.0 ? 3 : (dot(d, face) >= 0.0 ? 0 : 1));
  Vec2 n;
  if (dist > 0.0) {
    n = (1.0 / dist) * d;
  } else {  // the centre on the core segment: the +perp face
    n = face;
    feature = 0;
  }
  record(out, sp.q + a.half_thickness * n, n, gap, feature);
  return out;
}

PairContacts pljcx(const JoncView& a, const ConvexView& c, double alert) {
  // Candidates: each polygon vertex against the capsule, and each round end of the capsule
  // (a disk of radius b) against a polygon edge's interior (an end on a vertex is the vertex's
  // point already). A convex polygon meets a capsule along at most one patch: keep the deepest
  // point and the candidate farthest from it (the patch's other extremity).
  constexpr int kMax = 64;
  ContactPoint found[kMax];
  int n_found = 0;
  const Vec2 p0 = a.centre - a.half_length * a.axis, p1 = a.centre + a.half_length * a.axis;
  const double b = a.half_thickness;
  Vec2 centroid{0.0, 0.0};
  for (std::uint32_t i = 0; i < c.count; ++i) centroid += c.vertex[i];
  centroid *= 1.0 / static_cast<double>(c.count);
  for (std::uint32_t i = 0; i < c.count && n_found < kMax; ++i) {
    const SegmentPoint sp = closest_on_segment(p0, p1, c.vertex[i]);
    const Vec2 d = c.vertex[i] - sp.q;
    const double dist = norm(d);
    const double gap = dist - b;
    if (gap > alert) continue;
    Vec2 n = dist > 0.0 ? (1.0 / dist) * d : perp(a.axis);
    if (dist == 0.0 && dot(centroid - sp.q, n) < 0.0) n = -n;  // a vertex on the core: the polygon's side
    PairContacts one;
    record(one, sp.q + b * n, n, gap, kind_bits(1, i));
    found[n_found++] = one.points[0];
  }
  const Vec2 ends[2] = {p0, p1};
  for (std::uint32_t j = 0; j < 2 && n_found < kMax; ++j) {
    if (j == 1 && a.half_length == 0.0) break;
    const PolygonPoint pp = closest_on_polygon(c, ends[j]);
    if ((pp.feature >> 30) != 1) continue;  // on a vertex: counted above
    const double gap = pp.distance - b;
    if (gap > alert) continue;
    // pp.n points from the polygon toward the end; the contact normal points toward the polygon
    const Vec2 n = -pp.n;
    // the end is the capsule's point nearest that edge only if the core does not run toward it
    const Vec2 outward = j == 0 ? -a.axis : a.axis;
    if (dot(n, outward) < -1e-12) continue;
    PairContacts one;
    record(one, ends[j] + b * n, n, gap, kind_bits(2, j));
    found[n_found++] = one.points[0];
  }
  PairContacts out;
  if (n_found == 0) return crossing_contact(a, c, alert);
  int deepest = 0;
  for (int k = 1; k < n_found; ++k)
    if (found[k].gap < found[deepest].gap) deepest = k;
  out.points[out.count++] = found[deepest];
  int other = -1;
  double far = 0.0;
  for (int k = 0; k < n_found; ++k) {
    const double s = std::abs(dot(found[k].point - found[deepest].point, perp(found[deepest].normal)));
    if (k != deepest && s > far) far = s, other = k;
  }
  if (other >= 0) out.points[out.count++] = found[other];
  return out;
}

PairContacts plkdx(const RingView& a, const ConvexView& c, double alert) {
  PairContacts out;
  auto gap_of = [&](std::uint32_t i) { return a.radius - norm(c.vertex[i] - a.centre); };
  // the deepest vertex within alert, then of the others within alert the farthest from it along
  // the wall (an edge lying on the wall gives its two ends)
  int deepest = -1;
  double best = alert;
  for (std::uint32_t i = 0; i < c.count; ++i)
    if (const double g = gap_of(i); g <= best) best = g, deepest = static_cast<int>(i);
  if (deepest < 0) return out;
  const Vec2 tangent = perp(c.vertex[deepest] - a.centre);
  int other = -1;
  double far = 0.0;
  for (std::uint32_t i = 0; i < c.count; ++i) {
    if (static_cast<int>(i) == deepest || gap_of(i) > alert) continue;
    const double s = std::abs(dot(c.vertex[i] - c.vertex[deepest], tangent));
    if (s > far) far = s, other = static_cast<int>(i);
  }
  for (const int i : {deepest, other}) {
    if (i < 0) continue;
    const Vec2 d = c.vertex[i] - a.centre;
    const double dist = norm(d);
    const Vec2 u = dist > 0.0 ? (1.0 / dist) * d : Vec2{0.0, -1.0};  // outward, toward the wall
    record(out, a.centre + a.radius * u, -u, a.radius - dist, kind_bits(1, static_cast<std::uint32_t>(i)));
  }
  return out;
}

}  // namespace nscd
