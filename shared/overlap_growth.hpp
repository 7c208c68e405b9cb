// nscd/shared/overlap_growth.hpp — the overlap's growth over a long run, for summary.txt: the
// largest and the mean overlap per block of cycles, read back from the run's cycles.csv (so a
// run resumed many times is summarised whole).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace nscd::scenes {

struct OverlapBlock {
  int first_cycle = 0, last_cycle = 0;
  double max_overlap = 0.0;   ///< largest of the block's cycles (m)
  double mean_overlap = 0.0;  ///< mean of the cycles' mean overlaps (m)
};

/// Blocks of `block` cycles (the last one possibly shorter) from a CSV with the columns
/// cycle, mean_overlap and max_overlap. Throws nscd::Error if the file or a column is missing.
std::vector<OverlapBlock> overlap_blocks(const std::filesystem::path& cycles_csv, int block);

/// The block length for a run of `cycles`: 1000 from 2000 cycles on, else a tenth (at least 1).
int overlap_block_length(int cycles);

/// "key = value" lines: overlap_block_cycles, max_overlap_by_block, mean_overlap_by_block (values
/// separated by spaces, one per block) and max_overlap_growth (the last block's largest overlap
/// over the second's: the first holds the load's ramp-in; nan with fewer than three blocks).
std::string overlap_growth_lines(const std::vector<OverlapBlock>& blocks, int block);

}  // namespace nscd::scenes
