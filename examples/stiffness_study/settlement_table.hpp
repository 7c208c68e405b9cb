// examples/stiffness_study/settlement_table.hpp — step 3 of the stiffness study: read the
// cycles.csv of every (sample, k factor) run and reduce them to the mean settlement over the
// samples and its spread, cycle by cycle, for each k factor (Saussine et al. 2006, Fig. 11).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace stiffness {

/// One run's settlement curve: column `column` of its cycles.csv against column "cycle".
struct Series {
  std::vector<int> cycle;
  std::vector<double> settlement;  ///< m, positive downward (as ballast writes it)
};

/// Reads `file` (a ballast cycles.csv: a header of column names, then numeric rows). The
/// columns are found by name, so their order does not matter. Throws std::runtime_error
/// naming the file on a missing file, a missing column or a malformed number.
Series read_cycles_csv(const std::filesystem::path& file, const std::string& column = "settlement_min_load");

/// The samples of one k factor, reduced cycle by cycle.
struct KStats {
  double k_factor = 1.0;
  int samples = 0;             ///< how many runs went into the mean
  std::vector<int> cycle;
  std::vector<double> mean;    ///< m
  std::vector<double> stddev;  ///< m, sample standard deviation (n − 1); 0 for a single run
};

/// Mean and standard deviation over `runs`, on the cycles that every run has (the shortest
/// run sets the length). Throws std::runtime_error if the runs disagree on a cycle number.
KStats aggregate(double k_factor, const std::vector<Series>& runs);

/// Writes `file`: "cycle" then "mean_k<F>,std_k<F>" for each k factor, in the given order;
/// a k factor with fewer cycles than the longest leaves its cells empty past its end.
void write_settlement_by_k(const std::filesystem::path& file, const std::vector<KStats>& stats);

/// True if the final mean settlement strictly decreases as k grows (k factors sorted
/// ascending; k factors without any run are ignored). The paper's Fig. 11 trend: the stiffer
/// the sublayer, the smaller the settlement. False with fewer than two usable k factors.
bool decreases_with_k(std::vector<KStats> stats);

/// "1", "100", "0.5": the shortest text that reads back as `v` (for names like k100_s2006).
std::string number_text(double v);

}  // namespace stiffness
