// examples/datbox/main.cpp — `datbox_run`: runs an LMGC90 DATBOX folder (its 2D rigid subset,
// issue #39; src/io/datbox.hpp) with the settings a command.py would give as options, and writes
// nscd's usual outputs; --write-datbox writes the scene back as a DATBOX (at the end of the run,
// or at once with --steps 0).
//   build/examples/datbox/datbox_run --datbox tests/data/datbox/disks_box --steps 500 --output out/datbox
//   build/examples/datbox/datbox_run --datbox DIR --steps 0 --write-datbox out/copy   (a round trip)
//   build/examples/datbox/datbox_run --datbox DIR --order colored --threads 2 ...      (on two cores)
// Outputs in --output: summary.txt, steps.csv (one row per step), vtk/ (every --output-every
// steps), final.nscd (a checkpoint; not written where a drive is an evolution file or a
// non-constant formula: a checkpoint cannot hold those). docs/user-guide.md §8.
#include <algorithm>
#include <cstdio>
#include <string>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/io/csv.hpp"
#include "nscd/io/datbox.hpp"
#include "nscd/io/vtk_writer.hpp"
#include "nscd/shared/analysis.hpp"
#include "nscd/shared/datbox_warm_start.hpp"
#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/overlap_options.hpp"
#include "nscd/shared/driver/run_main.hpp"
#include "nscd/shared/driver/summary.hpp"
#include "nscd/shared/driver_checks.hpp"
#include "nscd/shared/step_watch.hpp"
#include "nscd/solvers/convergence.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "nscd/solvers/solver_kind.hpp"

using namespace nscd;

struct Config {
  std::string datbox;              // the DATBOX folder
  double dt = 1e-3;                // command.py's dt
  double theta = 0.5;              // command.py's theta
  double tol = 1.666e-4;           // nlgs tol
  std::string norm = "QM/16";      // nlgs norm (LMGC90's 'Quad ', 'QM/16', 'Maxm ': nscd's policies)
  double relaxation = 1.0;         // nlgs relax
  int sweeps = 1000;               // gs_it1 × gs_it2: at most this many sweeps ...
  int check_every = 10;            // ... checked every this many (gs_it2's role)
  std::string solver = "NLGS";
  std::string order = "fixed";     // LMGC90's sweep, contact after contact; a colored one for --threads
  int anderson = 0;                // Anderson mixing of the sweeps (0: off, as LMGC90)
  int threads = 1, solve_threads = 0, loop_threads = 0;
  bool solve_profile = false;
  std::int64_t steps = 1000;
  std::int64_t output_every = 50;  // VTK frames (0: none)
  std::string output = "out/datbox_run";
  std::string write_datbox;        // write the final scene as a DATBOX here
  bool overwrite = false;
  double overlap_limit = -1.0;     // the overlap budget (m; -1: 5e-4 x the smallest free body; 0: none)
  bool strict_overlap = false;
};

const driver::OptionTable<Config> kOptions(
    "datbox_run", "runs an LMGC90 DATBOX folder (2D rigid: RBDY2 with DISKx, JONCx, xKSID, POLYG, PT2Dx)",
    {{"datbox", &Config::datbox, "the DATBOX folder (BODIES.DAT, BULK_BEHAV.DAT, TACT_BEHAV.DAT, …)", driver::Kind::Run, driver::kRequired, "DIR"},
     {"dt", &Config::dt, "time step (s)", driver::Kind::Run},
     {"theta", &Config::theta, "θ of the θ-method, in [0.5, 1]", driver::Kind::Run},
     {"tol", &Config::tol, "NLGS tolerance", driver::Kind::Run},
     {"norm", &Config::norm, "NLGS convergence norm (Quad, QM/16, Maxm, …: nscd's policy names)", driver::Kind::Run},
     {"relaxation", &Config::relaxation, "NLGS relaxation ω in (0, 2)", driver::Kind::Run},
     {"sweeps", &Config::sweeps, "at most this many NLGS sweeps per step", driver::Kind::Run},
     {"check-every", &Config::check_every, "NLGS sweeps between convergence checks", driver::Kind::Run},
     {"solver", &Config::solver, "NLGS or NEWTON_AC", driver::Kind::Run},
     {"order", &Config::order, "NLGS sweep order: fixed (LMGC90's), reversed, shuffled, alternating, colored, colored-rows, colored-cells (graph-coloured: the orders --threads needs; other numbers than LMGC90's order)", driver::Kind::Run},
     {"anderson", &Config::anderson, "Anderson mixing of the NLGS sweeps, depth 1 to 8 (0: off, as in LMGC90; docs/theory.md 9.5b)", driver::Kind::Run},
     driver::threads_option<Config>(),
     driver::solve_threads_option<Config>(),
     driver::loop_threads_option<Config>(),
     driver::solve_profile_option<Config>(),
     {"steps", &Config::steps, "time steps to run (0: none, e.g. with --write-datbox)", driver::Kind::Run},
     {"output-every", &Config::output_every, "a VTK frame every this many steps (0: none)"},
     {"output", &Config::output, "output folder", driver::Kind::Free, driver::kNone, "DIR"},
     {"write-datbox", &Config::write_datbox, "write the scene at the end as a DATBOX folder here", driver::Kind::Free, driver::kNone, "DIR"},
     {"overwrite", &Config::overwrite, "replace an earlier run in --output", driver::Kind::Free, driver::kSwitch},
     driver::overlap_limit_option<Config>(driver::OverlapYardstick::FreeBody),
     driver::strict_overlap_option<Config>(driver::StrictStop::AtStep)});

bool parse(int argc, char** argv, Config& c) {
  if (!kOptions.parse(argc, argv, c)) return false;
  kOptions.require_finite(c);
  using driver::require;
  require(c.dt > 0, "--dt must be > 0");
  require(c.theta >= 0.5 && c.theta <= 1.0, "--theta must lie in [0.5, 1]");
  require(c.tol > 0, "--tol must be > 0");
  require(c.relaxation > 0 && c.relaxation < 2, "--relaxation must lie in (0, 2)");
  require(c.sweeps >= 1 && c.check_every >= 1, "--sweeps and --check-every must be >= 1");
  require(c.steps >= 0 && c.output_every >= 0, "--steps and --output-every must be >= 0");
  driver::check_overlap_options(c.overlap_limit, c.strict_overlap, driver::OverlapYardstick::FreeBody);
  require(c.anderson >= 0 && c.anderson <= 8, "--anderson must lie in [0, 8] (0: off), got " + std::to_string(c.anderson));
  try {
    parse_convergence_policy(c.norm);
    parse_solver_kind(c.solver);
    parse_sweep_order(c.order);
  } catch (const Error& e) {
    throw driver::InputError(e.what());
  }
  driver::check_threads(c.threads, c.solve_threads, c.loop_threads, c.order);
  return true;
}

StepperOptions stepper_options(const Config& c) {
  StepperOptions o;
  o.solver = parse_solver_kind(c.solver);
  o.nlgs.policy = parse_convergence_policy(c.norm);
  o.nlgs.tol = c.tol;
  o.nlgs.relaxation = c.relaxation;
  o.nlgs.max_sweeps = c.sweeps;
  o.nlgs.check_every = std::min(c.check_every, c.sweeps);
  if (o.nlgs.check_every == 1) o.nlgs.relaxation = 1.0;
  o.nlgs.order = parse_sweep_order(c.order);
  o.nlgs.anderson = c.anderson;
  o.nlgs.threads = o.threads = c.threads;  // the solve's, and the rest of the step's
  o.solve_threads = c.solve_threads;
  o.loop_threads = c.loop_threads;
  o.nlgs.profile = c.solve_profile;
  return o;
}

int run(const Config& c) {
  Datbox d = read_datbox(c.datbox);
  scenes::claim_output_folder(c.output, {"summary.txt", "steps.csv", "vtk", "final.nscd", "stopped_state.nscd"}, c.overwrite, false);
  Registry& reg = d.reg;
  reg.params.dt = c.dt;
  reg.params.theta = c.theta;
  validate(reg.params);
  const StepperOptions so = stepper_options(c);
  MoreauJean mj(reg, so);
  scenes::StepWatch watch;
  watch.overlap_limit = scenes::overlap_budget(c.overlap_limit, scenes::smallest_free_body_size(reg));
  std::size_t matched = 0;
  if (!d.contacts.empty()) mj.set_warm_start_memory(scenes::datbox_warm_start(reg, d.contacts, &matched));
  driver::input_accepted();
  if (const std::string w = driver::threads_warning("datbox_run", c.threads); !w.empty()) std::fprintf(stderr, "%s\n", w.c_str());
  for (const std::string& n : d.notes) std::printf("datbox_run: note: %s\n", n.c_str());
  std::printf("datbox_run: %zu bodies (%zu POLYG, %zu DISKx, %zu JONCx, %zu xKSID, %zu PT2Dx), %zu laws, %zu of %zu Vloc_Rloc contacts warm-started\n",
              reg.bodies.size(), reg.polyg.size(), reg.diskx.size(), reg.joncx.size(), reg.xksid.size(), reg.points.size(),
              reg.contact_laws.laws.size(), matched, d.contacts.size());

  CsvWriter csv(std::filesystem::path(c.output) / "steps.csv", {"step", "time", "contacts", "active", "sweeps", "converged", "kinetic_energy", "max_overlap"});
  VtkWriter vtk(std::filesystem::path(c.output) / "vtk");
  if (c.output_every > 0) vtk.write_frame(reg);
  std::int64_t unconverged = 0;
  double max_overlap = 0.0;
  for (std::int64_t s = 1; s <= c.steps; ++s) {
    const StepReport r = mj.step();
    watch.observe(reg, r, so);
    if (c.strict_overlap && watch.over_limit_steps > 0) scenes::stop_over_budget(reg, mj, c.output, r, watch);
    unconverged += r.converged ? 0 : 1;
    max_overlap = std::max(max_overlap, r.max_overlap);
    csv.row({double(s), r.time, double(r.contacts), double(r.active), double(r.sweeps), r.converged ? 1.0 : 0.0, kinetic_energy(reg), r.max_overlap});
    if (c.output_every > 0 && s % c.output_every == 0) vtk.write_frame(reg);
  }
  csv.flush();
  bool checkpointed = true;
  try {
    save_checkpoint(std::filesystem::path(c.output) / "final.nscd", reg, mj.warm_start_memory());
  } catch (const Error& e) {
    checkpointed = false;
    std::printf("datbox_run: no final.nscd: %s\n", e.what());
  }
  if (!c.write_datbox.empty()) {
    DatboxExtras x;
    x.law_name = &d.law_name;
    x.drives = &d.drives;
    const std::vector<DatboxContact> now = c.steps > 0 ? datbox_contacts(reg) : d.contacts;
    x.contacts = &now;
    x.step = d.step + c.steps;
    write_datbox(c.write_datbox, reg, x);
    std::printf("datbox_run: wrote the scene as a DATBOX in %s\n", c.write_datbox.c_str());
  }
  driver::Summary sum;
  sum.add("bodies", reg.bodies.size()).add("steps", c.steps).add("simulated_time", reg.time).add("unconverged_steps", unconverged);
  sum.add("contacts", mj.report().contacts).add("kinetic_energy", kinetic_energy(reg)).add("max_overlap", max_overlap);
  sum.add("warm_started_from_vloc_rloc", matched).add("checkpoint", checkpointed ? 1 : 0);
  sum.stream() << watch.summary();
  sum.write(std::filesystem::path(c.output) / "summary.txt");
  std::fputs(watch.solve_profile_table().c_str(), stdout);
  std::printf("datbox_run: %lld steps to t = %.6g s, %zu contacts, kinetic energy %.3e J/m, %lld unconverged\n",
              static_cast<long long>(c.steps), reg.time, mj.report().contacts, kinetic_energy(reg), static_cast<long long>(unconverged));
  return driver::kExitOk;
}

int main(int argc, char** argv) { return driver::run_main("datbox_run", argc, argv, Config{}, parse, run); }
