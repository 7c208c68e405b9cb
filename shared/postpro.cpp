// nscd/shared/postpro.cpp — see postpro.hpp.
#include "nscd/shared/postpro.hpp"

#include <string>

#include "nscd/core/error.hpp"
#include "nscd/core/thread_share.hpp"

namespace nscd::scenes {

NetworkMeter::NetworkMeter(const Registry& reg, std::span<const BodyId> grains)
    : is_grain_(reg.bodies.size(), 0), grains_(grains.size()) {
  for (BodyId g : grains) {
    if (!g.valid() || g.index() >= is_grain_.size())
      throw Error("NetworkMeter: grain " + std::to_string(g.index()) + " is not a body of the scene (" +
                  std::to_string(is_grain_.size()) + " bodies)");
    is_grain_[g.index()] = 1;
  }
}

namespace {

// One chunk's part of the network's first pass: its pairs, points, statuses and Σ r_n.
struct PairSums {
  std::size_t active_pairs = 0, active_points = 0, doubles = 0, ends = 0;
  std::size_t by_status[4] = {};  // counted by code (a switch mispredicted at every point)
  double sum_rn = 0.0;
};

// The first pass over points k0 … k1−1, whole pairs (detection lists the points of a body
// pair consecutively).
void pair_sums(const ContactTable& c, const std::vector<std::uint8_t>& is_grain, std::size_t k0, std::size_t k1,
               PairSums& p) {
  for (std::size_t k = k0; k < k1;) {
    std::size_t j = k, active = 0;
    while (j < k1 && c.cd_body[j] == c.cd_body[k] && c.an_body[j] == c.an_body[k]) {
      if (c.rn[j] > 0.0) {
        ++active;
        p.sum_rn += c.rn[j];
      }
      ++p.by_status[static_cast<std::size_t>(c.status[j]) & 3u];
      ++j;
    }
    if (active > 0) {
      ++p.active_pairs;
      p.active_points += active;
      p.doubles += active >= 2;
      p.ends += is_grain[c.cd_body[k].index()] + is_grain[c.an_body[k].index()];
    }
    k = j;
  }
}

}  // namespace

NetworkSample NetworkMeter::measure(const Registry& reg, int threads) const {
  if (reg.bodies.size() != is_grain_.size())
    throw Error("NetworkMeter: built for " + std::to_string(is_grain_.size()) + " bodies, the scene has " +
                std::to_string(reg.bodies.size()));
  NetworkSample s;
  const ContactTable& c = reg.contacts;
  // 1. Pairs, statuses, Σ r_n: chunks of points (sum_chunk_count), each moved on to a pair's start.
  const std::size_t n = c.size(), chunks = sum_chunk_count(n);
  std::vector<std::size_t> bounds;  // (several chunks only)
  for (std::size_t k = 0; k <= chunks && chunks > 1; ++k) {
    std::size_t b = sum_chunk_start(n, k);
    while (k > 0 && b < n && c.cd_body[b] == c.cd_body[b - 1] && c.an_body[b] == c.an_body[b - 1]) ++b;
    bounds.push_back(b);
  }
  auto bound = [&](std::size_t k) { return chunks > 1 ? bounds[k] : sum_chunk_start(n, k); };
  std::size_t ends = 0, doubles = 0, by_status[4] = {};  // (ends: grain ends of the active pairs)
  double sum_rn = 0.0;
  reduce_chunks<PairSums>(
      chunks, bound, threads, [&](std::size_t k0, std::size_t k1, PairSums& p) { pair_sums(c, is_grain_, k0, k1, p); },
      [&](const PairSums& p) {
        s.active_pairs += p.active_pairs;
        s.active_points += p.active_points;
        doubles += p.doubles;
        ends += p.ends;
        for (int q = 0; q < 4; ++q) by_status[q] += p.by_status[q];
        sum_rn += p.sum_rn;
      });
  static_assert(static_cast<int>(ContactStatus::Open) == 0 && static_cast<int>(ContactStatus::Stick) == 1 &&
                static_cast<int>(ContactStatus::SlipForward) == 2 && static_cast<int>(ContactStatus::SlipBackward) == 3);
  s.status.open = by_status[0];
  s.status.stick = by_status[1];
  s.status.slip_forward = by_status[2];
  s.status.slip_backward = by_status[3];
  if (s.active_pairs) s.double_contact_share = static_cast<double>(doubles) / static_cast<double>(s.active_pairs);
  if (grains_) s.coordination_number = static_cast<double>(ends) / static_cast<double>(grains_);
  if (s.active_points == 0) return s;
  s.sliding_share = static_cast<double>(s.status.slip_forward + s.status.slip_backward) / static_cast<double>(s.active_points);
  // 2. The strong / weak split about the mean normal force.
  s.mean_normal_force = sum_rn / static_cast<double>(s.active_points);
  struct Strong {
    std::size_t count = 0;
    double rn = 0.0;
  };
  double strong_rn = 0.0;
  reduce_chunks<Strong>(
      chunks, [n](std::size_t k) { return sum_chunk_start(n, k); }, threads,
      [&](std::size_t k0, std::size_t k1, Strong& p) {
        for (std::size_t k = k0; k < k1; ++k)
          if (c.rn[k] > s.mean_normal_force) {
            ++p.count;
            p.rn += c.rn[k];
          }
      },
      [&](const Strong& p) { s.strong += p.count, strong_rn += p.rn; });
  s.weak = s.active_points - s.strong;
  s.strong_force_share = strong_rn / sum_rn;
  s.weak_force_share = (sum_rn - strong_rn) / sum_rn;
  return s;
}

const std::vector<std::string>& network_columns() {
  static const std::vector<std::string> names = {
      "coordination_number", "sliding_share",       "strong_contacts", "weak_contacts",       "strong_force_share",
      "weak_force_share",    "status_open",         "status_stick",    "status_slip_forward", "status_slip_backward"};
  return names;
}

void append_network_values(const NetworkSample& s, std::vector<double>& row) {
  row.insert(row.end(), {s.coordination_number, s.sliding_share, double(s.strong), double(s.weak), s.strong_force_share,
                         s.weak_force_share, double(s.status.open), double(s.status.stick), double(s.status.slip_forward),
                         double(s.status.slip_backward)});
}

}  // namespace nscd::scenes
