// examples/accuracy_study/ranking.hpp — does a smaller study rank the settings as the full one
// does? Two finished studies of the same kind (their table.csv and trade.csv), compared setting
// by setting: for each group of rows (study 1's settings, study 2's steps per inclination) and
// each measure (cost, iterations, overlaps, settlement error), Spearman's rank correlation and
// the share of pairs of settings put in the same order; and whether each setting is within the
// spread between samples in both (issue #10: "use a reduced sample only if you show it gives the
// same ranking as the full one").
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "settings.hpp"

namespace accuracy {

/// A finished study's measures, read back from DIR/table.csv and DIR/trade.csv, by setting label
/// (NaN where the run failed or the file lacks the column).
struct Measures {
  std::map<std::string, double> value;  ///< "cpu_per_cycle", "mean_iterations", "unconverged_steps", "mean_overlap", ...
  int within_spread = -1;               ///< 1, 0, or -1 when unknown
};
using StudyMeasures = std::map<std::string, Measures>;

/// The measures compared, in the report's order.
const std::vector<std::string>& ranked_measures();

/// Reads DIR/table.csv and DIR/trade.csv; throws std::runtime_error naming the file when one is
/// missing or a line has the wrong number of fields.
StudyMeasures read_study(const std::filesystem::path& dir);

/// Spearman's rank correlation of two equally long series (ranks averaged over ties); NaN with
/// fewer than 3 values or when either series is constant.
double spearman(const std::vector<double>& a, const std::vector<double>& b);

/// Pairs (i < j) ordered the same way in both series, and pairs comparable (no tie in either).
struct PairOrder {
  int same = 0, comparable = 0;
};
PairOrder pair_order(const std::vector<double>& a, const std::vector<double>& b);

/// One group × measure of the comparison.
struct RankAgreement {
  std::string group;    ///< "study 1 (criterion)", "study 2, vertical", "study 2, inclined 5°"
  std::string measure;  ///< one of ranked_measures()
  int settings = 0;     ///< settings with a finite value in both studies
  double spearman = 0.0;
  PairOrder pairs;
};

/// Whether a setting is within the spread in each study.
struct Verdict {
  std::string setting;
  int here = -1, other = -1;
};

struct RankComparison {
  std::vector<RankAgreement> agreements;
  std::vector<Verdict> verdicts;  ///< the settings of the groups known in both
  int verdicts_same() const;
};

/// Compares `here` with `other` over `settings` (the study's list: it gives each label its group;
/// spread rows are not ranked).
RankComparison compare_rankings(const std::vector<Setting>& settings, const StudyMeasures& here, const StudyMeasures& other);

/// ranking.csv: group,measure,settings,spearman,pairs_same,pairs_comparable.
void write_ranking(const std::filesystem::path& file, const RankComparison& c);
/// The report's section: the table of agreements and the verdicts that differ.
std::string ranking_section(const RankComparison& c, const std::string& other_name);

}  // namespace accuracy
