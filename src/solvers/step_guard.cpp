// nscd/solvers/step_guard.cpp — see step_guard.hpp.
#include "nscd/solvers/step_guard.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/solvers/thread_range.hpp"

namespace nscd {
namespace {

constexpr int kListed = 5;
constexpr double kHuge = 1e308;  // bodies or contacts named in a message; the rest are counted

bool finite3(double a, double b, double c) { return std::isfinite(a) && std::isfinite(b) && std::isfinite(c); }

// Collects the offenders of one check into one message.
class Offenders {
 public:
  explicit Offenders(std::string what) : what_(std::move(what)) { out_.precision(17); }
  std::ostringstream& add() {
    ++count_;
    if (count_ <= kListed) {
      out_ << (count_ == 1 ? "" : "; ");
      return out_;
    }
    return sink_;
  }
  std::string message() const {
    if (count_ == 0) return {};
    std::string m = what_ + ": " + out_.str();
    if (count_ > kListed) m += "; and " + std::to_string(count_ - kListed) + " more";
    return m;
  }

 private:
  std::string what_;
  std::ostringstream out_, sink_;
  int count_ = 0;
};

}  // namespace

std::string body_label(const Registry& reg, std::size_t body) {
  const auto& names = reg.bodies.name;
  const std::string name = body < names.size() ? names[body] : std::string("?");
  return "'" + name + "' (#" + std::to_string(body) + ")";
}

std::string check_start_state(const Registry& reg, int threads) {
  const BodyTable& b = reg.bodies;
  const bool ok = all_of_index(b.size(), light_threads(b.size(), threads), [&b](std::size_t i) {
    return finite3(b.x[i], b.y[i], b.angle[i]) && finite3(b.vx[i], b.vy[i], b.spin[i]);
  });
  if (ok) return {};
  Offenders list("non-finite state at the start of the step (written outside the stepper?)");
  for (std::size_t i = 0; i < b.size(); ++i)
    if (!finite3(b.x[i], b.y[i], b.angle[i]) || !finite3(b.vx[i], b.vy[i], b.spin[i]))
      list.add() << "body " << body_label(reg, i) << " q = (" << b.x[i] << ", " << b.y[i] << ", " << b.angle[i]
                 << "), u = (" << b.vx[i] << ", " << b.vy[i] << ", " << b.spin[i] << ")";
  return list.message();
}

std::string check_free_state(const Registry& reg, std::span<const double> qm_x, std::span<const double> qm_y,
                             std::span<const double> qm_a, std::span<const SolverBody> free, double t_m,
                             int threads) {
  const bool ok = all_of_index(free.size(), light_threads(free.size(), threads), [&](std::size_t i) {
    return finite3(qm_x[i], qm_y[i], qm_a[i]) && finite3(free[i].vx, free[i].vy, free[i].w);
  });
  if (ok) return {};
  Offenders list("non-finite free state");
  for (std::size_t i = 0; i < free.size(); ++i) {
    if (!finite3(free[i].vx, free[i].vy, free[i].w)) {
      const BodyForce f = external_force(reg, BodyId(static_cast<std::uint32_t>(i)), t_m);
      auto& s = list.add();
      s << "body " << body_label(reg, i) << " u_free = (" << free[i].vx << ", " << free[i].vy << ", " << free[i].w
        << ")";
      if (!finite3(f.fx, f.fy, f.m))
        s << " from its external force (" << f.fx << ", " << f.fy << ", " << f.m << ") at t_m = " << t_m
          << " (a force function returned a non-finite value)";
      else
        s << " (an imposed velocity or an overflow of u + h F/m)";
    } else if (!finite3(qm_x[i], qm_y[i], qm_a[i])) {
      list.add() << "body " << body_label(reg, i) << " q_m = (" << qm_x[i] << ", " << qm_y[i] << ", " << qm_a[i]
                 << ") overflows (q + (1 - theta) h u)";
    }
  }
  return list.message();
}

std::string check_solution(const Registry& reg, const ContactSystem& sys, std::span<const double> qm_x,
                           std::span<const double> qm_y, std::span<const double> qm_a, double h, double theta,
                           int threads) {
  // the contacts' impulses, the links', the bodies' u_f and q_f: one read of each, the contacts
  // and the bodies on the threads from kLightParallelMin on
  const std::vector<SolverContact>& c = sys.contacts;
  const std::vector<SolverBody>& u = sys.bodies;
  bool ok = all_of_index(c.size(), light_threads(c.size(), threads),
                         [&c](std::size_t a) { return std::isfinite(c[a].pn) && std::isfinite(c[a].pt); });
  for (const SolverLink& l : sys.links) ok = ok && std::isfinite(l.p);
  ok = ok && all_of_index(u.size(), light_threads(u.size(), threads), [&](std::size_t i) {
         return finite3(u[i].vx, u[i].vy, u[i].w) &&
                finite3(qm_x[i] + theta * h * u[i].vx, qm_y[i] + theta * h * u[i].vy, qm_a[i] + theta * h * u[i].w);
       });
  if (ok) return {};
  Offenders list("non-finite solution");
  for (std::size_t a = 0; a < sys.contacts.size(); ++a) {
    const SolverContact& s = sys.contacts[a];
    if (!std::isfinite(s.pn) || !std::isfinite(s.pt))
      list.add() << "contact " << a << " of the step's problem, between " << body_label(reg, s.cd) << " and "
                 << body_label(reg, s.an) << ", impulse (" << s.pn << ", " << s.pt << ")";
  }
  for (const SolverLink& l : sys.links)
    if (!std::isfinite(l.p))
      list.add() << "spring link " << l.row << " between " << body_label(reg, l.cd) << " and " << body_label(reg, l.an)
                 << " impulse " << l.p;
  for (std::size_t i = 0; i < sys.bodies.size(); ++i) {
    const SolverBody& u = sys.bodies[i];
    if (!finite3(u.vx, u.vy, u.w))
      list.add() << "body " << body_label(reg, i) << " u_f = (" << u.vx << ", " << u.vy << ", " << u.w << ")";
    else if (!finite3(qm_x[i] + theta * h * u.vx, qm_y[i] + theta * h * u.vy, qm_a[i] + theta * h * u.w))
      list.add() << "body " << body_label(reg, i) << " q_f overflows (u_f = (" << u.vx << ", " << u.vy << ", " << u.w
                 << "))";
  }
  return list.message();
}

namespace {

// Polygons k0 … k1−1 added to `out` (its resolution still the largest coordinate).
void travel_of(const Registry& reg, std::span<const SolverBody> end, double h, std::size_t k0, std::size_t k1,
               AlertTravel& out) {
  AlertTravel a = out;  // (in registers: `out` may share a cache line with another thread's)
  const BodyTable& b = reg.bodies;
  const PolygTable& p = reg.polyg;
  const double alert = reg.params.alert;
  for (std::size_t k = k0; k < k1; ++k) {
    const std::size_t i = p.body[k].index();
    // speeds as sqrt(x² + y²), not std::hypot (slow enough to show in a step's cost): finite velocities
    // above 1e154 m/s would give inf, a travel beyond any alert, as they should
    const double v =
        std::sqrt(std::max(b.vx[i] * b.vx[i] + b.vy[i] * b.vy[i], end[i].vx * end[i].vx + end[i].vy * end[i].vy));
    const double w = std::max(std::abs(b.spin[i]), std::abs(end[i].w));
    const double travel = h * (v + w * p.radius[k]);
    if (travel > alert) ++a.skips;
    a.resolution = std::max({a.resolution, std::abs(b.x[i]), std::abs(b.y[i])});  // the largest coordinate, for now
    if (travel > a.max_travel) {
      a.max_travel = travel;
      a.fastest = static_cast<std::int64_t>(i);
    }
  }
  out = a;
}

}  // namespace

AlertTravel alert_travel(const Registry& reg, std::span<const SolverBody> end, double h, int threads) {
  AlertTravel a;
  const std::size_t n = reg.polyg.size();
  if (const int t = light_threads(n, threads); t > 1) {
    // each thread its range; the ranges in order, a later one's fastest only if strictly faster
    std::vector<AlertTravel> part;
    each_range_into(n, t, part,
                    [&](std::size_t k0, std::size_t k1, AlertTravel& p) { travel_of(reg, end, h, k0, k1, p); });
    for (const AlertTravel& p : part) {
      a.skips += p.skips;
      a.resolution = std::max(a.resolution, p.resolution);
      if (p.max_travel > a.max_travel) {
        a.max_travel = p.max_travel;
        a.fastest = p.fastest;
      }
    }
  } else {
    travel_of(reg, end, h, 0, n, a);
  }
  a.resolution = std::nextafter(a.resolution, kHuge) - a.resolution;
  return a;
}

}  // namespace nscd
