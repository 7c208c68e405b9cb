// nscd/solvers/thread_choice.cpp — see thread_choice.hpp.
#include "nscd/solvers/thread_choice.hpp"

#include <algorithm>

namespace nscd {
namespace {

// the k-th smallest of the first n entries of a copy
template <std::size_t N>
double kth(std::array<double, N> c, int n, int k) {
  std::nth_element(c.begin(), c.begin() + k, c.begin() + n);
  return c[static_cast<std::size_t>(k)];
}
// the upper median of the first n entries
template <std::size_t N>
double median(const std::array<double, N>& c, int n) {
  return kth(c, n, n / 2);
}

}  // namespace

void ThreadChoice::reset(int threads, int first, double favour) {
  favour_ = std::max(favour, 1.0);
  n_ = 0;
  for (int c = 1; c < threads && n_ + 1 < kMaxCounts; c *= 2) counts_[n_++] = c;
  counts_[n_++] = std::max(threads, 1);
  best_ = n_ - 1;
  step_ = 0;
  first_ = std::clamp(first, 0, kEpoch - exploring_steps());
  decided_ = restarted_ = false;
  seen_ = 0;
  chosen_cost_ = 0.0;
}

// Step s of the rounds: round s / (n·kBlock), block (s / kBlock) mod n; the most threads first in
// even rounds (a run of a few steps runs on the threads asked), the fewest first in odd ones.
int ThreadChoice::trying() const {
  const int s = step_ - first_, round = s / (n_ * kBlock), block = (s / kBlock) % n_;
  return round % 2 == 0 ? n_ - 1 - block : block;
}

int ThreadChoice::next() const { return counts_[exploring() ? trying() : best_]; }

void ThreadChoice::record(double cost, double size) {
  restarted_ = false;
  if (n_ == 1) return;
  if (exploring()) {
    const int s = step_ - first_, round = s / (n_ * kBlock);
    costs_[trying()][round * kBlock + s % kBlock] = cost;
    if ((s + 1) % (n_ * kBlock) == 0) decided_ = choose(round + 1) || round + 1 == kRounds;
    if (decided_) seen_ = 0, chosen_size_ = size;
  } else if (decided_) {
    watch(cost, size);
  }
  if (++step_ == kEpoch) step_ = 0, decided_ = false;
}

// The lowest weighed median over the rounds so far (a tie goes to the fewer threads); true when
// every other count's is kClear times it or more.
bool ThreadChoice::choose(int rounds) {
  std::array<double, kMaxCounts> med{};
  for (int k = 0; k < n_; ++k) {
    med[k] = median(costs_[k], rounds * kBlock) * (k + 1 < n_ ? favour_ : 1.0);
    if (med[k] < med[best_] || k == 0) best_ = k;
  }
  chosen_cost_ = median(costs_[best_], rounds * kBlock);
  for (int k = 0; k < n_; ++k)
    if (k != best_ && !(med[k] >= kClear * med[best_])) return false;
  return true;
}

// The chosen count's last kWatch costs: when three quarters of them drifted by kDrift or more
// the same way (a few slow steps do not), or the system's size did, a new epoch starts from the
// next step.
void ThreadChoice::watch(double cost, double size) {
  recent_[static_cast<std::size_t>(seen_ % kWatch)] = cost;
  const bool full = ++seen_ >= kWatch && chosen_cost_ > 0.0;
  const bool grown =
      chosen_size_ > 0.0 ? size > kDrift * chosen_size_ || size * kDrift < chosen_size_ : size >= kSizeFromNone;
  const double low = full ? kth(recent_, kWatch, kWatch / 4) : 0.0;
  const double high = full ? kth(recent_, kWatch, kWatch - 1 - kWatch / 4) : 0.0;
  const bool drifted = full && (low > kDrift * chosen_cost_ || high * kDrift < chosen_cost_);
  if (!grown && !drifted) return;
  decided_ = false;
  restarted_ = true;
  step_ = -1;  // (record's increment makes it the epoch's first step)
}

}  // namespace nscd
