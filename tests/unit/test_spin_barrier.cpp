// tests/unit/test_spin_barrier.cpp — the waits of the threads of a colored solve
// (src/solvers/spin_barrier.hpp):
//   - wait_for returns once a store (wake) gives the value it waits for, also after it has
//     stopped spinning and sleeps on the atomic, and even where the store's wake-up is lost
//     (a sleep lasts a millisecond at most: the hang of docs/record/benchmarks-history.md §11.24);
//   - the spin barrier with more threads than cores (the waiters sleep, so that the threads not
//     running get a core): at every round each thread sees every other's write of the round,
//     and wait_then hands thread 0's value to all.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <future>
#include <thread>
#include <vector>

#include "nscd/solvers/spin_barrier.hpp"

namespace {

using namespace nscd;

TEST(WaitFor, ReturnsTheValueAStoreGivesAfterItHasFallenAsleep) {
  std::atomic<unsigned> a{0};
  unsigned seen = 0;
  std::thread waiter([&] { seen = wait_for(a, [](unsigned v) { return v >= 5; }); });
  for (unsigned v = 1; v <= 5; ++v) {
    // long enough for the waiter to pass its spins and sleep on `a` between two stores
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    wake(a, v);
  }
  waiter.join();
  EXPECT_EQ(seen, 5u);
}

// A store that no wake() follows stands for a wake-up lost on the way: the sleeper must find the
// value at its next look, a millisecond later, not sleep on for good.
TEST(WaitFor, ThreadAsleepFindsAStoreWhoseWakeUpWasLost) {
  std::atomic<unsigned> a{0};
  std::promise<unsigned> seen;
  std::future<unsigned> result = seen.get_future();
  std::thread waiter([&] {
    t_spins = 0;  // asleep at once
    seen.set_value(wait_for(a, [](unsigned v) { return v == 1; }));
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));  // (the waiter asleep by now)
  a.store(1, std::memory_order_seq_cst);  // no wake()
  const bool returned = result.wait_for(std::chrono::seconds(5)) == std::future_status::ready;
  if (!returned) wake(a, 1);  // (lets the thread end, so that the test fails instead of hanging)
  waiter.join();
  ASSERT_TRUE(returned) << "wait_for slept on after the value changed";
  EXPECT_EQ(result.get(), 1u);
}

TEST(SpinBarrier, MoreWaitersThanCoresMeetAtEveryRound) {
  const std::size_t team = 2 * std::max(1u, std::thread::hardware_concurrency()) + 1;
  constexpr unsigned kRounds = 300;
  SpinBarrier barrier;
  barrier.reset(static_cast<unsigned>(team));
  std::vector<std::atomic<unsigned>> wrote(team);
  std::vector<unsigned> wrong(team, 0), handed(team, 0);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < team; ++t)
    threads.emplace_back([&, t] {
      unsigned sense = 0;
      for (unsigned round = 1; round <= kRounds; ++round) {
        wrote[t].store(round, std::memory_order_relaxed);
        const unsigned word = barrier.wait_then(sense, t, [&] { return 7 * round; });
        for (std::size_t u = 0; u < team; ++u) wrong[t] += wrote[u].load(std::memory_order_relaxed) != round;
        handed[t] += word == 7 * round;
        barrier.wait(sense, t);  // (no thread writes the next round before all have read this one)
      }
    });
  for (std::thread& th : threads) th.join();
  for (std::size_t t = 0; t < team; ++t) {
    EXPECT_EQ(wrong[t], 0u) << "thread " << t;
    EXPECT_EQ(handed[t], kRounds) << "thread " << t;
  }
}

}  // namespace
