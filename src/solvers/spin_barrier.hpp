// nscd/solvers/spin_barrier.hpp — a barrier for a team of threads that meet thousands of
// times a solve (the colored sweep's colours, the overlap projection's sweeps).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>

namespace nscd {

/// The tries a thread's wait_for makes before it sleeps: a few thousand pauses while the threads
/// it waits for run, far fewer after waits that had to sleep (halved at each, grown
/// back by 16 at each that did not), so that where more threads than cores take turns a
/// waiting thread soon gives its core to the one it waits for.
inline thread_local unsigned t_spins = 4096;

/// Waits until done(v) holds for the value v of `a`, and returns v: a pause a try, and after
/// t_spins tries, which a thread whose partners run on cores of their own seldom needs (a sweep
/// of a colour takes microseconds), asleep on `a` (std::atomic::wait, a futex) until a store
/// changes it. Every store to `a` goes through wake().
template <class Done>
unsigned wait_for(const std::atomic<unsigned>& a, const Done& done) {
  for (unsigned spins = 0;; ++spins) {
    const unsigned v = a.load(std::memory_order_acquire);
    if (done(v)) {
      t_spins = spins > t_spins ? std::max(64u, t_spins / 2) : std::min(4096u, t_spins + 16);
      return v;
    }
    if (spins < t_spins) {
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
    } else {
      a.wait(v, std::memory_order_acquire);
    }
  }
}

/// a = v (release), and the threads asleep on `a` in wait_for woken (none asleep: one load of
/// the library's table of waiters)
inline void wake(std::atomic<unsigned>& a, unsigned v) {
  a.store(v, std::memory_order_release);
  a.notify_all();
}

/// A barrier that spins: the colours of a small system are a microsecond apart, and OpenMP's
/// barrier costs several times more than this one (docs/benchmarks.md §8). After a few thousand
/// spins a waiting thread sleeps until the barrier moves (wait_for). wait_then(serial):
/// thread 0 waits for the others, runs `serial` and only then lets them go, so that a serial
/// part between two phases costs one barrier, not two (a barrier's cost is one round trip of a
/// cache line between cores, which is most of it on a small system:
/// docs/record/benchmarks-history.md §11.7). What `serial` returns (a verdict, whether the
/// solve is done) travels to every thread on the flag's own line: the others read it with the
/// flag, not as one more line from thread 0's core.
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
      wait_for(count_, [&](unsigned arrived) { return arrived + 1 == team_; });
      count_.store(0, std::memory_order_relaxed);
      const unsigned word = static_cast<unsigned>(serial());
      word_.store(word, std::memory_order_relaxed);
      wake(flag_, sense);
      return word;
    }
    count_.fetch_add(1, std::memory_order_acq_rel);
    count_.notify_all();
    wait_for(flag_, [&](unsigned flag) { return flag == sense; });
    return word_.load(std::memory_order_relaxed);
  }

 private:
  alignas(64) std::atomic<unsigned> count_{0};
  alignas(64) std::atomic<unsigned> flag_{0};
  std::atomic<unsigned> word_{0};  ///< (on the flag's line)
  unsigned team_ = 1;
};

}  // namespace nscd
