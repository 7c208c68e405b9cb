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
// SIMD lanes (nlgs_lanes.hpp, NlgsOptions::lanes), with the same numbers; a small system's
// colours in one run of bundles per thread, where the threads wait for each other only where
// their contacts meet on a body (nlgs_plan.hpp).
#pragma once

#include "nscd/core/own_line.hpp"
#include "nscd/solvers/contact_system.hpp"
#include "nscd/solvers/nlgs.hpp"
#include "nscd/solvers/nlgs_lanes.hpp"
#include "nscd/solvers/nlgs_mixing.hpp"
#include "nscd/solvers/nlgs_plan.hpp"
#include "nscd/solvers/nlgs_sweep.hpp"

namespace nscd {

/// Reusable buffers of the colored sweep (no allocation once warmed up): the sequential ones
/// (the skip rule's), the colouring and layout, the threads' shares in SIMD lanes, Anderson's
/// history (nlgs_mixing.hpp).
struct NlgsColoredWorkspace : NlgsWorkspace {
  std::vector<std::uint32_t> block_start;  ///< block b = contacts block_start[b] .. block_start[b+1]
  std::vector<std::uint32_t> color_start;  ///< colour c = blocks color_start[c] .. color_start[c+1]
  std::vector<std::uint32_t> block_id;     ///< each laid block's index before colouring (the overflow's: the last)
  std::vector<std::uint32_t> block_key;    ///< each laid block's share key (its column of cells, or its index)
  std::size_t keys = 0;                    ///< keys 0 … keys−1 (the overflow's block has key `keys`)
  std::vector<std::uint32_t> split;        ///< first block of each thread in each colour
  std::vector<std::uint32_t> body_new, body_old;  ///< on threads: the bodies numbered share by share, and back
  std::vector<std::uint32_t> body_share;          ///< … each body's share by its contacts, in the old numbers
  std::vector<SolverBody> body_copy;              ///< … (scratch: the bodies in the other order)
  std::vector<std::uint64_t> body_colors;  ///< colours taken at each body (bit c)
  bool cells = false;                      ///< the blocks are cells of the field (ColoredRows)
  bool strips = false;                     ///< the blocks are strips of the field (Colored)
  const void* arranged = nullptr;          ///< the system laid out by color_contacts (else null)
  std::size_t arranged_contacts = 0;       ///< … and its number of contacts then
  SweepOrder arranged_order = SweepOrder::Colored;  ///< … and the order it was laid out for
  /// The buffers of color_contacts and of the threads' shares, kept from step to step.
  struct ColorScratch {
    std::vector<std::uint32_t> block_of, first, members, next, col, placed, rank, rows, border, key, key_first, by_key,
        body_cell, thread_next;
    std::vector<std::uint64_t> upto;
    std::vector<std::uint32_t> body_block[2];  ///< strips on threads: each body's even and odd block
    std::vector<std::uint8_t> shares;          ///< … whether each block shares a body with the one before
    std::vector<double> span_bin, axis_spans[2], box_parts;
    struct Ends {
      std::uint32_t cd, an;  ///< a contact's dynamic bodies (UINT32_MAX: a kinematic end)
    };
    std::vector<Ends> ends;
    std::vector<SolverContact> contacts;
    std::vector<ContactStatus> status;
  } scratch;
  /// Each thread share's contacts dealt to SIMD lanes (nlgs_lanes.hpp), colour by colour: colour
  /// k of share u is share_bundles[u][bundle_split[u(C+1)+k] … bundle_split[u(C+1)+k+1]) (a
  /// system whose bundles fit the cache; else share_streamed); planned, colour 0's range holds
  /// every colour.
  std::vector<std::vector<MassBundle>> share_bundles;
  std::vector<std::vector<ContactBundle>> share_streamed;  ///< … the same, for systems whose bundles are streamed
  std::vector<std::vector<std::uint32_t>> share_order;  ///< … and the order of its blocks (scratch)
  std::vector<std::uint32_t> bundle_split;
  std::vector<OwnLine<PartClock>> clocks;  ///< each thread's parts (NlgsOptions::profile)
  /// … of a small system: every colour in one run of bundles per share, and the shares' stops
  /// (nlgs_plan.hpp); plan_tail: the dynamic bodies of share 0's tail (scratch)
  LanePlan plan;
  std::vector<std::uint32_t> plan_tail;
  LineVector<CriteriaAccumulator> block_sums;  ///< each block's convergence sums (checked sweeps), a line each
  NlgsMixingBuffers mixing;  ///< with NlgsOptions::anderson: the mixing's history and cones
};

/// Colours the contacts of `sys` and lays the system out for the colored sweep: its contacts
/// (with their rows and statuses) reordered block by block, colour by colour; ws.block_start
/// and ws.color_start give the blocks and colours (the last colour is the overflow), and ws
/// remembers the system as arranged. Returns the number of colours used, the overflow
/// included if non-empty. A large system's records are copied into the layout on `threads`
/// threads (the same layout on any number).
std::size_t color_contacts(ContactSystem& sys, NlgsColoredWorkspace& ws, SweepOrder order = SweepOrder::Colored,
                           int threads = 1);

/// NLGS on the scene's system with SweepOrder::Colored or ColoredRows on `opt.threads` threads;
/// colours the system first unless `ws` arranged this very system for this order
/// (MoreauJean::prepare does it, so that the step's problem reads the same before and after the
/// solve).
NlgsResult nlgs_iterate_colored(ContactSystem& sys, const NlgsOptions& opt, NlgsColoredWorkspace& ws);

/// The plan of the sweeps nlgs_iterate_colored would run on `sys` with `opt.threads` threads,
/// made on this thread, without a sweep: the same plan, its bodies in the system's own numbers
/// (the solve plans after numbering them share by share). Null where those sweeps are not
/// planned: without SIMD lanes, on threads beyond 16,384 contacts (kRenumberMax), on one thread
/// unless on strips or cells below kParallelMin contacts (where one thread sweeps the plan only
/// if it needs fewer passes of the lane kernel than the colours dealt one after the other, it is
/// returned either way). Lays `sys` out as nlgs_iterate_colored does. For a model of what the plan allows any number of threads (model_plan,
/// nlgs_plan_model.hpp).
const LanePlan* plan_colored(ContactSystem& sys, const NlgsOptions& opt, NlgsColoredWorkspace& ws);

/// The values of ranks k1 and k2 (0-based, k1 ≤ k2 < v.size()) of v's finite values, exactly as
/// std::nth_element would give them (the cells' sizes need a median and a 95th percentile each
/// step); v is reordered, `scratch` is work space.
void two_ranks(std::vector<double>& v, std::size_t k1, std::size_t k2, double& r1, double& r2,
               std::vector<double>& scratch);

}  // namespace nscd
