// tools/core_latency.cpp — the round trip of one cache line between two threads (a ping-pong of
// two atomic counters): what every barrier of the colored sweep pays at least once. On a virtual
// machine it follows where the host places the two vCPUs, and can change by several times within
// minutes; tools/threads_table.sh prints it beside each round so that a table states the state of
// the machine it was measured in (docs/record/benchmarks-history.md §11.0).
//   g++ -O2 -pthread tools/core_latency.cpp -o /tmp/core_latency && /tmp/core_latency [ROUNDS]
// Prints the median over ROUNDS (default 5) of the mean round trip of 100,000 exchanges, in ns.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

namespace {

// the two counters on their own cache lines: the line of one moves to the other thread and back
alignas(64) std::atomic<unsigned> ping{0};
alignas(64) std::atomic<unsigned> pong{0};

void wait_for(const std::atomic<unsigned>& x, unsigned v) {
  while (x.load(std::memory_order_acquire) != v) {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();  // as the solver's barrier spins
#endif
  }
}

// mean ns of one round trip over n exchanges: this thread writes ping, the partner answers on pong
double round_trip_ns(unsigned n) {
  ping.store(0);
  pong.store(0);
  std::thread partner([n] {
    for (unsigned i = 1; i <= n; ++i) {
      wait_for(ping, i);
      pong.store(i, std::memory_order_release);
    }
  });
  const auto t0 = std::chrono::steady_clock::now();
  for (unsigned i = 1; i <= n; ++i) {
    ping.store(i, std::memory_order_release);
    wait_for(pong, i);
  }
  const auto t1 = std::chrono::steady_clock::now();
  partner.join();
  return std::chrono::duration<double, std::nano>(t1 - t0).count() / n;
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  std::vector<double> ns;
  for (int r = 0; r < rounds; ++r) ns.push_back(round_trip_ns(100000));
  std::sort(ns.begin(), ns.end());
  std::printf("%.0f\n", ns[ns.size() / 2]);
}
