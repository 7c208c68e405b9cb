// nscd/solvers/nlgs_colored_solve.hpp — one colored solve (nlgs_iterate_colored) as a class,
// for the files that define its parts: nlgs_colored.cpp (shares, sweeps, bodies) and
// nlgs_colored_mixing.cpp (the Anderson mixing, on one thread or several). Not a user's API.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "nscd/core/own_line.hpp"
#include "nscd/solvers/nlgs_blocks.hpp"
#include "nscd/solvers/nlgs_colored.hpp"
#include "nscd/solvers/nlgs_mixing.hpp"
#include "nscd/solvers/scene_backend.hpp"
#include "nscd/solvers/spin_barrier.hpp"

namespace nscd::colored {

/// One colored solve, its steps as members: the threads' shares (split_shares), the bundles of
/// the SIMD lanes (build_share, finish_share), a colour's share swept (sweep_share), the end of
/// a sweep (end_of_sweep: 2.–4.), the mixing (mix_step: 5.), on one thread or several.
class ColoredSolve {
 public:
  ColoredSolve(ContactSystem& sys, const NlgsOptions& opt, NlgsColoredWorkspace& ws);
  NlgsResult run();
  /// The plan run() would sweep by, made on this thread (plan_colored); null if it plans none.
  const LanePlan* plan_only();

 private:
  void split_shares();
  void build_share(std::size_t u);
  template <class Bundles>
  void build_bundles(std::size_t u, Bundles& v);
  void finish_share(std::size_t u);
  void sweep_blocks(std::uint32_t b0, std::uint32_t b1, bool check);
  void sweep_range(std::size_t u, std::uint32_t b0, std::uint32_t b1, bool check, LaneCarry* carry = nullptr);
  void sweep_share(unsigned k, std::size_t u, bool check);
  void claim_block_sums(std::size_t u);
  bool end_of_sweep(int sweep, bool check);
  void mix_step(int sweep);
  void set_mix_chunks();
  template <class F>
  void each_run(const F& f) const;
  void set_mix_slots();
  void contact_owners(std::vector<std::uint32_t>& owner) const;
  void finish_owners(std::vector<std::uint32_t>& owner, bool fill) const;
  void group_bodies(const std::vector<std::uint32_t>& owner, std::vector<std::uint32_t>& order,
                    std::vector<std::uint32_t>& split);
  void set_body_slots();
  void renumber_bodies();
  void restore_bodies();
  void renumber(const std::vector<std::uint32_t>& to);
  void choose_sweeps();
  void plan_sweeps(bool team);
  bool plan_pays();
  void plan_on_threads(std::size_t t, SpinBarrier& barrier, unsigned& sense);
  void sweep_planned(std::size_t t, unsigned sweep, bool check, OwnLine<std::atomic<unsigned>>* done,
                     std::vector<unsigned>& seen);
  void sweep_colours(std::size_t t, std::size_t team, bool check, SpinBarrier& barrier, unsigned& sense);
  template <class F>
  void own_contacts(std::size_t t, std::size_t team, const F& f) const;
  void exchange_on_threads(std::size_t t, std::size_t team, bool out);
  void mix_on_threads(std::size_t t, std::size_t team, SpinBarrier& barrier, unsigned& sense);
  void propagate_moves(std::size_t team);
  void run_one_thread();
  void run_threads();
  PartClock& clock(std::size_t t) { return ws.clocks[t].v; }

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
  bool planned = false;  ///< the sweeps planned lane by lane (plan_sweeps)
  bool renumbered = false;  ///< the bodies numbered share by share (renumber_bodies)
  PlanInput plan_in;  ///< what the plan reads (plan_sweeps)
  std::size_t per_share = 1;
  std::size_t team_ran = 1;  ///< the threads the region ran on (OpenMP may give fewer than asked)
  /// Written by thread 0 after every sweep: on lines of its own, apart from the fields every
  /// thread reads at every sweep (a write there would take their line from the other cores).
  alignas(64) NlgsResult res;
};

}  // namespace nscd::colored
