// examples/ballast/run_state.hpp — what a ballast run's checkpoint carries besides the registry,
// and the files a resumed run takes up again (for ballast_study.cpp; not a public interface).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "ballast_study.hpp"

namespace ballast {

// The values of the options added since the first checkpoints, as runs had them before: the
// paper's fixed order, plain sweeps, no mixing, no projection (defaults since issue #36).
extern const std::map<std::string, std::string> kBeforeTheOption;

// The state of a run that a checkpoint must carry besides the registry.
struct RunState {
  int cycles_done = 0;
  double t0 = 0.0, y_ref = 0.0, x_ref = 0.0;
  std::int64_t sweeps = 0, steps = 0, unconverged = 0;
  double max_overlap = 0.0, sum_mean_overlap = 0.0;
  double sum_total_overlap = 0.0;  ///< Σ over steps of the step's total overlap (NaN: resumed from a checkpoint without it)
  double cpu_seconds = 0.0;        ///< processor time of the cycles (all processes that ran them)
  std::int64_t max_sweeps = 0;     ///< most iterations in one step (−1: resumed from a checkpoint without it)
  std::int64_t presweeps = 0;      ///< NEWTON_AC hybrid: NLGS sweeps before Newton, summed (−1: unknown, as above)
  double last_settlement_min = 0.0, last_settlement_max = 0.0;
  /// energy dissipated since the start of the cycles by the contacts and by the sublayer's
  /// dampers (J/m; NaN: resumed from a checkpoint without them)
  double contact_dissipation = 0.0, damper_dissipation = 0.0;
};

/// The run's options and state as checkpoint keys ("state.*"; `sample`: the sample file the run
/// started from, if any).
std::map<std::string, std::string> state_map(const Config& c, const RunState& s, const std::string& sample);
/// Reads state_map's keys back strictly: each value whole, finite, in range; errors name the
/// file and the key.
RunState state_from(const std::map<std::string, std::string>& m, const std::string& file);

// Keeps the header and the complete rows whose first column is <= last (a resumed run rewrites
// the rest). A run killed while writing can leave its last row cut short, with no end of line:
// that row is dropped whatever it reads as ("42" cut from step 4248 would read as step 42 and
// stay otherwise). A file written by an earlier version, whose columns are the first of
// `columns`, gets the new header and its rows "nan" in the new columns, so that every row has
// every column. The file is rewritten whole or not at all (atomic_write), so a kill during the
// truncation leaves the old file.
void truncate_csv(const std::filesystem::path& file, double last, const std::vector<std::string>& columns);

// --continue (batch jobs, requeued or rerun): resume the run in --output when it has a
// checkpoint, else start it there replacing ballast's own files. Returns false when the run
// there has already finished its --cycles (summary.txt says so): nothing to do.
bool apply_continue(Config& c);

}  // namespace ballast
