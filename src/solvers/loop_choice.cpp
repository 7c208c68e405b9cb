// nscd/solvers/loop_choice.cpp — see loop_choice.hpp.
#include "nscd/solvers/loop_choice.hpp"

#include <algorithm>

namespace nscd {

void LoopThreadChoice::reset(int threads) {
  n_ = 0;
  for (int c = 1; c < threads && n_ + 1 < kMaxCounts; c *= 2) counts_[n_++] = c;
  counts_[n_++] = std::max(threads, 1);
  best_ = n_ - 1;
  step_ = 0;
}

// Step s of an epoch's rounds: round s / (n·kBlock), block (s / kBlock) mod n; the most threads
// first in even rounds (a run of a few steps has its loops on the threads asked), the fewest
// first in odd ones.
int LoopThreadChoice::trying() const {
  const int round = step_ / (n_ * kBlock), block = (step_ / kBlock) % n_;
  return round % 2 == 0 ? n_ - 1 - block : block;
}

int LoopThreadChoice::next() const {
  return n_ == 1 || step_ >= exploring_steps() ? counts_[best_] : counts_[trying()];
}

void LoopThreadChoice::record(double seconds) {
  if (n_ == 1) return;
  if (step_ < exploring_steps()) costs_[trying()][step_ / (n_ * kBlock) * kBlock + step_ % kBlock] = seconds;
  if (++step_ == exploring_steps()) choose();
  if (step_ == kEpoch) step_ = 0;
}

// The lowest median; a tie goes to the fewer threads.
void LoopThreadChoice::choose() {
  double best = 0.0;
  for (int k = 0; k < n_; ++k) {
    Costs c = costs_[k];
    std::nth_element(c.begin(), c.begin() + c.size() / 2, c.end());
    const double median = c[c.size() / 2];
    if (k == 0 || median < best) best = median, best_ = k;
  }
}

}  // namespace nscd
