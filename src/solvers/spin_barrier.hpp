// nscd/solvers/spin_barrier.hpp — a barrier for a team of threads that meet thousands of
// times a solve (the colored sweep's colours, the overlap projection's sweeps).
#pragma once

#include <atomic>
#include <cstddef>
#include <thread>

namespace nscd {

/// Spins until done() holds: a pause a try, then, after a few thousand tries, a yield at each
/// (in case the thread it waits for shares its core).
template <class Done>
void spin_until(const Done& done) {
  for (unsigned spins = 0; !done(); ++spins) {
    if (spins < 4096) {
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
    } else {
      std::this_thread::yield();
    }
  }
}

/// A barrier that spins: the colours of a small system are a microsecond apart, and OpenMP's
/// barrier costs several times more than this one (docs/benchmarks.md §8). After a few thousand
/// spins a waiting thread yields, in case it shares its core with another. wait_then(serial):
/// thread 0 waits for the others, runs `serial` and only then lets them go, so that a serial
/// part between two phases costs one barrier, not two (a barrier's cost is one round trip of a
/// cache line between cores, which is most of it on a small system: docs/benchmarks.md
/// §11.7). What `serial` returns (a verdict, whether the solve is done) travels to every thread
/// on the flag's own line: the others read it with the flag, not as one more line from thread
/// 0's core.
class SpinBarrier {
 public:
  void reset(unsigned team) {
    team_ = team;
    count_.store(0, std::memory_order_relaxed);
    flag_.store(0, std::memory_order_relaxed);
  }
  /// `sense`: the calling thread's own, 0 before its first wait.
  void wait(unsigned& sense, std::size_t t) {
    wait_then(sense, t, [] { return 0u; });
  }
  /// The others arrive (count_), thread `t` = 0 sees them all, resets the count, runs `serial`
  /// and flips the flag they spin on (acquire and release order every write around it). Every
  /// thread returns what `serial` returned on thread 0.
  template <class F>
  unsigned wait_then(unsigned& sense, std::size_t t, const F& serial) {
    sense ^= 1u;
    if (t == 0) {
      spin_until([&] { return count_.load(std::memory_order_acquire) + 1 == team_; });
      count_.store(0, std::memory_order_relaxed);
      const unsigned word = static_cast<unsigned>(serial());
      word_.store(word, std::memory_order_relaxed);
      flag_.store(sense, std::memory_order_release);
      return word;
    }
    count_.fetch_add(1, std::memory_order_acq_rel);
    spin_until([&] { return flag_.load(std::memory_order_acquire) == sense; });
    return word_.load(std::memory_order_relaxed);
  }

 private:
  alignas(64) std::atomic<unsigned> count_{0};
  alignas(64) std::atomic<unsigned> flag_{0};
  std::atomic<unsigned> word_{0};  ///< (on the flag's line)
  unsigned team_ = 1;
};

}  // namespace nscd
