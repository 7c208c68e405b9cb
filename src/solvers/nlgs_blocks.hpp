// nscd/solvers/nlgs_blocks.hpp — the colored sweep's blocks (internal to nlgs_coloring.cpp,
// nlgs_blocks.cpp and nlgs_colored.cpp): a system whose bodies have positions cut into strips
// (SweepOrder::Colored) or a grid of cells (SweepOrder::ColoredRows, ColoredCells), each
// contact given its block; what the colouring needs of each contact (its dynamic bodies); the
// colours' limits.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "nscd/solvers/nlgs_colored.hpp"
#include "nscd/solvers/thread_range.hpp"

namespace nscd::colored {

inline constexpr unsigned kOverflow = 63;  ///< colours 0 … 62 run in parallel, 63 on one thread
inline constexpr std::uint32_t kSpill =
    std::numeric_limits<std::uint32_t>::max();  ///< a contact of no block: the overflow
/// A kinematic end of a contact (Ends).
inline constexpr std::uint32_t kNoBody = std::numeric_limits<std::uint32_t>::max();
using Ends = NlgsColoredWorkspace::ColorScratch::Ends;

/// Each contact's dynamic bodies, 8 bytes a contact (kNoBody for a kinematic end): what the
/// blocks and the colours need, without streaming the 152-byte records again and again (each
/// pass over the records costs milliseconds in a large system: docs/benchmarks.md §8).
void fill_ends(const std::vector<SolverContact>& c, std::vector<Ends>& ends, int threads);

/// Strips across the longer side of the bodies in contact (nlgs_blocks.cpp): each contact's
/// strip into block_of (kSpill: the overflow), each strip's index into `key`. False (nothing
/// decided) when the system has no positions or is too small or too narrow.
bool strip_blocks(const ContactSystem& sys, NlgsColoredWorkspace& ws, std::vector<std::uint32_t>& block_of,
                  std::size_t& nblocks, std::vector<std::uint32_t>& key, std::size_t& nkeys, int threads);

/// A grid of cells over the dynamic bodies in contact (nlgs_blocks.cpp): each contact's cell
/// into block_of (kSpill: the overflow), each cell's column into `key`. False (nothing decided)
/// when the system has no positions or is too small.
bool cell_blocks(const ContactSystem& sys, NlgsColoredWorkspace& ws, std::vector<std::uint32_t>& block_of,
                 std::size_t& nblocks, std::vector<std::uint32_t>& key, std::size_t& nkeys,
                 std::vector<std::uint32_t>& body_cell, bool from_top, int threads);

/// SweepOrder::ColoredCells: each cell's contacts (scratch.members, gathered by block) from
/// the bottom up, by the mean height of their dynamic bodies, ties in contact order.
void sort_cells_upward(const ContactSystem& sys, NlgsColoredWorkspace& ws, std::size_t nblocks, int threads);

}  // namespace nscd::colored
