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
  best_ = 0;
  first_ = std::clamp(first, 0, kEpoch - exploring_steps());
  own_epochs_ = true;
  new_epoch(true);
}

// A new epoch from the next step, its rounds led by the count chosen; `afresh` (a drift, new
// counts): of kEpoch steps, not lengthened by the choice its rounds repeat. One candidate has no
// epochs: a part that follows it (restart()) must not start its own at every step.
void ThreadChoice::new_epoch(bool afresh) {
  if (afresh) epoch_ = kEpoch, last_choice_ = 0;
  began_ = n_ > 1;
  step_ = 0;
  decided_ = false;
  lead_ = best_;
  seen_ = 0;
  chosen_cost_ = 0.0;
  lowest_.fill(0.0);
}

void ThreadChoice::lead(int count) {
  if (!pending()) return;
  int k = 0;
  while (k + 1 < n_ && counts_[k + 1] <= count) ++k;
  best_ = lead_ = k;
}

// Step s of the rounds: round s / (n·kBlock), the p-th block of it, p = (s / kBlock) mod n. In
// even rounds p = 0 is the lead and p ≥ 1 the others from the most threads to the fewest; odd
// rounds take them in the reverse order.
int ThreadChoice::trying() const {
  const int s = step_ - first_, round = s / (n_ * kBlock), block = (s / kBlock) % n_;
  const int p = round % 2 == 0 ? block : n_ - 1 - block;
  if (p == 0) return lead_;
  return n_ - p <= lead_ ? n_ - p - 1 : n_ - p;
}

int ThreadChoice::next() const { return counts_[exploring() ? trying() : best_]; }

// The steps of count k's block left to skip after this one: all of them after its first step
// where it cost kRejectAtOnce times another count's cheapest step or more, or after its second
// where it and the first each cost kReject times that or more.
int ThreadChoice::cut_block(int k, double cost) const {
  const int s = step_ - first_, at = s % kBlock, slot = (s / (n_ * kBlock)) * kBlock + at;
  if (at > 1) return 0;
  double other = 0.0;
  for (int j = 0; j < n_; ++j)
    if (j != k && lowest_[j] > 0.0 && (other == 0.0 || lowest_[j] < other)) other = lowest_[j];
  if (other == 0.0) return 0;
  const bool dear = at == 0 ? cost >= kRejectAtOnce * other : std::min(cost, costs_[k][slot - 1]) >= kReject * other;
  return dear ? kBlock - 1 - at : 0;
}

void ThreadChoice::record(double cost, double size) {
  restarted_ = began_ = false;
  if (n_ == 1) return;
  if (exploring()) {
    const int s = step_ - first_, round = s / (n_ * kBlock), k = trying();
    const int skip = cut_block(k, cost);
    std::fill_n(costs_[k].begin() + round * kBlock + s % kBlock, skip + 1, cost);
    lowest_[k] = lowest_[k] > 0.0 ? std::min(lowest_[k], cost) : cost;
    step_ += skip;
    if ((s + skip + 1) % (n_ * kBlock) == 0) decided_ = choose(round + 1) || round + 1 == kRounds;
    if (decided_) {
      epoch_ = counts_[best_] == last_choice_ ? std::min(2 * epoch_, kEpochMax) : kEpoch;
      last_choice_ = counts_[best_];
      seen_ = 0, chosen_size_ = size;
    }
  } else if (decided_ && drifted(cost, size)) {
    restarted_ = true;
    return new_epoch(true);
  }
  if (++step_ >= epoch_ && own_epochs_) new_epoch(false);
}

// A count's cost over the rounds so far: the median of its steps, or their mean where that is
// kStall times the median or more (steps that stall for time slices, not a rebuild's few).
double ThreadChoice::cost_of(int k, int rounds) const {
  const int n = rounds * kBlock;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += costs_[k][static_cast<std::size_t>(i)];
  const double med = median(costs_[k], n), mean = sum / n;
  return mean >= kStall * med ? mean : med;
}

// The lowest weighed cost over the rounds so far (a tie goes to the fewer threads); true when
// every other count's is kClear times it or more.
bool ThreadChoice::choose(int rounds) {
  std::array<double, kMaxCounts> cost{}, weighed{};
  for (int k = 0; k < n_; ++k) {
    cost[k] = cost_of(k, rounds);
    weighed[k] = cost[k] * (k + 1 < n_ ? favour_ : 1.0);
    if (weighed[k] < weighed[best_] || k == 0) best_ = k;
  }
  chosen_cost_ = cost[best_];
  for (int k = 0; k < n_; ++k)
    if (k != best_ && !(weighed[k] >= kClear * weighed[best_])) return false;
  return true;
}

// The chosen count's last kWatch costs: true when three quarters of them drifted by kDrift or
// more the same way (a few slow steps do not), or their mean rose kStall times (steps that
// stall), or the system's size drifted. A rise at the fewest threads does not count: more
// threads would not undo it.
bool ThreadChoice::drifted(double cost, double size) {
  recent_[static_cast<std::size_t>(seen_ % kWatch)] = cost;
  const bool full = ++seen_ >= kWatch && chosen_cost_ > 0.0;
  const bool grown =
      chosen_size_ > 0.0 ? size > kDrift * chosen_size_ || size * kDrift < chosen_size_ : size >= kSizeFromNone;
  if (!full) return grown;
  double sum = 0.0;
  for (const double c : recent_) sum += c;
  const double low = kth(recent_, kWatch, kWatch / 4), high = kth(recent_, kWatch, kWatch - 1 - kWatch / 4);
  const bool rose = best_ > 0 && (low > kDrift * chosen_cost_ || sum >= kStall * kWatch * chosen_cost_);
  return grown || rose || high * kDrift < chosen_cost_;
}

}  // namespace nscd
