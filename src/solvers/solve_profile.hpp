// nscd/solvers/solve_profile.hpp — where a colored solve's threads spend its time: sweeping,
// waiting for each other, mixing, thread 0's serial parts, and the set-up (NlgsOptions::profile;
// drivers' --solve-profile, docs/user-guide.md §2.5b).
//
// Each thread's clock is read where the thread passes from one part to another (a lap), never
// inside a loop over contacts: about four reads a sweep, a few tens of nanoseconds each. A wait
// met at once is counted with the sweep around it; only a wait that spins is a lap of its own.
#pragma once

#include <chrono>

namespace nscd {

/// Seconds of a solve's region, part by part, summed over its threads (thread-seconds), and the
/// region's own wall seconds: the parts add up to `region` × `threads` but for the clock's reads
/// at the region's start and end.
struct SolveParts {
  double region = 0.0;  ///< wall seconds from the region's start to its end
  double thread_seconds = 0.0;  ///< region × the threads that ran it
  double sweeping = 0.0;  ///< the sweeps' own work (their bundles, contacts, the check's sums)
  double waiting = 0.0;  ///< spinning or asleep: a planned sweep's unmet stops, barriers
  double mixing = 0.0;  ///< the Anderson mixing's own work (each thread its entries)
  double serial = 0.0;  ///< thread 0 alone: the overflow and links, the sums' merge, γ, the moves
  double setup = 0.0;  ///< the plan, the bundles built and read back, the mixing's start

  SolveParts& operator+=(const SolveParts& o) {
    region += o.region, thread_seconds += o.thread_seconds, sweeping += o.sweeping, waiting += o.waiting;
    mixing += o.mixing, serial += o.serial, setup += o.setup;
    return *this;
  }
  /// The parts' sum (thread-seconds).
  double parts() const { return sweeping + waiting + mixing + serial + setup; }
};

/// One thread's clock for SolveParts: lap(part) adds the time since the last lap to `part`.
/// Does nothing unless started (the solve is not profiled).
class PartClock {
 public:
  using Clock = std::chrono::steady_clock;
  enum Part { Sweeping, Waiting, Mixing, Serial, Setup };

  void start(bool on) {
    on_ = on;
    sweeping_ = waiting_ = mixing_ = serial_ = setup_ = 0.0;
    if (on_) last_ = Clock::now();
  }
  void lap(Part p) {
    if (!on_) return;
    const Clock::time_point now = Clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    (p == Sweeping ? sweeping_ : p == Waiting ? waiting_ : p == Mixing ? mixing_ : p == Serial ? serial_ : setup_) += s;
  }
  /// Adds this thread's parts to `to`.
  void add_to(SolveParts& to) const {
    to.sweeping += sweeping_, to.waiting += waiting_, to.mixing += mixing_, to.serial += serial_, to.setup += setup_;
  }

 private:
  bool on_ = false;
  Clock::time_point last_{};
  double sweeping_ = 0.0, waiting_ = 0.0, mixing_ = 0.0, serial_ = 0.0, setup_ = 0.0;
};

}  // namespace nscd
