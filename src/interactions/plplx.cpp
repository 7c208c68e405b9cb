// nscd/interactions/plplx.cpp — see plplx.hpp.
#include "nscd/interactions/plplx.hpp"

#include <algorithm>
#include <cstring>

#include "nscd/core/error.hpp"
#include "nscd/core/thread_share.hpp"
#include "nscd/interactions/round_detection.hpp"
#include "nscd/interactions/shadow_overlap.hpp"

namespace nscd {

double grain_median_radius(const Registry& reg) {
  std::vector<double> r(reg.polyg.radius);
  r.insert(r.end(), reg.diskx.radius.begin(), reg.diskx.radius.end());
  if (r.empty()) return 0.0;
  std::nth_element(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(r.size() / 2), r.end());
  return r[r.size() / 2];
}

void classify_big_polygons(Registry& reg, double big_ratio) {
  auto& t = reg.polyg;
  if (t.empty()) return;
  const double median = grain_median_radius(reg);
  for (std::size_t p = 0; p < t.size(); ++p) t.is_big[p] = t.radius[p] > big_ratio * median ? 1 : 0;
}

namespace {

// From this many polygons (world geometry) or candidate pairs (narrow phase) on, the loop runs on
// the detector's threads: a polygon's or a pair's work (tens to hundreds of nanoseconds) outweighs
// a parallel region's fork and join from a few hundred on (docs/benchmarks.md, "Threads: the
// thresholds"). Each result is its own, written in pair order: the same for any threads.
constexpr std::ptrdiff_t kDetectParallelMin = 256;

bool kinematic(const BodyTable& b, std::size_t i) {
  return b.inv_mass_x[i] == 0.0 && b.inv_mass_y[i] == 0.0 && b.inv_inertia[i] == 0.0;
}

// 1. World vertices, edge normals, centres and alert-inflated boxes of every polygon.
void world_geometry(const Registry& reg, PlplxDetector& det, const Configuration& q) {
  const PolygTable& t = reg.polyg;
  det.world_vertex.resize(t.vertex.size());
  det.world_normal.resize(t.vertex.size());
  det.world_centre.resize(t.size());
  det.box.resize(t.size());
  const double half_alert = 0.5 * reg.params.alert;
  const auto np = static_cast<std::ptrdiff_t>(t.size());
#pragma omp parallel for num_threads(det.threads) schedule(static) if (det.threads > 1 && np >= kDetectParallelMin)
  for (std::ptrdiff_t p = 0; p < np; ++p) {
    const std::size_t b = t.body[p].index();
    const Rot2 r = Rot2::of(q.angle[b]);
    const Vec2 g{q.x[b], q.y[b]};
    Aabb box{1e300, 1e300, -1e300, -1e300};
    for (std::uint32_t k = t.first_vertex[p], e = k + t.vertex_count[p]; k < e; ++k) {
      const Vec2 v = g + r.apply(t.vertex[k]);
      det.world_vertex[k] = v;
      det.world_normal[k] = r.apply(t.edge_normal[k]);
      box = {std::min(box.xmin, v.x), std::min(box.ymin, v.y), std::max(box.xmax, v.x), std::max(box.ymax, v.y)};
    }
    det.world_centre[p] = g + r.apply(t.centre[p]);
    det.box[p] = {box.xmin - half_alert, box.ymin - half_alert, box.xmax + half_alert, box.ymax + half_alert};
  }
}

// 1b. Which polygons are still: body, kinematic state, configuration and world geometry bit for
//     bit those of the last detection (and the alert distance unchanged); then this detection's
//     become the last.
void mark_still(const Registry& reg, PlplxDetector& det, const Configuration& q) {
  const PolygTable& t = reg.polyg;
  PlplxDetector::Kept& k = det.kept;
  const std::size_t P = t.size();
  const bool comparable = k.vertex.size() == det.world_vertex.size() && k.centre.size() == P && k.q.size() == 3 * P &&
                          k.body.size() == P && k.kinematic.size() == P && k.alert == reg.params.alert;
  if (!comparable) {
    k.q.assign(3 * P, 0.0);
    k.body.assign(P, 0);
    k.kinematic.assign(P, 0);
  }
  k.still.assign(P, 0);
  auto same = [](const void* a, const void* b, std::size_t bytes) { return std::memcmp(a, b, bytes) == 0; };
  const auto np = static_cast<std::ptrdiff_t>(P);
#pragma omp parallel for num_threads(det.threads) schedule(static) if (det.threads > 1 && np >= kDetectParallelMin)
  for (std::ptrdiff_t i = 0; i < np; ++i) {
    const auto p = static_cast<std::size_t>(i);
    const std::size_t b = t.body[p].index();
    const double pose[3] = {q.x[b], q.y[b], q.angle[b]};
    const auto kin = static_cast<std::uint8_t>(kinematic(reg.bodies, b));
    const std::size_t v0 = t.first_vertex[p], nv = t.vertex_count[p];
    k.still[p] = comparable && k.body[p] == b && k.kinematic[p] == kin && same(&k.q[3 * p], pose, sizeof pose) &&
                 same(&k.vertex[v0], &det.world_vertex[v0], nv * sizeof(Vec2)) &&
                 same(&k.normal[v0], &det.world_normal[v0], nv * sizeof(Vec2)) &&
                 same(&k.centre[p], &det.world_centre[p], sizeof(Vec2));
    std::memcpy(&k.q[3 * p], pose, sizeof pose);
    k.body[p] = static_cast<std::uint32_t>(b);
    k.kinematic[p] = kin;
  }
  k.alert = reg.params.alert;
}

// 1c. The broad phase, on the boxes of step 1, and the kept narrow-phase results resized to
//     its kept list when that list was rebuilt. Returns whether results are kept at all.
bool broad_phase(Registry& reg, PlplxDetector& det, bool round) {
  const PolygTable& t = reg.polyg;
  PlplxDetector::Kept& kept = det.kept;
  const bool many = det.box.size() >= static_cast<std::size_t>(kDetectParallelMin);
  find_pairs_reusing(det.box,
                     round ? std::span<const std::uint8_t>(det.is_big) : std::span<const std::uint8_t>(t.is_big),
                     det.broad, many ? det.threads : 1);
  det.stats.candidate_pairs = det.broad.pairs.size();
  // the narrow phase's kept results follow the broad phase's kept list
  const bool keeping = det.broad.margin > 0.0 && det.broad.pair_near.size() == det.broad.pairs.size();
  if (keeping && kept.rebuilds != det.broad.rebuilds) {
    kept.stamp.assign(det.broad.near.size(), 0);
    kept.result.resize(det.broad.near.size());
    kept.roles.resize(det.broad.near.size());
    kept.rebuilds = det.broad.rebuilds;
  }
  return keeping;
}

// 2. Narrow phase on each candidate pair, in the broad phase's deterministic order. Two
//    polygons: shadow overlap, the antagonist is the big polygon if there is one, else the
//    lower index. Any other pair: the dispatch table of round_detection.cpp.
struct NarrowPhase {
  const Registry& reg;
  PlplxDetector& det;
  std::uint32_t P;  // contactor indices below P are POLYGs
  bool keeping;  // kept results follow the broad phase's kept list
  std::uint64_t now;  // this detection's stamp

  ShadowOverlapResult pair(std::uint32_t i, std::uint32_t j, ContactorId& an, ContactorId& cd) const {
    if (i >= P || j >= P) return collide_round(reg, det, i, j, an, cd);
    const PolygTable& t = reg.polyg;
    const std::size_t bi = t.body[i].index(), bj = t.body[j].index();
    if (bi == bj || (kinematic(reg.bodies, bi) && kinematic(reg.bodies, bj))) return {};
    const bool swap = t.is_big[j] && !t.is_big[i];
    const std::uint32_t a = swap ? j : i, b = swap ? i : j;
    an = ContactorId(a);  // a POLYG's ContactorId is its index (kind 0)
    cd = ContactorId(b);
    const ConvexView A{&det.world_vertex[t.first_vertex[a]], &det.world_normal[t.first_vertex[a]], t.vertex_count[a]};
    const ConvexView B{&det.world_vertex[t.first_vertex[b]], &det.world_normal[t.first_vertex[b]], t.vertex_count[b]};
    return shadow_overlap(A, det.world_centre[a], B, det.world_centre[b], reg.params.alert);
  }

  // … or kept: pair pq (polygons i, j) takes its result of the last detection if both polygons
  // are still and that result was computed or kept then (so from the same inputs)
  ShadowOverlapResult pair_kept(std::size_t pq, std::uint32_t i, std::uint32_t j, ContactorId& an, ContactorId& cd,
                                std::size_t& reused) const {
    if (!keeping || i >= P || j >= P) return pair(i, j, an, cd);
    PlplxDetector::Kept& kept = det.kept;
    const std::uint32_t k = det.broad.pair_near[pq];
    const bool still = kept.still[i] && kept.still[j];
    if (still && kept.stamp[k] == now - 1) {
      kept.stamp[k] = now;
      an = kept.roles[k].first;
      cd = kept.roles[k].second;
      ++reused;
      return kept.result[k];
    }
    const ShadowOverlapResult res = pair(i, j, an, cd);
    if (still) {  // worth keeping: the pair may well stay still
      kept.result[k] = res;
      kept.roles[k] = {an, cd};
      kept.stamp[k] = now;
    }
    return res;
  }
};

// 3. Each point of a pair in contact: local frame and lever arms, written at rows at, at + 1
//    (the table already that long).
void write_points(const Registry& reg, ContactTable& c, std::size_t at, const Configuration& q, ContactorId an,
                  ContactorId cd, const ShadowOverlapResult& res) {
  const PolygTable& t = reg.polyg;
  const std::size_t bcd = contactor_kind_bits(cd) == 0 ? t.body[cd.value].index() : body_of(reg, cd).index();
  const std::size_t ban = contactor_kind_bits(an) == 0 ? t.body[an.value].index() : body_of(reg, an).index();
  const Vec2 gcd{q.x[bcd], q.y[bcd]}, gan{q.x[ban], q.y[ban]};
  const std::int32_t law = contact_law_index(reg, reg.bodies.material[bcd], reg.bodies.material[ban]);
  for (int k = 0; k < res.count; ++k) {
    const ContactPoint& p = res.points[k];
    const Vec2 n = p.normal, tg = perp(n);
    const Vec2 rcd = p.point - gcd, ran = p.point - gan;
    const std::size_t i = at + static_cast<std::size_t>(k);
    c.candidate[i] = cd;
    c.antagonist[i] = an;
    c.cd_body[i] = BodyId(static_cast<std::uint32_t>(bcd));
    c.an_body[i] = BodyId(static_cast<std::uint32_t>(ban));
    c.feature[i] = p.feature;
    c.gap[i] = p.gap;
    c.normal[i] = n;
    c.point[i] = p.point;
    c.cd_rn[i] = cross(rcd, n);
    c.cd_rt[i] = cross(rcd, tg);
    c.an_rn[i] = cross(ran, n);
    c.an_rt[i] = cross(ran, tg);
    c.rn[i] = 0.0;
    c.rt[i] = 0.0;
    c.status[i] = ContactStatus::Open;
    c.law[i] = law;
    c.mu[i] = law >= 0 ? reg.contact_laws.laws[static_cast<std::size_t>(law)].mu : 0.0;
  }
}

// 2 and 3 over every candidate pair, in pair order; returns the pairs whose result was kept.
// The last detection's rows are written over (growing the table zeroes its new rows first, a
// pass over memory for nothing: it grows by the rows it lacks only), then cut to the points found.
std::size_t narrow_and_append(Registry& reg, const NarrowPhase& nar, const Configuration& q) {
  PlplxDetector& det = nar.det;
  ContactTable& c = reg.contacts;
  const auto& pairs = det.broad.pairs;
  std::size_t reused = 0;
  if (det.threads <= 1 || pairs.size() < static_cast<std::size_t>(kDetectParallelMin)) {
    std::size_t rows = 0;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      ContactorId an, cd;
      const ShadowOverlapResult res = nar.pair_kept(k, pairs[k].first, pairs[k].second, an, cd, reused);
      if (res.count == 0) continue;
      ++det.stats.contact_pairs;
      det.stats.double_contacts += res.count == 2;
      if (c.size() < rows + 2) c.resize(rows + 2);  // (the vectors' capacity grows geometrically)
      write_points(reg, c, rows, q, an, cd, res);
      rows += static_cast<std::size_t>(res.count);
    }
    c.resize(rows);
    return reused;
  }
  // On the threads, each its range of pairs: their results and points counted; then each
  // thread writes its own points from the row that the ranges before it leave free.
  det.narrow.resize(pairs.size());
  det.narrow_roles.resize(pairs.size());
  det.thread_counts.assign(static_cast<std::size_t>(det.threads), {});
  ordered_fill(
      pairs.size(), det.threads, det.narrow_rows,
      [&](std::size_t k, std::size_t t) {
        auto& [an, cd] = det.narrow_roles[k];
        det.narrow[k] = nar.pair_kept(k, pairs[k].first, pairs[k].second, an, cd, det.thread_counts[t].reused);
        return static_cast<std::size_t>(det.narrow[k].count);
      },
      [&](std::size_t rows) { c.resize(rows); },
      [&](std::size_t k, std::size_t at, std::size_t t) {
        const ShadowOverlapResult& res = det.narrow[k];
        if (res.count == 0) return std::size_t{0};
        ++det.thread_counts[t].contact_pairs;
        det.thread_counts[t].double_contacts += res.count == 2;
        write_points(reg, c, at, q, det.narrow_roles[k].first, det.narrow_roles[k].second, res);
        return static_cast<std::size_t>(res.count);
      });
  for (const PlplxDetector::ThreadCounts& n : det.thread_counts) {
    reused += n.reused;
    det.stats.contact_pairs += n.contact_pairs;
    det.stats.double_contacts += n.double_contacts;
  }
  return reused;
}

}  // namespace

DetectionStats detect_plplx(Registry& reg, PlplxDetector& det, const Configuration& q) {
  const PolygTable& t = reg.polyg;
  const BodyTable& bodies = reg.bodies;
  det.stats = {};
  const bool round = has_round_contactors(reg);
  if (t.empty() && !round) {
    reg.contacts.clear();
    return det.stats;
  }
  if (q.x.size() != bodies.size() || q.y.size() != bodies.size() || q.angle.size() != bodies.size())
    throw Error("detect_plplx: configuration size does not match the body table");

  PlplxDetector::Kept& kept = det.kept;
  // counted first: a detection that throws below also ends what the last one kept
  const std::uint64_t now = ++kept.detections;  // from 2 on: a stamp of 0 never matches now − 1
  det.world_vertex.swap(kept.vertex);  // the last detection's world geometry, kept for comparison
  det.world_normal.swap(kept.normal);
  det.world_centre.swap(kept.centre);
  world_geometry(reg, det, q);
  if (round) round_world_geometry(reg, det, q);  // boxes and big flags of every contactor kind
  mark_still(reg, det, q);
  const bool keeping = broad_phase(reg, det, round);
  const NarrowPhase nar{reg, det, static_cast<std::uint32_t>(t.size()), keeping, now};
  const std::size_t reused = narrow_and_append(reg, nar, q);
  det.stats.contact_points = reg.contacts.size();
  det.stats.kept_pairs = reused;
  return det.stats;
}

}  // namespace nscd
