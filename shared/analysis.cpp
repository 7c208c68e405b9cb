// nscd/shared/analysis.cpp — see analysis.hpp.
#include "nscd/shared/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdint>
#include <vector>

#include "nscd/contactors/polyg.hpp"
#include "nscd/core/thread_share.hpp"
#include "nscd/shared/postpro.hpp"

namespace nscd::scenes {
namespace {

// Clips a convex polygon to the half-plane a·p <= b (Sutherland–Hodgman, one edge).
Polygon clip(const Polygon& in, Vec2 a, double b) {
  Polygon out;
  for (std::size_t i = 0; i < in.size(); ++i) {
    const Vec2 p = in[i], q = in[(i + 1) % in.size()];
    const double dp = dot(a, p) - b, dq = dot(a, q) - b;
    if (dp <= 0.0) out.push_back(p);
    if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) out.push_back(p + (dp / (dp - dq)) * (q - p));
  }
  return out;
}

double area(const Polygon& p) {
  double a2 = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) a2 += cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * a2;
}

}  // namespace

double packing_fraction(const Registry& reg, std::span<const BodyId> grains, const Window& w) {
  const double wa = (w.xmax - w.xmin) * (w.ymax - w.ymin);
  if (!(wa > 0.0)) return 0.0;
  std::vector<std::uint8_t> is_grain(reg.bodies.size(), 0);
  for (BodyId g : grains) is_grain[g.index()] = 1;
  double inside = 0.0;
  for (std::size_t k = 0; k < reg.polyg.size(); ++k) {
    if (!is_grain[reg.polyg.body[k].index()]) continue;
    Polygon p = world_polygon(reg, PolygId(static_cast<std::uint32_t>(k)));
    p = clip(p, {-1, 0}, -w.xmin);
    if (p.size() >= 3) p = clip(p, {1, 0}, w.xmax);
    if (p.size() >= 3) p = clip(p, {0, -1}, -w.ymin);
    if (p.size() >= 3) p = clip(p, {0, 1}, w.ymax);
    if (p.size() >= 3) inside += area(p);
  }
  return inside / wa;
}

Window bulk_window(const Registry& reg, std::span<const BodyId> grains, double box_width, double dmax) {
  if (grains.empty()) return {};
  std::vector<double> tops;
  tops.reserve(grains.size());
  for (BodyId g : grains) tops.push_back(reg.bodies.y[g.index()]);
  std::sort(tops.begin(), tops.end(), std::greater<>());
  const std::size_t n = std::max<std::size_t>(1, tops.size() / 20);
  double surface = 0.0;
  for (std::size_t i = 0; i < n; ++i) surface += tops[i];
  surface /= static_cast<double>(n);
  Window w{dmax, dmax, box_width - dmax, surface - 2.0 * dmax};
  if (w.ymax <= w.ymin || w.xmax <= w.xmin) return {};
  return w;
}

ContactNetwork contact_network(const Registry& reg, std::span<const BodyId> grains) {
  ContactNetwork net;
  if (grains.empty()) return net;
  // one definition of the network for the summaries and the time series (postpro.hpp)
  const NetworkSample s = NetworkMeter(reg, grains).measure(reg);
  net.coordination_number = s.coordination_number;
  net.double_contact_share = s.double_contact_share;
  net.active_pairs = s.active_pairs;
  net.active_points = s.active_points;
  return net;
}

double rms_speed(const Registry& reg, std::span<const BodyId> bodies, int threads) {
  struct Sums {
    double m = 0.0, e = 0.0;
  };
  double m = 0.0, e = 0.0;
  const std::size_t n = bodies.size();
  reduce_chunks<Sums>(
      sum_chunk_count(n), [n](std::size_t k) { return sum_chunk_start(n, k); }, threads,
      [&](std::size_t k0, std::size_t k1, Sums& s) {
        double cm = 0.0, ce = 0.0;  // (in registers)
        for (std::size_t k = k0; k < k1; ++k) {
          const std::size_t i = bodies[k].index();
          cm += reg.bodies.mass[i];
          ce += reg.bodies.mass[i] * (reg.bodies.vx[i] * reg.bodies.vx[i] + reg.bodies.vy[i] * reg.bodies.vy[i]);
        }
        s = {cm, ce};
      },
      [&](const Sums& s) { m += s.m, e += s.e; });
  return m > 0.0 ? std::sqrt(e / m) : 0.0;
}

double mean_speed(const Registry& reg, std::span<const BodyId> bodies) {
  double s = 0.0;
  for (BodyId b : bodies) s += std::hypot(reg.bodies.vx[b.index()], reg.bodies.vy[b.index()]);
  return bodies.empty() ? 0.0 : s / static_cast<double>(bodies.size());
}

double smallest_grain_size(const Registry& reg, std::span<const BodyId> grains) {
  std::vector<unsigned char> is_grain(reg.bodies.size(), 0);
  for (BodyId b : grains) is_grain[b.index()] = 1;
  double r = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < reg.polyg.size(); ++k)
    if (is_grain[reg.polyg.body[k].index()]) r = std::min(r, reg.polyg.radius[k]);
  for (std::size_t k = 0; k < reg.diskx.size(); ++k)
    if (is_grain[reg.diskx.body[k].index()]) r = std::min(r, reg.diskx.radius[k]);
  return std::isfinite(r) ? 2.0 * r : 0.0;
}

}  // namespace nscd::scenes
