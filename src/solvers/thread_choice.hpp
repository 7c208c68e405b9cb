// nscd/solvers/thread_choice.hpp — how many threads a part of the step runs on (the solve, the
// loops around it), chosen by what the steps cost on this machine (MoreauJean,
// StepperOptions::solve_threads and loop_threads).
#pragma once

#include <array>

namespace nscd {

/// Chooses a part of the step's threads, step by step, among 1, 2, 4, … and the threads asked.
/// Every part gives the same bits on any count, so the choice moves the time only. Why measure
/// rather than fix a threshold: whether a second core pays on a few thousand contacts depends on
/// how long a cache line takes between the cores, which differs between machines and, on a
/// virtual machine, from minute to minute; and a core that another program keeps busy makes a
/// thread that waits on it spin for whole time slices (docs/benchmarks.md §11.19–§11.20).
///
/// Each epoch of kEpoch steps has a window of rounds from its step `first` on: in a round every
/// count runs kBlock steps in a row (the order reversed every other round, so that a drift weighs
/// on all alike). After each round the count of the lowest median cost is chosen (the counts
/// below the threads asked weighed by `favour`); the rounds stop at kRounds, or after one where
/// every other count's weighed median is kClear times the chosen one's or more. A block of steps
/// and a median: the broad phase is rebuilt on some steps only. Until the first rounds end, and
/// in a run of a few steps, the part runs on the most threads.
///
/// The chosen count runs the rest of the epoch, unless its cost drifts: when three quarters of
/// its last kWatch steps cost kDrift times the median that chose it or more (another program took
/// a core), or 1/kDrift times or less, a new epoch starts at once. Not
/// on a shorter burst: another run's rounds on the same cores slow this one's steps for a few
/// steps, and would start its rounds, which slow the other's.
class ThreadChoice {
 public:
  static constexpr int kEpoch = 1024, kBlock = 4, kRounds = 2, kMaxCounts = 10, kWatch = 16;
  static constexpr double kClear = 1.25, kDrift = 2.0, kFavourAsked = 1.25;
  /// A system chosen for with no contacts has grown once it has this many.
  static constexpr double kSizeFromNone = 64.0;

  /// Candidates for `threads` asked (≥ 1): 1, 2, 4, … below it, and itself; a new epoch whose
  /// rounds start at its step `first` (so that two parts' rounds need not overlap). A count
  /// below `threads` is chosen only where its cost times `favour` (≥ 1) is the lowest: a part
  /// that should run on the threads asked unless fewer are clearly cheaper (the solve) takes
  /// kFavourAsked, one that may as well use fewer where they cost the same (the loops) 1.
  void reset(int threads, int first = 0, double favour = 1.0);
  /// The count for the next step (the same until record() is called).
  int next() const;
  /// The cost of the step just run on next()'s count (seconds, or seconds a sweep: any measure
  /// the count changes, the same in every step), and the size of its system (contacts; 0: none):
  /// a size that doubled or halved since the rounds chose starts a new epoch, since a small
  /// system's choice need not suit a large one.
  void record(double cost, double size = 0.0);
  /// A new epoch from the next step (another part's cost drifted).
  void restart() {
    if (n_ > 1) step_ = 0, decided_ = false;
  }
  /// True while the next step is one of the rounds'.
  bool exploring() const { return n_ > 1 && !decided_ && step_ >= first_ && step_ < first_ + exploring_steps(); }
  /// True when the last record() started new rounds (its cost drifted).
  bool restarted() const { return restarted_; }
  /// The count chosen by the last rounds (the largest before any).
  int chosen() const { return counts_[best_]; }
  int candidates() const { return n_; }
  /// The steps of a full window of rounds.
  int exploring_steps() const { return n_ * kBlock * kRounds; }

 private:
  int trying() const;  ///< the candidate a step of the rounds runs on
  bool choose(int rounds);
  void watch(double cost, double size);

  std::array<int, kMaxCounts> counts_{1};
  using Costs = std::array<double, kBlock * kRounds>;
  std::array<Costs, kMaxCounts> costs_{};  ///< each count's steps in this epoch's rounds
  std::array<double, kWatch> recent_{};  ///< the chosen count's last steps since the rounds
  double chosen_cost_ = 0.0, chosen_size_ = 0.0;  ///< the median that chose it
  double favour_ = 1.0;  ///< the weight of the counts below the threads asked
  int n_ = 1, best_ = 0, step_ = 0, first_ = 0, seen_ = 0;
  bool decided_ = false;  ///< this epoch's rounds are over
  bool restarted_ = false;
};

}  // namespace nscd
