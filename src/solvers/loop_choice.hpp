// nscd/solvers/loop_choice.hpp — how many threads a step's loops around the solve run on,
// chosen by what the steps cost on this machine (MoreauJean, StepperOptions::loop_threads).
#pragma once

#include <array>

namespace nscd {

/// Chooses the threads of the loops around the solve (the free state, the detection, the records,
/// the warm start, the layout's copy, the guard, the projection, the end of the step), step by
/// step, among 1, 2, 4, … and the threads asked. Every one of those loops gives the same bits on
/// any count, so the choice moves the time only. Why measure rather than fix a threshold: whether
/// a second core pays on a loop of a few thousand contacts depends on how long a cache line takes
/// between the cores, and that differs between machines and, on a virtual machine, from minute to
/// minute (docs/benchmarks.md §11.19). Each epoch of kEpoch steps opens with kRounds rounds in
/// which every count runs kBlock steps in a row (the order reversed every other round, so that a
/// drift weighs on all alike); the count whose steps had the lowest median cost runs the rest of
/// the epoch. A block of steps and a median: the broad phase is rebuilt on some steps only. An
/// epoch starts on the most threads, so that a run of a few steps has its loops on the threads.
class LoopThreadChoice {
 public:
  static constexpr int kEpoch = 1024, kBlock = 4, kRounds = 2, kMaxCounts = 10;

  /// Candidates for `threads` asked (≥ 1): 1, 2, 4, … below it, and itself; a new epoch.
  void reset(int threads);
  /// The count for the next step (the same until record() is called).
  int next() const;
  /// The cost in seconds of the step just run on next()'s count: the parts of the step the
  /// count changes (all but the solve).
  void record(double seconds);
  /// The count chosen by the last epoch's rounds (the largest before any).
  int chosen() const { return counts_[best_]; }
  int candidates() const { return n_; }

 private:
  int exploring_steps() const { return n_ * kBlock * kRounds; }
  int trying() const;  ///< the candidate a step of the rounds runs on
  void choose();

  std::array<int, kMaxCounts> counts_{1};
  using Costs = std::array<double, kBlock * kRounds>;
  std::array<Costs, kMaxCounts> costs_{};  ///< each count's steps this epoch
  int n_ = 1, best_ = 0, step_ = 0;  ///< candidates, the chosen one, the step in the epoch
};

}  // namespace nscd
