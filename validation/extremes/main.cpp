// validation/extremes/main.cpp — `nscd_extremes`: the extremes suite (extremes.hpp), one
// command.
//
//   nscd_extremes                 the CI subset (points marked quick), NLGS and NEWTON_AC
//   nscd_extremes --full          every point of every family: the limits table of docs/extremes.md
//   nscd_extremes --family TEXT   only the families whose name contains TEXT
//   nscd_extremes --solver NAME   only NLGS or NEWTON_AC
//   nscd_extremes --markdown FILE also write the runs and the limits as markdown tables
//   nscd_extremes --policy P --tol X --max-sweeps N   another NLGS setting (default: the
//                                 drivers' QM/16, 1.666e-4, 1000)
//
// Exit status: 0 when no run is SILENT and every run marked must_hold holds; 1 otherwise;
// 2 on a bad argument.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "extremes.hpp"
#include "nscd/solvers/newton_ac.hpp"

using namespace nscd;
using namespace nscd::extremes;

namespace {

struct Row {
  std::string family, value, solver;
  Outcome o;
  bool must_hold = false;
};

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::string run_line(const Row& r) {
  std::ostringstream s;
  s << "| " << r.family << " | " << r.value << " | " << r.solver << " | " << name_of(r.o.verdict) << " | "
    << fmt("%.2e", r.o.max_overlap) << " | " << fmt("%.2e", r.o.max_drift) << " | " << fmt("%.2e", r.o.energy_gain)
    << " | " << fmt("%.1e", r.o.max_residual) << " | " << r.o.unconverged << "/" << r.o.false_converged << "/"
    << r.o.alert_skips << "/" << r.o.coarse << " of " << r.o.steps << " | " << fmt("%.1f", r.o.seconds) << " | " << r.o.failed
    << (r.o.note.empty() ? "" : (r.o.failed.empty() ? "" : "; ") + r.o.note) << " |";
  return s.str();
}

}  // namespace

int main(int argc, char** argv) {
  bool full = false;
  std::string family_filter, solver_filter, markdown, policy, tol, max_sweeps;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&](std::string& out) {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "nscd_extremes: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      out = argv[++i];
    };
    if (a == "--full") full = true;
    else if (a == "--quick") full = false;
    else if (a == "--family") value(family_filter);
    else if (a == "--solver") value(solver_filter);
    else if (a == "--markdown") value(markdown);
    else if (a == "--policy") value(policy);
    else if (a == "--tol") value(tol);
    else if (a == "--max-sweeps") value(max_sweeps);
    else {
      std::fprintf(stderr, "nscd_extremes: unknown argument '%s' (--full, --quick, --family TEXT, --solver NAME, --markdown FILE, --policy P, --tol X, --max-sweeps N)\n", a.c_str());
      return 2;
    }
  }
  std::vector<SolverKind> solvers{SolverKind::NLGS};
  if (newton_ac_available()) solvers.push_back(SolverKind::NEWTON_AC);
  else std::printf("NEWTON_AC is not available in this build (no SuiteSparse): NLGS only\n");

  const char* header = "| family | value | solver | verdict | max overlap (m) | max drift (m) | energy gain (J/m) | max residual | unconv./false conv./alert skips/coarse | s | failed; measured |\n"
                       "|---|---|---|---|---|---|---|---|---|---|---|";
  std::printf("%s\n", header);
  std::vector<Row> rows;
  std::ostringstream limits;
  limits << "| family | what must hold | solver | holds up to | first failure |\n|---|---|---|---|---|\n";
  int silent = 0, must_fail = 0;
  for (const Family& f : families(full)) {
    if (!family_filter.empty() && f.name.find(family_filter) == std::string::npos) continue;
    for (SolverKind k : solvers) {
      const std::string solver = k == SolverKind::NLGS ? "NLGS" : "NEWTON_AC";
      if (!solver_filter.empty() && solver != solver_filter) continue;
      std::string holds_to = "-", first_failure = "none in the range";
      bool failing = false;
      int ran = 0;
      for (const Point& p : f.points) {
        if (!full && !p.quick) continue;
        StepperOptions o = setting(k);
        if (!policy.empty()) o.nlgs.policy = parse_convergence_policy(policy);
        if (!tol.empty()) o.nlgs.tol = std::stod(tol);
        if (!max_sweeps.empty()) o.nlgs.max_sweeps = std::stoi(max_sweeps);
        Row r{f.name, p.value, solver, run(p.build(), o), p.must_hold};
        ++ran;
        std::printf("%s\n", run_line(r).c_str());
        std::fflush(stdout);
        const bool ok = r.o.verdict == Verdict::Holds || r.o.verdict == Verdict::Warned;
        if (r.o.verdict == Verdict::Silent) ++silent;
        if (r.must_hold && !ok) ++must_fail;
        if (!ok && !failing) {
          failing = true;
          first_failure = p.value + ": " + name_of(r.o.verdict) + " (" + r.o.failed + ")";
        }
        if (ok && !failing) holds_to = p.value;
        rows.push_back(std::move(r));
      }
      if (ran > 0) limits << "| " << f.name << " | " << f.holds << " | " << solver << " | " << holds_to << " | " << first_failure << " |\n";
    }
  }
  std::printf("\nLimits (%s):\n%s", full ? "--full" : "quick subset", limits.str().c_str());
  for (const Row& r : rows)
    if (!r.o.refused.empty()) std::printf("refused: %s %s %s: %.300s\n", r.family.c_str(), r.value.c_str(), r.solver.c_str(), r.o.refused.c_str());
  if (!markdown.empty()) {
    std::ofstream out(markdown);
    out << "## Limits\n\n" << limits.str() << "\n## Runs\n\n" << header << "\n";
    for (const Row& r : rows) out << run_line(r) << "\n";
    if (!out) {
      std::fprintf(stderr, "nscd_extremes: cannot write %s\n", markdown.c_str());
      return 1;
    }
  }
  std::printf("\n%zu runs: %d SILENT, %d nominal runs failing\n", rows.size(), silent, must_fail);
  return silent == 0 && must_fail == 0 ? 0 : 1;
}
