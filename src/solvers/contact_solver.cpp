// nscd/solvers/contact_solver.cpp — see contact_solver.hpp.
#include "nscd/solvers/contact_solver.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "nscd/core/error.hpp"
#include "nscd/solvers/nlgs_colored.hpp"
#include "nscd/solvers/nlgs_mixing.hpp"
#include "nscd/solvers/nlgs_sweep.hpp"
#include "nscd/solvers/scene_backend.hpp"

namespace nscd {
namespace {

/// The NLGS sums and counts of a solve, into a report.
SolveReport nlgs_report(const NlgsResult& r) {
  SolveReport s;
  s.sweeps = r.sweeps;
  s.mixes = r.mixes;
  s.mix_returns = r.mix_returns;
  s.converged = r.converged;
  s.criteria = r.criteria;
  s.parts = r.parts;
  return s;
}

/// NLGS in a sequential order (fixed, reversed, shuffled, alternating) on the scene in place,
/// with Anderson mixing where asked (nlgs_mixing.hpp).
class SequentialNlgs final : public ContactSolver {
 public:
  explicit SequentialNlgs(const ContactSolverOptions& o) : opt_(o.nlgs) {}
  std::string_view name() const override { return "NLGS"; }
  void configure(const ContactSolverOptions& o) override { opt_ = o.nlgs; }
  void solve(ContactSystem& sys, int) override {
    if (opt_.anderson > 0) {
      report_ = nlgs_report(nlgs_iterate_mixed(sys, opt_, ws_, mixing_));
      return;
    }
    SceneBackend be(sys);
    report_ = nlgs_report(nlgs_iterate(be, opt_, ws_));
  }

 private:
  NlgsOptions opt_;
  NlgsWorkspace ws_;
  NlgsMixingBuffers mixing_;
};

/// NLGS colour by colour (nlgs_colored.hpp): prepare() lays the system out in its blocks.
class ColoredNlgs final : public ContactSolver {
 public:
  explicit ColoredNlgs(const ContactSolverOptions& o) : opt_(o.nlgs) {}
  std::string_view name() const override { return "NLGS_COLORED"; }
  void configure(const ContactSolverOptions& o) override { opt_ = o.nlgs; }
  void prepare(ContactSystem& sys, int loop_threads) override { color_contacts(sys, ws_, opt_.order, loop_threads); }
  void solve(ContactSystem& sys, int threads) override {
    NlgsOptions o = opt_;
    o.threads = std::clamp(threads, 1, opt_.threads);
    report_ = nlgs_report(nlgs_iterate_colored(sys, o, ws_));
  }
  ContactColors colors(const ContactSystem& sys) const override {
    const bool laid = ws_.arranged == &sys && ws_.arranged_contacts == sys.contacts.size() &&
                      !ws_.color_start.empty() && ws_.block_start.size() > ws_.color_start.back() &&
                      ws_.block_start[ws_.color_start.back()] == sys.contacts.size();
    return laid ? ContactColors{&ws_.block_start, &ws_.color_start} : ContactColors{};
  }

 private:
  NlgsOptions opt_;
  NlgsColoredWorkspace ws_;
};

/// The global solver on the contacts and the iterated links at once, from the warm-start
/// impulses; the hybrid's NLGS sweeps run first, in place on the scene (links included).
class NewtonAc final : public ContactSolver {
 public:
  explicit NewtonAc(const ContactSolverOptions& o) : opt_(o.newton) {}
  std::string_view name() const override { return "NEWTON_AC"; }
  void configure(const ContactSolverOptions& o) override { opt_ = o.newton; }
  bool reports_residual() const override { return true; }
  void solve(ContactSystem& sys, int) override {
    NewtonOptions no = opt_;
    int presweeps = 0;
    if (no.presweeps > 0) {
      SceneBackend be(sys);
      presweeps = nlgs_iterate(be, presweep_options(no), ws_).sweeps;
      no.presweeps = 0;
    }
    BilateralRows rows;
    const FrictionProblem2D p = sys.local_problem_with_links(rows);
    std::vector<double> r = sys.impulses(true);
    const NewtonResult nr = newton_ac_solve(p, r, no, rows);
    sys.set_impulses(r, true);
    report_ = {};
    report_.presweeps = presweeps;
    report_.sweeps = nr.iterations;
    report_.converged = nr.converged;
    report_.residual = nr.residual;
    report_.line_search_steps = nr.line_search_steps;
    report_.factorizations = nr.refactorizations;
    report_.factor_seconds = nr.factor_seconds;
  }

 private:
  NewtonOptions opt_;
  NlgsWorkspace ws_;  ///< the hybrid's sweeps
};

}  // namespace

std::string_view contact_solver_name(SolverKind kind, const NlgsOptions& nlgs) {
  if (kind == SolverKind::NEWTON_AC) return "NEWTON_AC";
  return is_colored(nlgs.order) ? "NLGS_COLORED" : "NLGS";
}

std::unique_ptr<ContactSolver> make_contact_solver(std::string_view name, const ContactSolverOptions& o) {
  if (name == "NLGS") return std::make_unique<SequentialNlgs>(o);
  if (name == "NLGS_COLORED") return std::make_unique<ColoredNlgs>(o);
  if (name == "NEWTON_AC") return std::make_unique<NewtonAc>(o);
  throw Error("unknown contact solver '" + std::string(name) + "' (NLGS, NLGS_COLORED, NEWTON_AC)");
}

}  // namespace nscd
