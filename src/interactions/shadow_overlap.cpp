// nscd/interactions/shadow_overlap.cpp — see shadow_overlap.hpp.
#include "nscd/interactions/shadow_overlap.hpp"

#include <cmath>

namespace nscd {
namespace {

inline std::uint32_t next(std::uint32_t i, std::uint32_t n) { return i + 1 == n ? 0 : i + 1; }
inline std::uint32_t prev(std::uint32_t i, std::uint32_t n) { return i == 0 ? n - 1 : i - 1; }

// Two unit directions closer than this (sine of the angle) are the same breakpoint.
constexpr double kSameDirection = 1e-12;

inline bool same_direction(Vec2 u, Vec2 v) { return dot(u, v) > 0.0 && std::abs(cross(u, v)) < kSameDirection; }

// Pseudo-angle of D counter-clockwise from V, increasing with the angle on [0, 2π):
// 1 − cos on [0, π], 3 + cos on (π, 2π). Coincident directions give exactly 0.
inline double ccw_pseudo_angle(Vec2 V, Vec2 D) {
  if (same_direction(V, D)) return 0.0;
  const double c = dot(V, D), s = cross(V, D);
  return s >= 0.0 ? 1.0 - c : 3.0 + c;
}

// The walk's state: direction V and the critical vertices iA (max of A·V), iB (min of B·V).
struct Walk {
  const ConvexView& A;
  const ConvexView& B;
  Vec2 V;
  std::uint32_t iA = 0, iB = 0;

  double shov(Vec2 D, std::uint32_t ia, std::uint32_t ib) const { return dot(A.vertex[ia] - B.vertex[ib], D); }
  // Breakpoints where A's critical vertex changes: normal of edge iA (counter-clockwise side)
  // or of edge iA−1 (clockwise side); B's: minus the normal of edge iB or iB−1.
  Vec2 a_break(std::uint32_t edge) const { return A.normal[edge]; }
  Vec2 b_break(std::uint32_t edge) const { return -B.normal[edge]; }
};

// Neighbouring breakpoint of the walk in one rotation sense, with the critical vertices valid
// on the far side of V (V itself may sit on a breakpoint) and shov evaluated there.
struct Neighbour {
  Vec2 D;
  std::uint32_t iA, iB;
  double h;
};

Neighbour ccw_neighbour(const Walk& w) {
  std::uint32_t ia = w.iA, ib = w.iB;
  if (same_direction(w.V, w.a_break(ia))) ia = next(ia, w.A.count);
  if (same_direction(w.V, w.b_break(ib))) ib = next(ib, w.B.count);
  const Vec2 da = w.a_break(ia), db = w.b_break(ib);
  const Vec2 D = ccw_pseudo_angle(w.V, da) <= ccw_pseudo_angle(w.V, db) ? da : db;
  return {D, ia, ib, w.shov(D, ia, ib)};
}

Neighbour cw_neighbour(const Walk& w) {
  std::uint32_t ia = w.iA, ib = w.iB;
  if (same_direction(w.V, w.a_break(prev(ia, w.A.count)))) ia = prev(ia, w.A.count);
  if (same_direction(w.V, w.b_break(prev(ib, w.B.count)))) ib = prev(ib, w.B.count);
  const Vec2 da = w.a_break(prev(ia, w.A.count)), db = w.b_break(prev(ib, w.B.count));
  // clockwise angle from V to D = counter-clockwise angle from D to V
  const Vec2 D = ccw_pseudo_angle(da, w.V) <= ccw_pseudo_angle(db, w.V) ? da : db;
  return {D, ia, ib, w.shov(D, ia, ib)};
}

// Distance from p to the segment [a, b].
inline double point_segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double l2 = dot(ab, ab);
  const double u = l2 > 0.0 ? std::fmin(std::fmax(dot(p - a, ab) / l2, 0.0), 1.0) : 0.0;
  return norm(p - (a + u * ab));
}

// Edge–edge contact between edge ea = (ea, ea+1) of A and eb = (eb, eb+1) of B: the contact
// segment is the overlap of the two edges' projections on the mean tangent (the direction
// averaging both edges); its extremities become the contact points.
int edge_edge(const ConvexView& A, std::uint32_t ea, const ConvexView& B, std::uint32_t eb, double alert,
              ContactPoint out[2]) {
  const Vec2 a0 = A.vertex[ea], a1 = A.vertex[next(ea, A.count)];
  const Vec2 b0 = B.vertex[eb], b1 = B.vertex[next(eb, B.count)];
  const Vec2 n = normalized(A.normal[ea] - B.normal[eb]);
  const Vec2 t = perp(n);
  const double sa0 = dot(a0, t), sa1 = dot(a1, t), sb0 = dot(b0, t), sb1 = dot(b1, t);
  const double lo = std::fmax(std::fmin(sa0, sa1), std::fmin(sb0, sb1));
  const double hi = std::fmin(std::fmax(sa0, sa1), std::fmax(sb0, sb1));
  const double len = std::fmin(std::abs(sa1 - sa0), std::abs(sb1 - sb0));
  if (!(hi - lo > 1e-9 * len)) return 0;  // the edges' shadows on t barely meet: not edge–edge
  // Each extremity is a vertex of one polygon over the other's edge, and is described as that
  // vertex–edge contact: the normal of the edge it faces, the gap of the vertex from that edge's
  // line. Then U_N is exactly the rate of that gap, whatever the edges' relative rotation and
  // sliding (a normal averaged over the two edges would drift the gap of a point sliding along
  // an edge, unseen by U_N: overlaps grew by ~v sin(angle) h per step with no force).
  int count = 0;
  const bool lo_from_b = std::fmin(sb0, sb1) >= std::fmin(sa0, sa1);
  const bool hi_from_b = std::fmax(sb0, sb1) <= std::fmax(sa0, sa1);
  for (std::uint32_t k = 0; k < 2; ++k) {
    const bool from_b = k == 0 ? lo_from_b : hi_from_b;
    const bool first_is_lo_b = sb0 <= sb1, first_is_lo_a = sa0 <= sa1;
    ContactPoint p;
    if (from_b) {
      const Vec2 v = (k == 0) == first_is_lo_b ? b0 : b1;  // the candidate's vertex at this end
      const Vec2 nA = A.normal[ea];
      p.gap = dot(v - a0, nA);
      p.normal = nA;
      p.point = v - (0.5 * p.gap) * nA;
    } else {
      const Vec2 v = (k == 0) == first_is_lo_a ? a0 : a1;  // the antagonist's vertex at this end
      const Vec2 nB = -B.normal[eb];
      p.gap = dot(b0 - v, nB);
      p.normal = nB;
      p.point = v + (0.5 * p.gap) * nB;
    }
    if (p.gap > alert) continue;
    p.feature = make_feature(FeatureKind::EdgeEdge, ea, eb, k);
    out[count++] = p;
  }
  return count;
}

// 1. The start: the centre-to-centre direction d0 (as w.V) and its critical vertices; returns
//    the shadow overlap there.
double start_walk(Walk& w, Vec2 gA, Vec2 gB) {
  const ConvexView &A = w.A, &B = w.B;
  Vec2 d0 = gB - gA;
  const double l0 = norm(d0);
  d0 = l0 > 0.0 ? (1.0 / l0) * d0 : Vec2{1.0, 0.0};
  w.V = d0;
  double amax = dot(A.vertex[0], d0), bmin = dot(B.vertex[0], d0);
  for (std::uint32_t k = 1; k < A.count; ++k)
    if (const double s = dot(A.vertex[k], d0); s > amax) { amax = s; w.iA = k; }
  for (std::uint32_t k = 1; k < B.count; ++k)
    if (const double s = dot(B.vertex[k], d0); s < bmin) { bmin = s; w.iB = k; }
  return amax - bmin;
}

// Where the walk of step 2 ended.
enum class WalkEnd { Breakpoint, Apart, Degenerate };

// 2. Rotate V toward decreasing shadow overlap h, one critical-vertex change at a time.
//    Between two changes shov is |c| cos(angle), whose minimum over an arc where it is
//    positive lies at an end: comparing breakpoints is enough.
WalkEnd rotate(Walk& w, Vec2 d0, double& h, double alert, int& rotations) {
  const ConvexView &A = w.A, &B = w.B;
  // V may start on a breakpoint already (symmetric configurations: a box centred on a floor)
  bool at_breakpoint = same_direction(d0, w.a_break(w.iA)) || same_direction(d0, w.a_break(prev(w.iA, A.count))) ||
                       same_direction(d0, w.b_break(w.iB)) || same_direction(d0, w.b_break(prev(w.iB, B.count)));
  const int max_rotations = static_cast<int>(A.count + B.count) + 2;
  for (int it = 0; it < max_rotations; ++it) {
    const Neighbour up = ccw_neighbour(w), down = cw_neighbour(w);
    // V stays in the half-plane V·G_A G_B > 0 (paper §2.3): a neighbour outside it is not a
    // candidate, but the other one still is (the first move may leave the half-plane only
    // if neither neighbour lies in it)
    const bool up_in = dot(up.D, d0) > 0.0, down_in = dot(down.D, d0) > 0.0;
    const bool use_up = up_in == down_in ? up.h <= down.h : up_in;
    const Neighbour& best = use_up ? up : down;
    // the first move always leaves the start direction for the better breakpoint (where
    // shov > 0 concavity makes it no worse), so the contact frame is an edge normal
    const bool improve = !at_breakpoint || best.h < h;
    if (!improve || (at_breakpoint && dot(best.D, d0) <= 0.0)) break;
    w.V = best.D;
    w.iA = best.iA;
    w.iB = best.iB;
    h = best.h;
    at_breakpoint = true;
    ++rotations;
    if (h < -alert) return WalkEnd::Apart;  // a separating direction: the polygons are apart
  }
  return at_breakpoint ? WalkEnd::Breakpoint : WalkEnd::Degenerate;  // degenerate: V cannot leave the start half-plane
}

// 3. Which polygon's edge is normal to V (−1: none), and so which corner intrudes.
struct CriticalEdges {
  std::int64_t a = -1, b = -1;
};

CriticalEdges critical_edges(const Walk& w) {
  const Vec2 V = w.V;
  const std::uint32_t nA = w.A.count, nB = w.B.count;
  CriticalEdges e;
  if (same_direction(V, w.A.normal[w.iA]))
    e.a = w.iA;
  else if (same_direction(V, w.A.normal[prev(w.iA, nA)]))
    e.a = prev(w.iA, nA);
  if (same_direction(V, -w.B.normal[w.iB]))
    e.b = w.iB;
  else if (same_direction(V, -w.B.normal[prev(w.iB, nB)]))
    e.b = prev(w.iB, nB);
  return e;
}

// 4. A pair separated along V (shov < 0) is reported only if it truly lies within the alert
//    distance: the shadow separation −shov is only a lower bound of the distance (two
//    corners facing each other diagonally are up to √2 farther apart than their shadows on
//    an edge normal). Where the walk stopped, shov is at a local minimum and, the pair being
//    separated, at the global one (the separating directions form one arc, on which shov is
//    unimodal): the closest points then lie on the critical features (the intruding corner
//    and the edge normal to V, or the two parallel edges), whose distance is the exact one.
double separated_distance(const Walk& w, CriticalEdges e) {
  const ConvexView &A = w.A, &B = w.B;
  const auto edge_end = [](const ConvexView& P, std::int64_t k) {
    return P.vertex[next(static_cast<std::uint32_t>(k), P.count)];
  };
  if (e.a >= 0 && e.b >= 0) {
    const Vec2 a0 = A.vertex[e.a], a1 = edge_end(A, e.a), b0 = B.vertex[e.b], b1 = edge_end(B, e.b);
    return std::fmin(std::fmin(point_segment_distance(a0, b0, b1), point_segment_distance(a1, b0, b1)),
                     std::fmin(point_segment_distance(b0, a0, a1), point_segment_distance(b1, a0, a1)));
  }
  if (e.a >= 0) return point_segment_distance(B.vertex[w.iB], A.vertex[e.a], edge_end(A, e.a));
  if (e.b >= 0) return point_segment_distance(A.vertex[w.iA], B.vertex[e.b], edge_end(B, e.b));
  return 0.0;
}

// 5a. Corner iB of the candidate against edge `edge_a` of the antagonist; a neighbour of the
//     corner within the alert distance of that edge's line makes it edge–edge.
void corner_of_b(const Walk& w, std::uint32_t edge_a, double alert, ShadowOverlapResult& res) {
  const ConvexView &A = w.A, &B = w.B;
  const Vec2 V = w.V;
  const double line = dot(A.vertex[edge_a], V);
  const std::uint32_t jn = next(w.iB, B.count), jp = prev(w.iB, B.count);
  const double gn = dot(B.vertex[jn], V) - line, gp = dot(B.vertex[jp], V) - line;
  if (std::fmin(gn, gp) <= alert) {
    const std::uint32_t eb = gn <= gp ? w.iB : jp;  // edge of B holding both corners
    res.count = edge_edge(A, edge_a, B, eb, alert, res.points);
    if (res.count > 0) return;
  }
  const Vec2 b = B.vertex[w.iB];
  const double g = dot(b, V) - line;
  res.points[0] =
      ContactPoint{g, V, b - (0.5 * g) * V, make_feature(FeatureKind::CandidateVertexOnAntagonistEdge, w.iB, edge_a)};
  res.count = 1;
}

// 5b. Corner iA of the antagonist against edge `edge_b` of the candidate.
void corner_of_a(const Walk& w, std::uint32_t edge_b, double alert, ShadowOverlapResult& res) {
  const ConvexView &A = w.A, &B = w.B;
  const Vec2 V = w.V;
  const double line = dot(B.vertex[edge_b], V);
  const std::uint32_t jn = next(w.iA, A.count), jp = prev(w.iA, A.count);
  const double gn = line - dot(A.vertex[jn], V), gp = line - dot(A.vertex[jp], V);
  if (std::fmin(gn, gp) <= alert) {
    const std::uint32_t ea = gn <= gp ? w.iA : jp;
    res.count = edge_edge(A, ea, B, edge_b, alert, res.points);
    if (res.count > 0) return;
  }
  const Vec2 a = A.vertex[w.iA];
  const double g = line - dot(a, V);
  res.points[0] =
      ContactPoint{g, V, a + (0.5 * g) * V, make_feature(FeatureKind::AntagonistVertexOnCandidateEdge, w.iA, edge_b)};
  res.count = 1;
}

// 5c. V is normal to an edge of each polygon: parallel edges.
void parallel_edges(const Walk& w, CriticalEdges e, double h, double alert, ShadowOverlapResult& res) {
  const auto ea = static_cast<std::uint32_t>(e.a);
  res.count = edge_edge(w.A, ea, w.B, static_cast<std::uint32_t>(e.b), alert, res.points);
  if (res.count > 0) return;
  // parallel edges whose shadows on the tangent do not overlap: corner against corner,
  // reported as the candidate's corner on the antagonist's edge line
  const double g = -h;
  const Vec2 b = w.B.vertex[w.iB];
  res.points[0] =
      ContactPoint{g, w.V, b - (0.5 * g) * w.V, make_feature(FeatureKind::CandidateVertexOnAntagonistEdge, w.iB, ea)};
  res.count = g <= alert ? 1 : 0;
}

}  // namespace

ShadowOverlapResult shadow_overlap(const ConvexView& A, Vec2 gA, const ConvexView& B, Vec2 gB, double alert) {
  ShadowOverlapResult res;
  Walk w{A, B, Vec2{}};
  double h = start_walk(w, gA, gB);
  if (h < -alert) return res;  // the shadows are apart by more than the alert distance
  const Vec2 d0 = w.V;
  if (rotate(w, d0, h, alert, res.rotations) != WalkEnd::Breakpoint) return res;
  const CriticalEdges e = critical_edges(w);
  if (h < 0.0 && separated_distance(w, e) > alert) return res;
  // 5. The contact points: a corner against an edge, or two parallel edges.
  if (e.a >= 0 && e.b < 0)
    corner_of_b(w, static_cast<std::uint32_t>(e.a), alert, res);
  else if (e.b >= 0 && e.a < 0)
    corner_of_a(w, static_cast<std::uint32_t>(e.b), alert, res);
  else if (e.a >= 0 && e.b >= 0)
    parallel_edges(w, e, h, alert, res);
  return res;
}

}  // namespace nscd
