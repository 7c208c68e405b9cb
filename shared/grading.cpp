// nscd/shared/grading.cpp — see grading.hpp.
#include "nscd/shared/grading.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "nscd/core/error.hpp"
#include "nscd/io/text_reader.hpp"

namespace nscd::scenes {

double uniform01(std::mt19937_64& rng) {
  // mt19937_64 yields all 64 bits; keep the 53 a double can hold exactly.
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

std::uint64_t uniform_below(std::mt19937_64& rng, std::uint64_t n) {
  if (n == 0) throw Error("uniform_below: the range must not be empty");
  // Raw values >= limit belong to an incomplete block of n and would bias the modulo.
  const std::uint64_t max = std::numeric_limits<std::uint64_t>::max();
  const std::uint64_t limit = max - (max % n + 1) % n;  // the accepted values are [0, limit]
  std::uint64_t x = rng();
  while (x > limit) x = rng();
  return x % n;
}

Grading paper_grading() { return {{361, 0.010}, {242, 0.015}, {121, 0.020}}; }

Grading paper_grading(std::size_t n) {
  if (n == 0) throw Error("paper_grading: needs at least one grain");
  if (n > kMaxScaledGrains) throw Error("paper_grading: at most " + std::to_string(kMaxScaledGrains) + " grains, got " + std::to_string(n));
  Grading g = paper_grading();
  const std::size_t total = grain_count(g);
  // exact integer arithmetic: floor(count * n / total), then the largest remainders get one more
  std::vector<std::pair<std::size_t, std::size_t>> remainder;  // (remainder, class)
  std::size_t given = 0;
  for (std::size_t k = 0; k < g.size(); ++k) {
    const std::size_t scaled = g[k].count * n;  // < 361 * 1e12: no overflow
    remainder.emplace_back(static_cast<std::size_t>(scaled % total), k);
    g[k].count = static_cast<std::size_t>(scaled / total);
    given += g[k].count;
  }
  std::stable_sort(remainder.begin(), remainder.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t i = 0; given < n; ++i, ++given) ++g[remainder[i].second].count;
  return g;
}

Grading uniform_radius_grading(std::size_t n, double rmin, double rmax, std::uint64_t seed) {
  if (n == 0) throw Error("uniform_radius_grading: needs at least one grain");
  if (!std::isfinite(rmin) || !std::isfinite(rmax) || !(rmin > 0.0) || !(rmax >= rmin))
    throw Error("uniform_radius_grading: needs 0 < rmin <= rmax, got rmin = " + exact(rmin) +
                ", rmax = " + exact(rmax));
  std::mt19937_64 rng(seed);
  Grading g;
  g.reserve(n);
  for (std::size_t i = 0; i < n; ++i) g.push_back({1, 2.0 * (rmin + (rmax - rmin) * uniform01(rng))});
  return g;
}

std::size_t grain_count(const Grading& g) {
  std::size_t n = 0;
  for (const auto& c : g) n += c.count;
  return n;
}

double largest_diameter(const Grading& g) {
  double d = 0.0;
  for (const auto& c : g) d = std::max(d, c.diameter);
  return d;
}

std::vector<double> expand_grading(const Grading& g, std::uint64_t seed) {
  std::vector<double> d;
  d.reserve(grain_count(g));
  for (std::size_t k = 0; k < g.size(); ++k) {
    if (!std::isfinite(g[k].diameter) || !(g[k].diameter > 0.0))
      throw Error("expand_grading: class " + std::to_string(k) + " has diameter " + std::to_string(g[k].diameter) +
                  ", expected a finite value > 0");
    d.insert(d.end(), g[k].count, g[k].diameter);
  }
  // Fisher–Yates: position i takes a uniform pick among the positions [0, i].
  std::mt19937_64 rng(seed);
  for (std::size_t i = d.size(); i > 1; --i) std::swap(d[i - 1], d[uniform_below(rng, i)]);
  return d;
}

}  // namespace nscd::scenes
