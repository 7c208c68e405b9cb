// examples/solver_comparison/output.cpp — step 3 of the comparison: problems.csv (one row per
// solve), summary.txt (key = value lines, then the tables) and the printed tables.
//
// The tables answer "which solver gets there first": for each problem and each target
// residual (1e-4, 1e-6, 1e-8 of ||q||), the fastest NLGS solve (any policy, any tolerance)
// and the fastest NEWTON_AC solve whose residual_q is at or below the target, and their
// time ratio.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "comparison.hpp"
#include "nscd/core/error.hpp"
#include "nscd/solvers/newton_ac.hpp"

namespace fs = std::filesystem;

namespace comparison {
namespace {

constexpr double kTargets[] = {1e-4, 1e-6, 1e-8};

// The fastest row of `solver` on `problem` with residual_q <= target (nullptr if none).
const Row* fastest(const std::vector<Row>& rows, const std::string& problem, const std::string& solver, double target) {
  const Row* best = nullptr;
  for (const Row& r : rows)
    if (r.problem == problem && r.solver == solver && r.residual_q <= target && (!best || r.seconds < best->seconds))
      best = &r;
  return best;
}

// The smallest residual_q a solver got on a problem (any setting), or -1.
double best_residual(const std::vector<Row>& rows, const std::string& problem, const std::string& solver) {
  double best = -1.0;
  for (const Row& r : rows)
    if (r.problem == problem && r.solver == solver && (best < 0.0 || r.residual_q < best)) best = r.residual_q;
  return best;
}

std::string cell(const Row* r) {
  if (!r) return "-";
  std::ostringstream s;
  s << std::setprecision(3);
  if (r->solver == "NLGS") s << r->policy << " " << std::scientific << std::setprecision(0) << r->tol;
  else s << "tol " << std::scientific << std::setprecision(0) << r->tol;
  s << std::defaultfloat << std::setprecision(3) << ": " << r->iterations << " it, " << r->seconds << " s";
  return s.str();
}

// The table: problem, contacts, then per target the NLGS cell, the NEWTON_AC cell, the ratio.
std::string table(const std::vector<NamedProblem>& problems, const std::vector<Row>& rows) {
  std::ostringstream t;
  t << "Fastest solve from r = 0 reaching residual/|q| <= target (cells: setting: iterations, median time;\n"
       "'-': no setting reached it; ratio = NLGS time / NEWTON_AC time)\n";
  for (const double target : kTargets) {
    t << "\ntarget " << std::scientific << std::setprecision(0) << target << std::defaultfloat << "\n";
    char line[512];
    std::snprintf(line, sizeof line, "  %-16s %8s  %-32s %-28s %s\n", "problem", "contacts", "NLGS", "NEWTON_AC", "ratio");
    t << line;
    for (const NamedProblem& p : problems) {
      const Row* g = fastest(rows, p.name, "NLGS", target);
      const Row* n = fastest(rows, p.name, "NEWTON_AC", target);
      std::string ratio = "-";
      if (g && n && n->seconds > 0.0) {
        std::ostringstream r;
        r << std::setprecision(2) << g->seconds / n->seconds;
        ratio = r.str();
      }
      std::snprintf(line, sizeof line, "  %-16s %8zu  %-32s %-28s %s\n", p.name.c_str(), p.problem.nc, cell(g).c_str(),
                    cell(n).c_str(), ratio.c_str());
      t << line;
    }
  }
  t << "\nSmallest residual/|q| reached (any setting)\n";
  auto sci = [](double v) {
    char b[32];
    if (v < 0.0) return std::string("-");  // no solve of that solver
    std::snprintf(b, sizeof b, "%.2e", v);
    return std::string(b);
  };
  for (const NamedProblem& p : problems) {
    char line[256];
    std::snprintf(line, sizeof line, "  %-16s NLGS %-9s  NEWTON_AC %s\n", p.name.c_str(),
                  sci(best_residual(rows, p.name, "NLGS")).c_str(), sci(best_residual(rows, p.name, "NEWTON_AC")).c_str());
    t << line;
  }
  return t.str();
}

}  // namespace

void write_csv(const Config& c, const std::vector<Row>& rows) {
  const fs::path file = fs::path(c.output) / "problems.csv";
  std::ofstream csv(file);
  csv << "problem,contacts,solver,policy,tol,iterations,residual_q,seconds,reached\n" << std::setprecision(6);
  for (const Row& r : rows)
    csv << r.problem << ',' << r.contacts << ',' << r.solver << ',' << r.policy << ',' << r.tol << ',' << r.iterations << ','
        << r.residual_q << ',' << r.seconds << ',' << (r.reached ? 1 : 0) << '\n';
  if (!csv) throw nscd::Error("cannot write " + file.string());
}

std::string write_summary(const Config& c, const std::vector<NamedProblem>& problems, const std::vector<Row>& rows,
                          double wall_seconds, const std::string& extra_summary) {
  const fs::path out(c.output);
  int nlgs = 0, newton = 0, nlgs_reached = 0, newton_reached = 0;
  for (const Row& r : rows) {
    (r.solver == "NLGS" ? nlgs : newton) += 1;
    if (r.reached) (r.solver == "NLGS" ? nlgs_reached : newton_reached) += 1;
  }
  const std::string text = table(problems, rows);
  std::ofstream sum(out / "summary.txt");
  sum << std::setprecision(6) << "quick = " << (c.quick ? 1 : 0) << "\n"
      << "problems = " << problems.size() << "\n"
      << "solves = " << rows.size() << "\n"
      << "nlgs_solves = " << nlgs << "\n"
      << "nlgs_reached = " << nlgs_reached << "\n"
      << "newton_available = " << (nscd::newton_ac_available() ? 1 : 0) << "\n"
      << "newton_solves = " << newton << "\n"
      << "newton_reached = " << newton_reached << "\n"
      << "time_cap = " << c.time_cap << "\n"
      << "newton_max_iterations = " << c.newton_max_iterations << "\n"
      << "repeats = " << c.repeats << "\n"
      << "wall_time = " << wall_seconds << "\n";
  // the baseline: residual/||q|| of r = 0 (1 when every contact with q_N < 0 is closed, far
  // less when open contacts' law shifts dominate ||q||)
  for (const NamedProblem& p : problems) {
    const double r0 = nscd::natural_map_error(p.problem, std::vector<double>(2 * p.problem.nc, 0.0)).relative_q;
    sum << "contacts_" << p.name << " = " << p.problem.nc << "\n" << "residual_q_at_r0_" << p.name << " = " << r0 << "\n";
  }
  sum << extra_summary;
  if (!nscd::newton_ac_available())
    sum << "\nNOTE: NEWTON_AC is not available in this build (no SuiteSparse): its rows are skipped.\n";
  sum << "\nProblems\n";
  for (const NamedProblem& p : problems) sum << "  " << p.name << ": " << p.origin << "\n";
  sum << "\n" << text;
  if (!sum) throw nscd::Error("cannot write " + (out / "summary.txt").string());
  return text;
}

}  // namespace comparison
