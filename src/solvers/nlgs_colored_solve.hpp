// nscd/solvers/nlgs_colored_solve.hpp — one colored solve (nlgs_iterate_colored) as a class,
// for the files that define its parts: nlgs_colored.cpp (shares, sweeps, bodies) and
// nlgs_colored_mixing.cpp (the Anderson mixing, on one thread or several). Not a user's API.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <thread>
#include <vector>

#include "nscd/solvers/nlgs_blocks.hpp"
#include "nscd/solvers/nlgs_colored.hpp"
#include "nscd/solvers/nlgs_mixing.hpp"
#include "nscd/solvers/scene_backend.hpp"

namespace nscd::colored {

/// A barrier that spins: the colours of a small system are a microsecond apart, and OpenMP's
/// barrier costs several times more than this one (docs/benchmarks.md §8). After a few thousand
/// spins a waiting thread yields, in case it shares its core with another. wait_then(serial):
/// thread 0 waits for the others, runs `serial` and only then lets them go, so that a serial
/// part between two phases costs one barrier, not two (a barrier's cost is one round trip of a
/// cache line between cores, which is most of it on a small system: §11.7). What `serial`
/// returns (a verdict, whether the solve is done) travels to every thread on the flag's own
/// line: the others read it with the flag, not as one more line from thread 0's core.
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
      spin([&] { return count_.load(std::memory_order_acquire) + 1 == team_; });
      count_.store(0, std::memory_order_relaxed);
      const unsigned word = static_cast<unsigned>(serial());
      word_.store(word, std::memory_order_relaxed);
      flag_.store(sense, std::memory_order_release);
      return word;
    }
    count_.fetch_add(1, std::memory_order_acq_rel);
    spin([&] { return flag_.load(std::memory_order_acquire) == sense; });
    return word_.load(std::memory_order_relaxed);
  }

 private:
  template <class Done>
  static void spin(const Done& done) {
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
  alignas(64) std::atomic<unsigned> count_{0};
  alignas(64) std::atomic<unsigned> flag_{0};
  std::atomic<unsigned> word_{0};  ///< (on the flag's line)
  unsigned team_ = 1;
};

/// One colored solve, its steps as members: the threads' shares (split_shares), the bundles of
/// the SIMD lanes (build_share, finish_share), a colour's share swept (sweep_share), the end of
/// a sweep (end_of_sweep: 2.–4.), the mixing (mix_step: 5.), on one thread or several.
class ColoredSolve {
 public:
  ColoredSolve(ContactSystem& sys, const NlgsOptions& opt, NlgsColoredWorkspace& ws);
  NlgsResult run();

 private:
  void split_shares();
  void build_share(std::size_t u);
  template <class Bundles>
  void build_bundles(std::size_t u, Bundles& v);
  void finish_share(std::size_t u);
  void sweep_blocks(std::uint32_t b0, std::uint32_t b1, bool check);
  void sweep_share(unsigned k, std::size_t u, bool check);
  bool end_of_sweep(int sweep, bool check);
  void mix_step(int sweep);
  void set_mix_chunks();
  template <class F>
  void each_run(const F& f) const;
  void set_mix_slots();
  void body_owners(std::vector<std::uint32_t>& owner) const;
  void group_bodies(std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& split);
  void set_body_slots();
  void renumber_bodies();
  void restore_bodies();
  void renumber(const std::vector<std::uint32_t>& to);
  void list_border_bodies();
  void fetch_border_bodies(std::size_t run) const;
  template <class F>
  void own_contacts(std::size_t t, std::size_t team, const F& f) const;
  void exchange_on_threads(std::size_t t, std::size_t team, bool out);
  void mix_on_threads(std::size_t t, std::size_t team, SpinBarrier& barrier, unsigned& sense);
  void propagate_moves(std::size_t team);
  void run_one_thread();
  void run_threads();

  ContactSystem& sys;
  const NlgsOptions& opt;
  NlgsColoredWorkspace& ws;
  SceneBackend be;
  const std::size_t n;
  NlgsMixing mixing;  ///< Anderson's (its ω: 1 while mixing, else the relaxation)
  const std::uint32_t* block_start = nullptr;
  const std::uint32_t* start = nullptr;  ///< the colours' first blocks (ws.color_start)
  unsigned colours = 0;  ///< colours 0 … colours−1 are used (greedy: the lowest free colour first)
  bool parallel = false;
  int threads = 1;
  std::size_t T = 1;
  bool lanes = false, stream = false;
  std::size_t per_share = 1;
  /// Written by thread 0 after every sweep: on lines of its own, apart from the fields every
  /// thread reads at every sweep (a write there would take their line from the other cores).
  alignas(64) NlgsResult res;
};

}  // namespace nscd::colored
