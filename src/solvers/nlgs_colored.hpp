// nscd/solvers/nlgs_colored.hpp — NLGS swept colour by colour, on one thread or several, with a
// result that does not depend on the number of threads.
//
// Blocks, for a system whose bodies have positions (of any size): strips across the field
// (SweepOrder::Colored) or a grid of cells (SweepOrder::ColoredRows); blocks of consecutive
// contacts otherwise (a dumped problem). Colouring, block by block: a block's colour is never one taken
// at any of its *dynamic* bodies (kinematic bodies are never written, so any number of blocks of
// a colour may touch the floor). Strips and consecutive blocks take the lowest such colour
// (greedy, as Box2D's constraint_graph.c colours contacts); cells, numbered row by row from the
// bottom, take the lowest colour above those taken at their bodies (levels), so that the sweep
// is that of the cells one after the other, row by row. Colours 0 … 62 are swept in parallel;
// blocks that find none free, and contacts that fit no block, go to an overflow colour swept on
// one thread. The system is laid out block by block, colour by colour, and each thread takes
// one range of blocks (of strips, of columns of cells) in every colour. Inside a colour no two
// blocks share a dynamic body, so sweeping them on any thread gives the same numbers; each
// block adds up its own convergence sums, and the blocks' sums are added in one fixed order
// after the sweep. The order differs from `fixed`, so sweeps to convergence differ too —
// docs/theory.md §9.5. Each thread visits its blocks of a colour several contacts at a time in
// SIMD lanes (nlgs_lanes.hpp, NlgsOptions::lanes), with the same numbers.
#pragma once

#include "nscd/solvers/contact_system.hpp"
#include "nscd/solvers/nlgs.hpp"
#include "nscd/solvers/nlgs_sweep.hpp"

namespace nscd {

/// From this many contacts on, a step's loops over the contacts run on NlgsOptions::threads: the
/// colored sweep's blocks of consecutive contacts (strips and cells: from 256 contacts on), the
/// colouring's passes over the contacts and its copy into the layout, and MoreauJean's loops
/// around the solve (below, a parallel region costs more than it saves on this project's
/// machine).
inline constexpr std::size_t kParallelMin = 8192;

/// Colours the contacts of `sys` and lays the system out for the colored sweep: its contacts
/// (with their rows and statuses) reordered block by block, colour by colour; ws.block_start
/// and ws.color_start give the blocks and colours (the last colour is the overflow), and ws
/// remembers the system as arranged. Returns the number of colours used, the overflow
/// included if non-empty. A large system's records are copied into the layout on `threads`
/// threads (the same layout on any number).
std::size_t color_contacts(ContactSystem& sys, NlgsWorkspace& ws, SweepOrder order = SweepOrder::Colored, int threads = 1);

/// NLGS on the scene's system with SweepOrder::Colored or ColoredRows on `opt.threads` threads;
/// colours the system first unless `ws` arranged this very system for this order (MoreauJean::prepare does it, so that the
/// step's problem reads the same before and after the solve).
NlgsResult nlgs_iterate_colored(ContactSystem& sys, const NlgsOptions& opt, NlgsWorkspace& ws);

/// The values of ranks k1 and k2 (0-based, k1 ≤ k2 < v.size()) of v's finite values, exactly as
/// std::nth_element would give them (the cells' sizes need a median and a 95th percentile each
/// step); v is reordered, `scratch` is work space.
void two_ranks(std::vector<double>& v, std::size_t k1, std::size_t k2, double& r1, double& r2, std::vector<double>& scratch);

}  // namespace nscd
