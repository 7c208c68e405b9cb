// nscd/solvers/spin_barrier.hpp — a barrier for a team of threads that meet thousands of
// times a solve (the colored sweep's colours, the overlap projection's sweeps).
#pragma once

#include <algorithm>
#include <atomic>
#include <climits>
#include <cstddef>
#include <thread>

#ifdef __linux__
#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <ctime>
#endif

namespace nscd {

/// The tries a thread's wait_for makes before it sleeps: a few thousand pauses while the threads
/// it waits for run, far fewer after waits that had to sleep (halved at each, grown
/// back by 16 at each that did not), so that where more threads than cores take turns a
/// waiting thread soon gives its core to the one it waits for.
inline thread_local unsigned t_spins = 4096;

namespace detail {
/// Threads asleep in wait_for, all addresses together: wake() makes a system call only while
/// one is (none in a run whose threads each have a core).
inline std::atomic<int> g_sleepers{0};
/// A sleep in wait_for lasts at most this long before the value is read again, so that a
/// wake-up lost anywhere (a hang was seen once: docs/record/benchmarks-history.md §11.24) costs
/// a millisecond, never the run.
inline constexpr long kSleepNs = 1'000'000;

/// Asleep while `a` holds v, for at most kSleepNs (a futex on Linux; elsewhere a yield).
inline void sleep_while(const std::atomic<unsigned>& a, unsigned v) {
#ifdef __linux__
  static_assert(sizeof(std::atomic<unsigned>) == sizeof(unsigned), "a futex is a 32-bit word");
  timespec limit{0, kSleepNs};
  syscall(SYS_futex, reinterpret_cast<const unsigned*>(&a), FUTEX_WAIT_PRIVATE, v, &limit, nullptr, 0);
#else
  (void)a, (void)v;
  std::this_thread::yield();
#endif
}

/// The threads asleep on `a` woken (after a store or an exchange to it, in sequential
/// consistency: with g_sleepers' increment in wait_for, either the sleeper reads the new value
/// or this call sees it counted, never neither).
inline void wake_sleepers(std::atomic<unsigned>& a) {
  if (g_sleepers.load(std::memory_order_seq_cst) == 0) return;
#ifdef __linux__
  syscall(SYS_futex, reinterpret_cast<unsigned*>(&a), FUTEX_WAKE_PRIVATE, INT_MAX, nullptr, nullptr, 0);
#endif
}
}  // namespace detail

/// Yields before a wait_for sleeps: a sleeper's wake-up costs tens of microseconds.
inline constexpr unsigned kYields = 4;

/// Waits until done(v) holds for the value v of `a`, and returns v: a pause a try, and after
/// t_spins tries, which a thread whose partners run on cores of their own seldom needs (a sweep
/// of a colour takes microseconds), kYields yields, then asleep until a store changes it
/// (wake()) or a millisecond has passed. Every store to `a` goes through wake().
template <class Done>
unsigned wait_for(const std::atomic<unsigned>& a, const Done& done) {
  for (unsigned spins = 0;; ++spins) {
    const unsigned v = a.load(std::memory_order_seq_cst);
    if (done(v)) {
      t_spins = spins > t_spins ? std::max(64u, t_spins / 2) : std::min(4096u, t_spins + 16);
      return v;
    }
    if (spins < t_spins) {
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
      continue;
    }
    if (spins < t_spins + kYields) {  // (the core offered to a thread that waits for one)
      std::this_thread::yield();
      continue;
    }
    // counted first, then the value read again: a wake() after the count sees the sleeper
    detail::g_sleepers.fetch_add(1, std::memory_order_seq_cst);
    if (a.load(std::memory_order_seq_cst) == v) detail::sleep_while(a, v);
    detail::g_sleepers.fetch_sub(1, std::memory_order_seq_cst);
  }
}

/// a = v, and the threads asleep on `a` in wait_for woken (none asleep: one load)
inline void wake(std::atomic<unsigned>& a, unsigned v) {
  a.store(v, std::memory_order_seq_cst);
  detail::wake_sleepers(a);
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
    count_.fetch_add(1, std::memory_order_seq_cst);
    detail::wake_sleepers(count_);
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
