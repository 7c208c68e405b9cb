// examples/accuracy_study/table.hpp — from the runs' summary.txt to the study's table.csv,
// trade.csv and report.md: one Row per setting, the spread between samples, the settings within
// it, the overlap ratio between the longest and the shortest step, the trade (cost against error).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "settings.hpp"

namespace accuracy {

/// One setting's measures (NaN where its run failed).
struct Row {
  Setting setting;
  bool ok = false;
  std::string why;                 ///< why not ok ("run failed: exit status 1", ...)
  int cycles = 0;
  double wall_seconds = 0.0;       ///< wall time of the cycles (s)
  double cpu_per_cycle = 0.0;      ///< processor time per cycle (s)
  double mean_iterations = 0.0;    ///< NLGS sweeps or Newton iterations per step
  double max_iterations = 0.0;     ///< the most in one step (NaN: a run that did not record it)
  double mean_presweeps = 0.0;     ///< NEWTON_AC's hybrid: NLGS sweeps a step before Newton (NaN: not recorded)
  double unconverged_steps = 0.0;
  double mean_overlap = 0.0, max_overlap = 0.0, cumulated_overlap = 0.0;  ///< m
  double settlement = 0.0;         ///< m, at the smallest load of the last cycle
};

/// Reads "key = value" lines.
std::map<std::string, std::string> read_summary(const std::filesystem::path& file);

/// The row of a setting from its run's summary.txt; not ok (with why) if the file is missing, the
/// run was not valid, it ran other than `cycles` cycles or a value is missing or not finite.
Row read_row(const Setting& s, const std::filesystem::path& summary, int cycles);

/// The table's header (exactly the columns) and the file.
extern const char* const kTableHeader;
void write_table(const std::filesystem::path& file, const std::vector<Row>& rows);

/// The spread between samples: the rows at the reference setting (any sample; study 2's dt 2e-4
/// vertical row is the reference run) that are ok.
struct Spread {
  int samples = 0;
  double mean = 0.0, min = 0.0, max = 0.0, stddev = 0.0;
  double range() const { return max - min; }
};
Spread sample_spread(const std::vector<Row>& rows);

/// The reference row of `r` for the settlement error: for study 1's rows (and the spread rows)
/// the NEWTON_AC criterion row of smallest tolerance (1e-8), or, when no NEWTON_AC row ran, the
/// NonStrict NLGS criterion row of smallest tolerance (1e-7); for a step row, the shortest step
/// at the same inclination. nullopt if absent.
std::optional<Row> error_reference(const std::vector<Row>& rows, const Row& r);

/// Study 2: mean overlap at the longest step over that at the shortest, per inclination.
double overlap_ratio(const std::vector<Row>& rows, double inclination);
/// Study 2: the largest step such that it and every shorter step settle within `tolerance` of
/// the shortest step's settlement (same inclination); 0 if none.
double largest_step_within(const std::vector<Row>& rows, double inclination, double tolerance);

/// trade.csv: setting, solver, family (criterion / step / spread), cpu_per_cycle, wall_per_cycle,
/// mean_iterations, mean_overlap, max_overlap, settlement_error (vs error_reference), reference,
/// within_spread (1/0).
void write_trade(const std::filesystem::path& file, const std::vector<Row>& rows, const Spread& spread);

/// A number for Markdown: printf's `fmt`, or "–" when not finite.
std::string fixed(double v, const char* fmt);

/// report.md: the run size, the table, the spread and the findings of the study.
void write_report(const std::filesystem::path& file, Study study, const std::vector<Row>& rows, const std::string& run_size,
                  const std::string& plots_note);

}  // namespace accuracy
