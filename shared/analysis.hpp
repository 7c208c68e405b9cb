// nscd/shared/analysis.hpp — measures of a granular sample, for summaries and studies.
//
//   packing_fraction       area of the grains inside a rectangular window / window area (each
//                          polygon clipped to the window, Sutherland–Hodgman)
//   bulk_window            the window used by the drivers: the core of the layer, one largest
//                          diameter away from the floor and the walls, and two below the free
//                          surface (the mean top of the highest 5 % of the grains)
//   contact_network        from the forces of the last step: the coordination number
//                          z = (number of active body-pair contacts, counted once per grain
//                          involved) / number of grains — walls count as partners of a grain
//                          but not as grains — and the share of active pairs that touch by
//                          two points (edge–edge contacts).
#pragma once

#include <span>

#include "nscd/registry/registry.hpp"

namespace nscd::scenes {

struct Window {
  double xmin = 0.0, ymin = 0.0, xmax = 0.0, ymax = 0.0;
};

double packing_fraction(const Registry& reg, std::span<const BodyId> grains, const Window& w);

/// See the header comment; returns an empty window (xmax <= xmin) when the layer is too thin.
Window bulk_window(const Registry& reg, std::span<const BodyId> grains, double box_width, double largest_diameter);

struct ContactNetwork {
  double coordination_number = 0.0;
  double double_contact_share = 0.0;
  std::size_t active_pairs = 0;
  std::size_t active_points = 0;
};

ContactNetwork contact_network(const Registry& reg, std::span<const BodyId> grains);

/// sqrt(Σ m v² / Σ m) over the bodies (translation only): the rest criterion of the drivers; on
/// `threads` threads beyond kSumWhole bodies (the same bits on any number).
double rms_speed(const Registry& reg, std::span<const BodyId> bodies, int threads = 1);
/// Mean of |v| over the bodies (the paper's "average velocity", Fig. 7).
double mean_speed(const Registry& reg, std::span<const BodyId> bodies);

/// The overlap budget's default fraction of the smallest grain (drivers' --overlap-limit):
/// 5e-4 × 1 cm = 5 µm for the paper's sample, a tenth of the paper's smallest settlement step.
inline constexpr double kOverlapLimitFraction = 5e-4;
/// Twice the smallest circumscribed radius of the POLYG and DISKx contactors of the bodies (m);
/// 0 when they have none.
double smallest_grain_size(const Registry& reg, std::span<const BodyId> grains);

}  // namespace nscd::scenes
