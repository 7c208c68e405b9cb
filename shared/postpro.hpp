// nscd/shared/postpro.hpp — the time series that LMGC90's POSTPRO gives and the drivers write
// into steps.csv / cycles.csv (issue #11; every quantity defined in docs/output.md, "Time
// series"), from the forces of the last step: the contact network — coordination number,
// share of sliding contacts, the strong / weak split of Radjai et al. (1998), the count of
// contact points per solver status.
//
// Cheap at a CSV interval: NetworkMeter::measure is two passes over the contact table (the
// grain mask is built once, by the constructor), on threads where the table holds more than
// kSumWhole points. The other series come from the library: the kinetic energy
// (nscd::kinetic_energy, one pass over the bodies) and the energy the contacts and the spring
// dampers dissipate, integrated every step by the stepper (StepReport::contact_dissipation,
// damper_dissipation).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "nscd/registry/registry.hpp"

namespace nscd::scenes {

/// Contact points of reg.contacts by their status after the last solve. `open` counts the
/// points with no force (separated, or detected within the alert distance but not touching,
/// and points between materials without a contact law).
struct StatusCounts {
  std::size_t open = 0, stick = 0, slip_forward = 0, slip_backward = 0;
};

/// The contact network after a step. "Active" means a normal force r_n > 0.
struct NetworkSample {
  /// (grain ends of the active body pairs) / (number of grains): a grain–grain pair counts
  /// 2, a grain–wall (or grain–sleeper, grain–pad) pair 1 — the definition of
  /// contact_network (analysis.hpp) and of deposit's summary.txt.
  double coordination_number = 0.0;
  std::size_t active_pairs = 0;   ///< body pairs with at least one active point
  std::size_t active_points = 0;  ///< contact points with r_n > 0
  double double_contact_share = 0.0;  ///< share of the active pairs touching by two points
  /// (slip_forward + slip_backward) / active_points (0 when nothing is active)
  double sliding_share = 0.0;
  double mean_normal_force = 0.0;  ///< <r_n> over the active points (N/m)
  /// Radjai et al. (1998): active points with r_n > <r_n> (strong) and r_n <= <r_n> (weak),
  /// and the share of Σ r_n each carries (0 when nothing is active).
  std::size_t strong = 0, weak = 0;
  double strong_force_share = 0.0, weak_force_share = 0.0;
  StatusCounts status;
};

/// Measures the network of a scene whose grains are fixed at construction (the bodies that
/// count in the coordination number; walls, floor, sleeper and pads are partners only).
class NetworkMeter {
 public:
  /// Throws nscd::Error if a grain is not a body of `reg`.
  NetworkMeter(const Registry& reg, std::span<const BodyId> grains);
  /// Throws nscd::Error if `reg` has not the number of bodies it was built for. On `threads`
  /// threads beyond kSumWhole points: the same bits on any number (core/thread_share.hpp).
  NetworkSample measure(const Registry& reg, int threads = 1) const;

 private:
  std::vector<std::uint8_t> is_grain_;
  std::size_t grains_ = 0;
};

/// The CSV column names of a NetworkSample, in the order append_network_values writes them:
/// coordination_number, sliding_share, strong_contacts, weak_contacts, strong_force_share,
/// weak_force_share, status_open, status_stick, status_slip_forward, status_slip_backward.
const std::vector<std::string>& network_columns();
/// Appends the sample's values to a CSV row, in the order of network_columns().
void append_network_values(const NetworkSample& s, std::vector<double>& row);

}  // namespace nscd::scenes
