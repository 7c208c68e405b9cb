// nscd/shared/grading.hpp — grain-size distributions ("gradings") for the scene builders, and
// the small deterministic random helpers every scene uses.
//
// A Grading is a list of classes (count, circumscribed diameter): the diameter of the circle
// through the vertices of a regular polygon, the size the paper quotes for its pentagons.
//
//   paper_grading()               361 × 1 cm, 242 × 1.5 cm, 121 × 2 cm pentagons: the ballast
//                                 grading at scale one third (Saussine et al. 2006, §3).
//   paper_grading(n)              the same three classes in the same proportions (1/2, 1/3, 1/6),
//                                 n grains in all (largest remainders: counts sum to n).
//   uniform_radius_grading(...)   n grains, circumradius uniform in [rmin, rmax] (the LMGC90
//                                 comparison uses 700 pentagons with r in [12.5, 25] mm).
//   expand_grading(g, seed)       one diameter per grain, classes mixed by a seeded shuffle.
//
// Determinism: every random draw comes from std::mt19937_64, whose raw 64-bit output is fixed
// by the C++ standard. The mapping to [0, 1) and to bounded integers is written here rather
// than taken from std::uniform_*_distribution (implementation-defined), so a seed gives the
// same scene with every standard library.
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace nscd::scenes {

struct GradingClass {
  std::size_t count = 0;  ///< number of grains of this class
  double diameter = 0.0;  ///< circumscribed diameter (m)
};
using Grading = std::vector<GradingClass>;

/// 361 × 0.01 m, 242 × 0.015 m, 121 × 0.02 m (724 grains), in this order.
Grading paper_grading();

/// The paper's grading scaled to n grains: the counts 361, 242, 121 times n / 724, rounded by
/// largest remainders (ties to the smaller class) so that they sum to n; paper_grading(724)
/// is paper_grading(). Classes rounded to zero grains are kept with count 0. Throws
/// nscd::Error for n = 0 or n > kMaxScaledGrains.
inline constexpr std::size_t kMaxScaledGrains = 1'000'000'000'000;
Grading paper_grading(std::size_t n);

/// n classes of one grain each, circumradius drawn uniformly in [rmin, rmax] (m) from `seed`.
/// Throws nscd::Error unless n > 0 and 0 < rmin <= rmax (all finite).
Grading uniform_radius_grading(std::size_t n, double rmin, double rmax, std::uint64_t seed);

/// Total number of grains of a grading.
std::size_t grain_count(const Grading& g);
/// Largest diameter of a grading (0 for an empty grading).
double largest_diameter(const Grading& g);

/// One diameter per grain (count of each class repeated), then shuffled by Fisher–Yates from
/// `seed`: the order in which the grains are placed on a lattice. Throws nscd::Error on a
/// class with a diameter that is not finite and > 0.
std::vector<double> expand_grading(const Grading& g, std::uint64_t seed);

// ---- deterministic random helpers (shared by the scene builders) -----------------------

/// Uniform double in [0, 1): the top 53 bits of one raw draw, times 2^-53.
double uniform01(std::mt19937_64& rng);
/// Uniform integer in [0, n), n > 0, without modulo bias (rejection of the incomplete last
/// block of 2^64 mod n values).
std::uint64_t uniform_below(std::mt19937_64& rng, std::uint64_t n);

}  // namespace nscd::scenes
