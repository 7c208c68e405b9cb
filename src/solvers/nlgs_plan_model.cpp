// nscd/solvers/nlgs_plan_model.cpp — the planned sweep on a model (model_plan,
// nlgs_plan_model.hpp).
#include "nscd/solvers/nlgs_plan_model.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>

#include "nscd/core/error.hpp"

namespace nscd {

// A time of the plan's clock is a bundle where some lane is busy; it costs a unit where one of
// lanes 4–7 is (the lanes are numbered busiest first), half a unit where only lanes 0–3 are.
std::vector<double> bundle_costs(const SharePlan& s) {
  constexpr int K = ContactBundle::kLanes;
  std::vector<unsigned char> busy(s.span, 0);  // 1: lanes below K/2 only, 2: a lane from K/2
  for (int j = 0; j < K; ++j)
    for (const LaneRun& r : s.runs[j])
      for (std::uint32_t t = r.start; t < r.end; ++t)
        busy[t] = std::max(busy[t], static_cast<unsigned char>(j >= K / 2 ? 2 : 1));
  std::vector<double> cost{0.0};
  for (const unsigned char b : busy)
    if (b != 0) cost.push_back(cost.back() + (b == 2 ? 1.0 : 0.5));
  return cost;
}

namespace {

// One share on its clock: the sweep it is in (from 1), its next stop, its step, its time.
struct ShareClock {
  int sweep = 1;
  std::size_t stop = 0;
  std::uint32_t at = 0;
  double time = 0.0;
  std::vector<double> ends;  ///< when it ended each sweep
};

// What the shares published: (steps swept in all, when), in order.
using Published = std::vector<std::pair<std::int64_t, double>>;

}  // namespace

// Each share runs until it meets a wait that no publish answers yet; the shares take turns
// until every one has swept `sweeps` sweeps. A wait for share v's step `need` of this sweep (or,
// need ≤ 0, need + v's steps of the last one) ends when v publishes that step or a later one,
// or at once if v has.
PlanModel model_plan(const LanePlan& plan, double tail, int sweeps, double latency) {
  if (sweeps < 2) throw Error("plan model: at least 2 sweeps, got " + std::to_string(sweeps));
  const std::size_t T = plan.shares.size();
  PlanModel m;
  std::vector<std::vector<double>> cost(T);
  for (std::size_t u = 0; u < T; ++u) {
    cost[u] = bundle_costs(plan.shares[u]);
    if (cost[u].size() != plan.shares[u].bundles + 1)
      throw Error("plan model: a share's bundles do not match its lanes");
    m.work.push_back(cost[u].back() + (u == 0 ? tail : 0.0));
    m.total += m.work.back();
  }
  const int half = sweeps / 2;  // (the sweeps after it are measured)
  std::vector<ShareClock> clock(T);
  std::vector<Published> pub(T);
  auto steps = [&](std::size_t u) { return static_cast<std::int64_t>(plan.shares[u].steps()); };
  // share u up to its next wait not met, or its last sweep; false where it did not move
  auto advance = [&](std::size_t u) {
    const SharePlan& s = plan.shares[u];
    ShareClock& c = clock[u];
    bool moved = false;
    while (c.sweep <= sweeps) {
      const std::int64_t base = (c.sweep - 1) * steps(u);
      if (c.stop < s.stops.size() && std::min(s.stops[c.stop].at, s.bundles) <= c.at) {
        const ShareStop& x = s.stops[c.stop];
        if (x.share == ShareStop::kPublish) {
          pub[u].emplace_back(base + c.at, c.time);
        } else if (const std::int64_t need = (c.sweep - 1) * steps(x.share) + x.need; need > 0) {
          const Published& p = pub[x.share];
          const auto it =
              std::lower_bound(p.begin(), p.end(), need, [](const auto& e, std::int64_t v) { return e.first < v; });
          if (it == p.end()) return moved;
          if (it->second > c.time) {
            if (c.sweep > half) m.idle += it->second + latency - c.time, m.waits += 1.0;
            c.time = it->second + latency;
          }
        }
        ++c.stop;
        moved = true;
        continue;
      }
      const std::uint32_t next = c.stop < s.stops.size() ? std::min(s.stops[c.stop].at, s.bundles) : s.bundles;
      c.time += cost[u][next] - cost[u][c.at];
      c.at = next;
      moved = true;
      if (c.stop < s.stops.size() || c.at < s.bundles) continue;
      c.time += u == 0 ? tail : 0.0;  // the tail, then the sweep's end published
      pub[u].emplace_back(c.sweep * steps(u), c.time);
      c.ends.push_back(c.time);
      ++c.sweep, c.at = 0, c.stop = 0;
    }
    return moved;
  };
  for (;;) {
    bool moved = false, left = false;
    for (std::size_t u = 0; u < T; ++u) {
      moved = advance(u) || moved;
      left = left || clock[u].sweep <= sweeps;
    }
    if (!left) break;
    if (!moved) throw Error("plan model: the shares wait for each other in a cycle");
  }
  double first = 0.0, last = 0.0;
  for (const ShareClock& c : clock) {
    first = std::max(first, c.ends[static_cast<std::size_t>(half - 1)]);
    last = std::max(last, c.ends.back());
  }
  const double measured = sweeps - half;
  m.sweep = (last - first) / measured;
  m.waits /= measured;
  m.idle /= measured;
  return m;
}

}  // namespace nscd
