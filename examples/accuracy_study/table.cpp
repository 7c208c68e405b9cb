// examples/accuracy_study/table.cpp — reading the runs and reducing them (see table.hpp).
#include "table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace accuracy {

namespace fs = std::filesystem;

const char* const kTableHeader =
    "setting,solver,policy,tol,dt,inclination,wall_seconds,mean_iterations,unconverged_steps,mean_overlap,max_overlap,"
    "cumulated_overlap,settlement";

std::map<std::string, std::string> read_summary(const fs::path& file) {
  std::map<std::string, std::string> m;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    const auto eq = line.find(" = ");
    if (eq != std::string::npos) m[line.substr(0, eq)] = line.substr(eq + 3);
  }
  return m;
}

namespace {

double number(const std::map<std::string, std::string>& m, const std::string& key, const fs::path& file) {
  const auto it = m.find(key);
  if (it == m.end()) throw std::runtime_error(file.string() + " has no '" + key + "'");
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(it->second, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != it->second.size() || !std::isfinite(v))
    throw std::runtime_error(file.string() + ": '" + key + " = " + it->second + "' is not a finite number");
  return v;
}

std::string csv_number(double v) {
  if (!std::isfinite(v)) return "nan";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

bool same(double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)); }

// The reference setting on any sample: the reference and spread rows, and study 2's dt 2e-4
// vertical row (the same run as the reference).
bool is_reference_setting(const Setting& s) {
  const Setting r = reference_setting(s.seed);
  return s.solver == r.solver && s.policy == r.policy && same(s.tol, r.tol) && s.min_sweeps == r.min_sweeps && same(s.dt, r.dt) &&
         same(s.inclination, r.inclination);
}

// A row of study 2's series: a step row, or the reference run (dt 2e-4, vertical), which is
// that series' dt 2e-4 row when a table holds both studies (trade).
bool in_step_series(const Row& r) { return r.setting.role == Role::step || r.setting.role == Role::reference; }

}  // namespace

Row read_row(const Setting& s, const fs::path& summary, int cycles) {
  Row r;
  r.setting = s;
  const double nan = std::nan("");
  r.wall_seconds = r.cpu_per_cycle = r.mean_iterations = r.max_iterations = r.mean_presweeps = r.unconverged_steps = nan;
  r.mean_overlap = r.max_overlap = r.cumulated_overlap = r.settlement = nan;
  if (!fs::exists(summary)) {
    r.why = "no " + summary.string();
    return r;
  }
  const auto m = read_summary(summary);
  const auto result = m.find("result");
  if (result == m.end() || result->second != "valid") {
    r.why = summary.string() + ": result " + (result == m.end() ? "missing" : "'" + result->second + "'");
    return r;
  }
  try {
    r.cycles = static_cast<int>(number(m, "cycles", summary));
    if (r.cycles != cycles) throw std::runtime_error(summary.string() + ": " + std::to_string(r.cycles) + " cycles, not " + std::to_string(cycles));
    r.wall_seconds = number(m, "time_per_cycle", summary) * r.cycles;
    r.cpu_per_cycle = number(m, "cpu_time_per_cycle", summary);
    r.mean_iterations = number(m, "mean_sweeps", summary);
    // optional: a run made before ballast recorded it (or resumed from such a checkpoint) has none
    const auto most = m.find("max_sweeps");
    if (most != m.end()) r.max_iterations = std::strtod(most->second.c_str(), nullptr);
    if (const auto pre = m.find("mean_presweeps"); pre != m.end()) r.mean_presweeps = std::strtod(pre->second.c_str(), nullptr);
    r.unconverged_steps = number(m, "unconverged_steps", summary);
    r.mean_overlap = number(m, "mean_overlap", summary);
    r.max_overlap = number(m, "max_overlap", summary);
    r.cumulated_overlap = number(m, "cumulated_overlap", summary);
    r.settlement = number(m, "final_settlement", summary);
    r.ok = true;
  } catch (const std::exception& e) {
    r.why = e.what();
  }
  return r;
}

void write_table(const fs::path& file, const std::vector<Row>& rows) {
  std::ofstream out(file);
  out << kTableHeader << '\n';
  for (const Row& r : rows) {
    const Setting& s = r.setting;
    out << s.label << ',' << s.solver << ',' << s.policy << ',' << number_text(s.tol) << ',' << number_text(s.dt) << ','
        << number_text(s.inclination) << ',' << csv_number(r.wall_seconds) << ',' << csv_number(r.mean_iterations) << ','
        << csv_number(r.unconverged_steps) << ',' << csv_number(r.mean_overlap) << ',' << csv_number(r.max_overlap) << ','
        << csv_number(r.cumulated_overlap) << ',' << csv_number(r.settlement) << '\n';
  }
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

Spread sample_spread(const std::vector<Row>& rows) {
  Spread s;
  std::vector<double> v;
  for (const Row& r : rows)
    if (r.ok && is_reference_setting(r.setting)) v.push_back(r.settlement);
  s.samples = static_cast<int>(v.size());
  if (v.empty()) return s;
  s.min = *std::min_element(v.begin(), v.end());
  s.max = *std::max_element(v.begin(), v.end());
  for (double x : v) s.mean += x / double(v.size());
  if (v.size() > 1) {
    double q = 0.0;
    for (double x : v) q += (x - s.mean) * (x - s.mean);
    s.stddev = std::sqrt(q / double(v.size() - 1));
  }
  return s;
}

std::optional<Row> error_reference(const std::vector<Row>& rows, const Row& r) {
  const Row* best = nullptr;
  const Row* nlgs = nullptr;  // study 1 without a NEWTON_AC row: the tightest NonStrict NLGS row
  for (const Row& x : rows) {
    if (!x.ok) continue;
    if (r.setting.role == Role::step) {
      if (in_step_series(x) && same(x.setting.inclination, r.setting.inclination) &&
          (best == nullptr || x.setting.dt < best->setting.dt))
        best = &x;
    } else if (x.setting.role == Role::criterion && same(x.setting.dt, r.setting.dt)) {
      if (x.setting.solver == "NEWTON_AC" && (best == nullptr || x.setting.tol < best->setting.tol)) best = &x;
      if (x.setting.solver == "NLGS" && x.setting.policy == "NonStrict" && x.setting.min_sweeps == 0 &&
          (nlgs == nullptr || x.setting.tol < nlgs->setting.tol))
        nlgs = &x;
    }
  }
  if (best == nullptr) best = nlgs;
  if (best == nullptr) return std::nullopt;
  return *best;
}

double overlap_ratio(const std::vector<Row>& rows, double inclination) {
  const Row *lo = nullptr, *hi = nullptr;
  for (const Row& r : rows) {
    if (!r.ok || !in_step_series(r) || !same(r.setting.inclination, inclination)) continue;
    if (lo == nullptr || r.setting.dt < lo->setting.dt) lo = &r;
    if (hi == nullptr || r.setting.dt > hi->setting.dt) hi = &r;
  }
  if (lo == nullptr || hi == lo || !(lo->mean_overlap > 0)) return std::nan("");
  return hi->mean_overlap / lo->mean_overlap;
}

double largest_step_within(const std::vector<Row>& rows, double inclination, double tolerance) {
  std::vector<const Row*> v;
  for (const Row& r : rows)
    if (in_step_series(r) && same(r.setting.inclination, inclination)) v.push_back(&r);
  std::sort(v.begin(), v.end(), [](const Row* a, const Row* b) { return a->setting.dt < b->setting.dt; });
  if (v.empty() || !v.front()->ok) return 0.0;
  double largest = 0.0;
  for (const Row* r : v) {
    if (!r->ok || !(std::abs(r->settlement - v.front()->settlement) <= tolerance)) break;
    largest = r->setting.dt;
  }
  return largest;
}

void write_trade(const fs::path& file, const std::vector<Row>& rows, const Spread& spread) {
  std::ofstream out(file);
  out << "setting,solver,family,cpu_per_cycle,wall_per_cycle,mean_iterations,mean_overlap,max_overlap,settlement_error,reference,"
         "within_spread,max_iterations,mean_presweeps\n";
  for (const Row& r : rows) {
    const auto ref = error_reference(rows, r);
    const double err = (r.ok && ref) ? std::abs(r.settlement - ref->settlement) : std::nan("");
    const bool within = std::isfinite(err) && spread.samples > 1 && err <= spread.range();
    out << r.setting.label << ',' << r.setting.solver << ',' << (r.setting.role == Role::step ? "step" : r.setting.role == Role::spread ? "spread" : "criterion") << ','
        << csv_number(r.cpu_per_cycle) << ',' << csv_number(r.ok ? r.wall_seconds / r.cycles : std::nan("")) << ','
        << csv_number(r.mean_iterations) << ',' << csv_number(r.mean_overlap) << ',' << csv_number(r.max_overlap) << ','
        << csv_number(err) << ',' << (ref ? ref->setting.label : "none") << ',' << (within ? 1 : 0) << ','
        << csv_number(r.max_iterations) << ',' << csv_number(r.mean_presweeps) << '\n';
  }
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

std::string fixed(double v, const char* fmt) {
  if (!std::isfinite(v)) return "–";
  char buf[48];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

namespace {

// The report's title, run size, the columns explained and, when NEWTON_AC ran as the hybrid, what
// its rows hold.
void report_head(std::ostringstream& o, Study study, const std::vector<Row>& rows, const std::string& run_size) {
  o << "# Accuracy study: " << study_name(study) << "\n\n" << run_size << "\n\n";
  o << "Columns: wall time of the cycles (s, the machine shared, runs in parallel), processor time per cycle (s), "
       "solver iterations per step (NLGS sweeps or Newton iterations: mean, and the most in one step), unconverged steps, overlaps over the run "
       "(mean over the steps of the mean overlap, largest overlap, mean over the steps of the summed overlap), "
       "final settlement, and its difference from the tightest setting of its family (study 1: the NEWTON_AC "
       "row of smallest tolerance, or without one the NonStrict NLGS row of smallest tolerance; study 2: the shortest step at the same "
       "inclination).\n\n";
  const auto hybrid = std::find_if(rows.begin(), rows.end(), [](const Row& r) {
    return r.setting.solver == "NEWTON_AC" && r.setting.newton_presweeps > 0;
  });
  if (hybrid != rows.end())
    o << "The NEWTON_AC rows are the hybrid: each step, at most " << hybrid->setting.newton_presweeps
      << " NLGS sweeps (stopping at Quad " << number_text(hybrid->setting.newton_presweep_tol)
      << "), then Newton to the row's tolerance; their iterations are Newton's (the sweeps a step, when the runs recorded them, "
         "in brackets), the sweeps' cost is in the times.\n\n";
}

// The table, one line per row, then the runs that failed.
void report_table(std::ostringstream& o, const std::vector<Row>& rows, const Spread& sp) {
  o << "| setting | wall (s) | CPU s/cycle | iterations (mean / max) | unconverged | mean overlap (µm) | max overlap (µm) | cumulated (µm) "
       "| settlement (mm) | Δ settlement (mm) | within spread |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  int failed = 0;
  for (const Row& r : rows) {
    const auto ref = error_reference(rows, r);
    const double err = (r.ok && ref) ? r.settlement - ref->settlement : std::nan("");
    const bool shown = std::isfinite(err) && sp.samples >= 2 && r.setting.role != Role::spread;  // a spread row is the spread
    const char* within = !shown ? "–" : (std::abs(err) <= sp.range() ? "yes" : "no");
    o << "| " << r.setting.label << " | " << fixed(r.wall_seconds, "%.1f") << " | " << fixed(r.cpu_per_cycle, "%.3g") << " | "
      << fixed(r.mean_iterations, "%.1f") << " / " << fixed(r.max_iterations, "%.0f")
      << (r.setting.solver == "NEWTON_AC" && r.mean_presweeps > 0 ? " (+" + fixed(r.mean_presweeps, "%.1f") + " NLGS)" : "") << " | " << fixed(r.unconverged_steps, "%.0f") << " | " << fixed(1e6 * r.mean_overlap, "%.3g")
      << " | " << fixed(1e6 * r.max_overlap, "%.3g") << " | " << fixed(1e6 * r.cumulated_overlap, "%.3g") << " | "
      << fixed(1e3 * r.settlement, "%.3f") << " | " << fixed(1e3 * err, "%+.3f") << " | " << within << " |\n";
    failed += r.ok ? 0 : 1;
  }
  o << "\n";
  if (failed > 0) {
    o << "Failed runs (" << failed << "):\n\n";
    for (const Row& r : rows)
      if (!r.ok) o << "- " << r.setting.label << ": " << r.why << "\n";
    o << "\n";
  }
}

// The spread between samples, and for study 1 the row its Δ settlement is measured from.
void report_spread(std::ostringstream& o, Study study, const std::vector<Row>& rows, const Spread& sp) {
  o << "**Spread between samples** (the reference setting on " << sp.samples << " samples): settlement mean "
    << fixed(1e3 * sp.mean, "%.3f") << " mm, range " << fixed(1e3 * sp.range(), "%.3f") << " mm, standard deviation "
    << fixed(1e3 * sp.stddev, "%.3f") << " mm. A setting is *within spread* when its settlement differs from the tightest "
    << "setting's by no more than that range.\n\n";
  if (study != Study::criterion && study != Study::trade) return;
  for (const Row& r : rows) {
    if (r.setting.role != Role::reference) continue;
    const auto ref = error_reference(rows, r);
    o << "**Δ settlement of study 1** is measured from "
      << (ref ? "`" + ref->setting.label + "`" : std::string("no row (none ran)"))
      << (ref && ref->setting.solver != "NEWTON_AC"
              ? " (no NEWTON_AC row ran: the NonStrict NLGS row of smallest tolerance)"
              : "")
      << ".\n\n";
    break;
  }
}

// Study 2's findings per inclination: the overlap ratio and the largest step within the spread.
void report_steps(std::ostringstream& o, const std::vector<Row>& rows, const Spread& sp) {
  for (double inc : {0.0, 5.0}) {
    const double ratio = overlap_ratio(rows, inc);
    const double within = sp.samples > 1 ? largest_step_within(rows, inc, sp.range()) : 0.0;
    o << "**Step length, load " << (inc == 0.0 ? "vertical" : "inclined 5°")
      << ":** mean overlap at dt 1e-3 / at dt 1e-4 = " << fixed(ratio, "%.2f")
      << " (paper: about 8); largest step whose settlement, and every shorter step's, stays "
      << "within the spread of the dt 1e-4 run: " << (within > 0 ? number_text(within) + " s" : std::string("none"))
      << ".\n\n";
  }
}

// Study 1's finding: the cheapest setting (processor time per cycle) within the spread, per solver.
void report_cheapest(std::ostringstream& o, const std::vector<Row>& rows, const Spread& sp) {
  for (const char* solver : {"NLGS", "NEWTON_AC"}) {
    const Row* best = nullptr;
    for (const Row& r : rows) {
      if (!r.ok || r.setting.solver != solver || r.setting.role == Role::spread || r.setting.role == Role::step)
        continue;
      const auto ref = error_reference(rows, r);
      if (!ref || sp.samples < 2 || !(std::abs(r.settlement - ref->settlement) <= sp.range())) continue;
      if (best == nullptr || r.cpu_per_cycle < best->cpu_per_cycle) best = &r;
    }
    o << "**Cheapest " << solver << " setting at dt 2e-4 within the spread:** "
      << (best ? best->setting.label + " (" + fixed(best->cpu_per_cycle, "%.3g") + " s of processor time per cycle, " +
                     fixed(best->mean_iterations, "%.1f") + " iterations per step, mean overlap " +
                     fixed(1e6 * best->mean_overlap, "%.3g") + " µm)"
               : std::string("none"))
      << ".\n\n";
  }
}

}  // namespace

void write_report(const fs::path& file, Study study, const std::vector<Row>& rows, const std::string& run_size,
                  const std::string& plots_note) {
  const Spread sp = sample_spread(rows);
  std::ostringstream o;
  report_head(o, study, rows, run_size);
  report_table(o, rows, sp);
  report_spread(o, study, rows, sp);
  if (study == Study::step || study == Study::trade) report_steps(o, rows, sp);
  if (study == Study::criterion || study == Study::trade) report_cheapest(o, rows, sp);
  if (!plots_note.empty()) o << plots_note << "\n";
  std::ofstream out(file);
  out << o.str();
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

}  // namespace accuracy
