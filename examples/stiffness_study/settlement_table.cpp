// examples/stiffness_study/settlement_table.cpp — reading cycles.csv files and reducing them
// to mean ± standard deviation per k factor (see settlement_table.hpp).
#include "settlement_table.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace stiffness {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, ',')) {
    while (!cell.empty() && (cell.back() == '\r' || cell.back() == ' ')) cell.pop_back();
    while (!cell.empty() && cell.front() == ' ') cell.erase(cell.begin());
    cells.push_back(cell);
  }
  return cells;
}

double to_number(const std::string& text, const std::filesystem::path& file, int line) {
  double v = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v))
    throw std::runtime_error(file.string() + ":" + std::to_string(line) + ": '" + text + "' is not a number");
  return v;
}

}  // namespace

std::string number_text(double v) {
  char b[40];
  const auto r = std::to_chars(b, b + sizeof b, v);
  return std::string(b, r.ptr);
}

Series read_cycles_csv(const std::filesystem::path& file, const std::string& column) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(file.string() + " is empty (no header)");
  const std::vector<std::string> header = split(line);
  const auto find = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) throw std::runtime_error(file.string() + " has no column '" + name + "'");
    return static_cast<std::size_t>(it - header.begin());
  };
  const std::size_t ic = find("cycle"), is = find(column);
  Series s;
  int n = 1;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> cells = split(line);
    if (cells.size() <= std::max(ic, is))
      throw std::runtime_error(file.string() + ":" + std::to_string(n) + ": fewer columns than the header");
    s.cycle.push_back(static_cast<int>(std::lround(to_number(cells[ic], file, n))));
    s.settlement.push_back(to_number(cells[is], file, n));
  }
  return s;
}

KStats aggregate(double k_factor, const std::vector<Series>& runs) {
  KStats k;
  k.k_factor = k_factor;
  k.samples = static_cast<int>(runs.size());
  if (runs.empty()) return k;
  std::size_t n = runs.front().cycle.size();
  for (const Series& r : runs) n = std::min(n, r.cycle.size());
  for (std::size_t i = 0; i < n; ++i) {
    const int c = runs.front().cycle[i];
    double sum = 0.0;
    for (const Series& r : runs) {
      if (r.cycle[i] != c)
        throw std::runtime_error("runs of k factor " + number_text(k_factor) + " disagree: row " + std::to_string(i + 1) +
                                 " is cycle " + std::to_string(c) + " in one, " + std::to_string(r.cycle[i]) + " in another");
      sum += r.settlement[i];
    }
    const double mean = sum / double(runs.size());
    // Two passes (mean first) so that the variance does not lose digits when the spread is
    // much smaller than the settlement itself.
    double sq = 0.0;
    for (const Series& r : runs) sq += (r.settlement[i] - mean) * (r.settlement[i] - mean);
    k.cycle.push_back(c);
    k.mean.push_back(mean);
    k.stddev.push_back(runs.size() > 1 ? std::sqrt(sq / double(runs.size() - 1)) : 0.0);
  }
  return k;
}

void write_settlement_by_k(const std::filesystem::path& file, const std::vector<KStats>& stats) {
  std::ofstream out(file, std::ios::trunc);
  if (!out) throw std::runtime_error("cannot write " + file.string());
  out.precision(10);
  out << "cycle";
  for (const KStats& k : stats) out << ",mean_k" << number_text(k.k_factor) << ",std_k" << number_text(k.k_factor);
  out << '\n';
  // The rows follow the longest k factor; cycles are 1, 2, … in every ballast run.
  const KStats* longest = nullptr;
  for (const KStats& k : stats)
    if (!longest || k.cycle.size() > longest->cycle.size()) longest = &k;
  const std::size_t rows = longest ? longest->cycle.size() : 0;
  for (std::size_t i = 0; i < rows; ++i) {
    out << longest->cycle[i];
    for (const KStats& k : stats) {
      if (i < k.cycle.size()) out << ',' << k.mean[i] << ',' << k.stddev[i];
      else out << ",,";
    }
    out << '\n';
  }
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

bool decreases_with_k(std::vector<KStats> stats) {
  std::erase_if(stats, [](const KStats& k) { return k.mean.empty(); });
  std::sort(stats.begin(), stats.end(), [](const KStats& a, const KStats& b) { return a.k_factor < b.k_factor; });
  if (stats.size() < 2) return false;
  for (std::size_t i = 1; i < stats.size(); ++i)
    if (!(stats[i].mean.back() < stats[i - 1].mean.back())) return false;
  return true;
}

}  // namespace stiffness
