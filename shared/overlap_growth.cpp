// nscd/shared/overlap_growth.cpp — see overlap_growth.hpp.
#include "nscd/shared/overlap_growth.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "nscd/core/error.hpp"

namespace nscd::scenes {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) out.push_back(cell);
  return out;
}

}  // namespace

int overlap_block_length(int cycles) { return cycles >= 2000 ? 1000 : std::max(1, cycles / 10); }

std::vector<OverlapBlock> overlap_blocks(const std::filesystem::path& cycles_csv, int block) {
  std::ifstream in(cycles_csv);
  if (!in) throw Error("cannot read " + cycles_csv.string());
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> head = split(line);
  auto column = [&](const char* name) {
    const auto it = std::find(head.begin(), head.end(), name);
    if (it == head.end()) throw Error(cycles_csv.string() + " has no column '" + name + "'");
    return static_cast<std::size_t>(it - head.begin());
  };
  const std::size_t kc = column("cycle"), kmean = column("mean_overlap"), kmax = column("max_overlap");
  std::vector<OverlapBlock> blocks;
  std::vector<int> counts;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = split(line);
    if (cells.size() <= std::max({kc, kmean, kmax})) continue;
    const int cycle = std::atoi(cells[kc].c_str());
    if (cycle < 1) continue;
    const std::size_t b = static_cast<std::size_t>((cycle - 1) / block);
    if (blocks.size() <= b) {
      blocks.resize(b + 1);
      counts.resize(b + 1, 0);
    }
    OverlapBlock& o = blocks[b];
    o.first_cycle = static_cast<int>(b) * block + 1;
    o.last_cycle = std::max(o.last_cycle, cycle);
    o.max_overlap = std::max(o.max_overlap, std::strtod(cells[kmax].c_str(), nullptr));
    o.mean_overlap += std::strtod(cells[kmean].c_str(), nullptr);
    ++counts[b];
  }
  for (std::size_t b = 0; b < blocks.size(); ++b)
    if (counts[b] > 0) blocks[b].mean_overlap /= counts[b];
  return blocks;
}

std::string overlap_growth_lines(const std::vector<OverlapBlock>& blocks, int block) {
  std::ostringstream s;
  s.precision(6);
  s << "overlap_block_cycles = " << block << "\nmax_overlap_by_block =";
  for (const OverlapBlock& b : blocks) s << ' ' << b.max_overlap;
  s << "\nmean_overlap_by_block =";
  for (const OverlapBlock& b : blocks) s << ' ' << b.mean_overlap;
  const double growth = blocks.size() >= 3 && blocks[1].max_overlap > 0.0 ? blocks.back().max_overlap / blocks[1].max_overlap : std::nan("");
  s << "\nmax_overlap_growth = " << growth << '\n';
  return s.str();
}

}  // namespace nscd::scenes
