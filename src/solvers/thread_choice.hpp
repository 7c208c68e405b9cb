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
/// thread that waits on it spin for whole time slices (docs/record/benchmarks-history.md
/// §11.19–§11.20).
///
/// Each epoch has a window of rounds from its step `first` on: in a round every count runs
/// kBlock steps in a row, first the count the part ran on before (the lead: one thread in the
/// first epoch), then the others from the most threads to the fewest, the order reversed every
/// other round so that a drift weighs on all alike. A count's cost is the median of its steps
/// (the broad phase is rebuilt on some steps only), or their mean where that is kStall times the
/// median or more: where a thread shares its core with another program, most steps run at full
/// speed and a few wait whole time slices. After each round the count of the lowest cost is
/// chosen (the counts below the threads asked weighed by `favour`). The rounds stop at kRounds,
/// or after one where every other count's weighed median is kClear times the chosen one's or
/// more. Where a thread has no core of its own (another run
/// on the same cores) each step costs tens of time slices, so a block ends early: after its
/// first step where it cost kRejectAtOnce times another count's cheapest or more, after its
/// second where both cost kReject times that or more.
///
/// An epoch lasts kEpoch steps, twice as many each time its rounds choose the count the last
/// ones chose (up to kEpochMax), so that a long run measures again seldom where nothing changes.
/// The chosen count runs the rest of the epoch, unless its cost drifts: when three quarters of
/// its last kWatch steps cost kDrift times the median that chose it or more (another program took
/// a core), or 1/kDrift times or less, or when their mean is kStall times it or more, a new epoch
/// starts at once. Not on a shorter burst:
/// another run's rounds on the same cores slow this one's steps for a few steps, and would start
/// its rounds, which slow the other's. Nor on a rise at the fewest threads, which more threads
/// would not undo.
class ThreadChoice {
 public:
  static constexpr int kEpoch = 1024, kEpochMax = 8 * kEpoch, kBlock = 4, kRounds = 2, kMaxCounts = 10, kWatch = 16;
  static constexpr double kClear = 1.25, kDrift = 2.0, kFavourAsked = 1.25, kReject = 3.0, kRejectAtOnce = 32.0,
                          kStall = 4.0;
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
  /// A new epoch from the next step, led by the count chosen: another part's began (`afresh`:
  /// because its cost drifted; an epoch of kEpoch steps).
  void restart(bool afresh = true) {
    if (n_ > 1) new_epoch(afresh);
  }
  /// From now on (until reset) a new epoch starts only at restart(): the part follows another's
  /// epochs, so that the two parts' rounds keep their order.
  void follow() { own_epochs_ = false; }
  /// True while the next step is one of the rounds'.
  bool exploring() const { return n_ > 1 && !decided_ && step_ >= first_ && step_ < first_ + exploring_steps(); }
  /// True while this epoch's rounds have not started (the steps before `first`).
  bool pending() const { return n_ > 1 && !decided_ && step_ < first_; }
  /// While pending(): the count the part runs on until the rounds (another part's choice), which
  /// they try first. The largest candidate not above `count`.
  void lead(int count);
  /// True when the last record() started new rounds (its cost drifted).
  bool restarted() const { return restarted_; }
  /// True when a new epoch started at the last record() or since (its cost drifted, or its
  /// kEpoch steps and more ended, or restart()); never with one candidate.
  bool began() const { return began_; }
  /// The count chosen by the last rounds (one thread before any, or the lead given).
  int chosen() const { return counts_[best_]; }
  int candidates() const { return n_; }
  /// The steps of a full window of rounds.
  int exploring_steps() const { return n_ * kBlock * kRounds; }

 private:
  int trying() const;  ///< the candidate a step of the rounds runs on
  double cost_of(int k, int rounds) const;
  bool choose(int rounds);
  int cut_block(int k, double cost) const;
  bool drifted(double cost, double size);
  void new_epoch(bool afresh);

  std::array<int, kMaxCounts> counts_{1};
  using Costs = std::array<double, kBlock * kRounds>;
  std::array<Costs, kMaxCounts> costs_{};  ///< each count's steps in this epoch's rounds
  std::array<double, kMaxCounts> lowest_{};  ///< each count's cheapest step in this epoch's rounds
  std::array<double, kWatch> recent_{};  ///< the chosen count's last steps since the rounds
  double chosen_cost_ = 0.0, chosen_size_ = 0.0;  ///< the median that chose it
  double favour_ = 1.0;  ///< the weight of the counts below the threads asked
  int n_ = 1, best_ = 0, lead_ = 0, step_ = 0, first_ = 0, seen_ = 0;
  int epoch_ = kEpoch, last_choice_ = 0;  ///< this epoch's length; the count the last rounds chose
  bool decided_ = false;  ///< this epoch's rounds are over
  bool restarted_ = false, began_ = false;
  bool own_epochs_ = true;  ///< false: new epochs only at restart() (follow())
};

}  // namespace nscd
