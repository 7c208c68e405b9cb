// examples/biaxial/main.cpp — `biaxial`: a biaxial compression of polydisperse frictional disks
// between four JONCx walls, the first test a granular researcher runs on a new code (issue #12).
//
// What it shows
//   DISKx grains and JONCx walls in the same stepper, laws and solver as the ballast's polygons.
//   1. The disks (radii uniform in [r_min, r_max]) sit on a square lattice between the walls.
//   2. Isotropic compaction: the top and right walls are pushed by σ₃ × their length, grains
//      frictionless (the densest packing a pressure makes), until at rest or until the packing
//      fraction is steady (--compaction-plateau; NLGS Quad 1e-4, at most 1000 sweeps a step).
//   3. Biaxial compression: the grains get their friction μ; the top wall moves down at a
//      constant speed (the strain rate set by the inertial number I = ε̇ ⟨d⟩ √(ρ/σ₃), quasi-static
//      for I <= 1e-3), the right wall keeps σ₃. The stress ratio rises to a peak and falls to a
//      residual plateau; the mobilized friction angle sin φ = (σ₁ − σ₃)/(σ₁ + σ₃) is the
//      material's strength (docs/studies.md §6.1). σ₁ and σ₃ of an output row are the time
//      averages of the wall forces over the row's steps (the walls' impulse over the row / its
//      duration): NLGS does not converge on a large sample within the sweep cap (the sweeps a
//      step needs grow with the sample's height, docs/studies.md §6.1), one step's wall forces
//      are poorly resolved, their sum over many steps is not. The grains' internal (Love–Weber)
//      stress, averaged the same way, is a cross-check.
//
// Build
//   cmake -S . -B build && cmake --build build --target biaxial
// Run
//   build/examples/biaxial/biaxial --output out/biaxial                  (2000 disks, minutes)
//   build/examples/biaxial/biaxial --grains 300 --max-strain 0.1 --output out/biaxial_small
//   build/examples/biaxial/biaxial --shape pentagon --grains 500 --output out/biaxial_pentagons
//   build/examples/biaxial/biaxial --tol 1e-5 --max-sweeps 3000 ...     (the former setting)
//   build/examples/biaxial/biaxial --help
// Outputs under --output
//   curves.csv    per row: strain ε₁, volumetric strain ε_v (contraction > 0), σ₁, σ₃ (Pa, row
//                 averages), sin φ, φ (degrees), φ from the row's last step alone, the internal
//                 stress's principal values and φ, packing fraction, coordination number, kinetic
//                 energy, mean sweeps a step, the largest natural-map residual checked in the row
//   curves.png    stress ratio and volumetric strain against ε₁ (when Python's matplotlib is found)
//   summary.txt   peak_friction_angle, residual_friction_angle (degrees), their strains, the
//                 same from the internal stress (*_internal), the packing fraction after
//                 compaction, the inertial number, sweeps, residuals, steps, CPU times
//   vtk/          frames for ParaView (--vtk-every)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/io/csv.hpp"
#include "nscd/io/vtk_writer.hpp"
#include "nscd/shared/analysis.hpp"
#include "nscd/shared/biaxial.hpp"
#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/overlap_options.hpp"
#include "nscd/shared/driver/run_main.hpp"
#include "nscd/shared/driver/summary.hpp"
#include "nscd/shared/driver_checks.hpp"
#include "nscd/shared/step_watch.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "nscd/solvers/nlgs.hpp"

using namespace nscd;

namespace {

struct Config {
  std::int64_t grains = 2000;
  std::string shape = "disk";
  std::uint64_t seed = 2012;
  double r_min = 2e-3, r_max = 4e-3;
  double mu = 0.5;
  double wall_density = 2600.0;
  double pressure = 1e4;          // σ₃ (Pa = N/m per metre of wall)
  double inertial_number = 1e-3;  // sets the strain rate
  double max_strain = 0.15;
  double peak_from = 0.005;
  double dt = 2e-4;
  double tol = 1.666e-4;
  std::int64_t max_sweeps = 1000;
  std::string solver = "NLGS";
  std::string compaction_solver = "NLGS";
  double compaction_tol = 1e-4;
  double compaction_plateau = 2e-4;
  std::int64_t compaction_max_sweeps = 1000;
  std::string policy = "Quad";
  std::string order = "fixed";
  std::string compaction_order = "fixed";
  int threads = 1, solve_threads = 0, loop_threads = 0;
  bool solve_profile = false;
  double newton_tol = 1e-8;
  std::int64_t newton_presweeps = 0;
  std::int64_t residual_check_every = 10;
  std::int64_t rows_every = 20;
  std::int64_t vtk_every = 0;
  double progress_every = 10.0;
  std::string output = "out/biaxial";
  bool overwrite = false;
  double overlap_limit = -1.0;  // the overlap budget (m; -1: 5e-4 x the smallest grain; 0: none)
  bool strict_overlap = false;
};

const driver::OptionTable<Config> kOptions(
    "biaxial", "biaxial compression of polydisperse frictional disks between four JONCx walls",
    {{"grains", &Config::grains, "number of grains, in [10, 200000]"},
     {"shape", &Config::shape, "grains: disk (DISKx) or pentagon (regular POLYG of circumradius r, random orientation)"},
     {"seed", &Config::seed, "random seed of the radii"},
     {"r-min", &Config::r_min, "smallest grain radius (m; a pentagon's circumradius)"},
     {"r-max", &Config::r_max, "largest grain radius (m)"},
     {"mu", &Config::mu, "grain-grain friction during the compression (the walls are frictionless)"},
     {"wall-density", &Config::wall_density, "density of the walls (kg/m3): the mass of the moving walls"},
     {"pressure", &Config::pressure, "confining stress sigma3 (Pa = N/m per metre of wall)"},
     {"inertial-number", &Config::inertial_number, "I = strain rate x mean diameter x sqrt(density / sigma3); quasi-static <= 1e-3"},
     {"max-strain", &Config::max_strain, "axial strain at which the compression stops, in (0, 0.5]"},
     {"peak-from", &Config::peak_from, "the peak is sought among the rows at axial strain >= this (the first rows hold the wall's start-up transient)"},
     {"dt", &Config::dt, "time step (s)"},
     {"tol", &Config::tol, "NLGS tolerance of the compression (see --policy)"},
     {"max-sweeps", &Config::max_sweeps, "NLGS sweeps per compression step, at most"},
     {"solver", &Config::solver, "contact solver of the compression: NLGS or NEWTON_AC (SuiteSparse)"},
     {"compaction-solver", &Config::compaction_solver, "contact solver of the compaction: NLGS or NEWTON_AC (SuiteSparse)"},
     {"compaction-plateau", &Config::compaction_plateau, "end the compaction also when the packing fraction changes by less than this over 0.02 s (0: at rest only)"},
     {"compaction-tol", &Config::compaction_tol, "NLGS tolerance (Quad policy) of the compaction, when its solver is NLGS"},
     {"compaction-max-sweeps", &Config::compaction_max_sweeps, "NLGS sweeps per compaction step, at most"},
     {"policy", &Config::policy, "NLGS convergence policy: Quad, Maxm, QM/16, Strict, NonStrict, Energy"},
     {"order", &Config::order, "NLGS sweep order of the compression: fixed, reversed, shuffled, alternating (forward then backward), colored, colored-rows, colored-cells"},
     {"compaction-order", &Config::compaction_order, "NLGS sweep order of the compaction (the same choices); in fixed, the compaction's solve runs on one thread whatever --threads says"},
     driver::threads_option<Config>(),
     driver::solve_threads_option<Config>(),
     driver::loop_threads_option<Config>(),
     driver::solve_profile_option<Config>(),
     {"newton-tol", &Config::newton_tol, "NEWTON_AC: natural-map residual / |q| to reach"},
     {"newton-presweeps", &Config::newton_presweeps, "NEWTON_AC hybrid: NLGS sweeps (to Quad 1e-3) before Newton, 0: pure Newton"},
     {"residual-check-every", &Config::residual_check_every, "steps between checks of the natural-map residual / |q| (0: never)"},
     {"rows-every", &Config::rows_every, "steps between rows of curves.csv"},
     {"vtk-every", &Config::vtk_every, "steps between VTK frames (0: none)"},
     {"progress-every", &Config::progress_every, "wall seconds between progress lines"},
     {"output", &Config::output, "output folder"},
     {"overwrite", &Config::overwrite, "replace an earlier run in --output", driver::Kind::Free, driver::kSwitch},
     driver::overlap_limit_option<Config>(driver::OverlapYardstick::Grain),
     driver::strict_overlap_option<Config>(driver::StrictStop::AtStep)});

bool parse(int argc, char** argv, Config& c) {
  if (!kOptions.parse(argc, argv, c)) return false;
  kOptions.require_finite(c);
  using driver::require;
  require(c.grains >= 10 && c.grains <= 200000, "--grains must lie in [10, 200000], got " + std::to_string(c.grains));
  require(c.r_min > 0 && c.r_max >= c.r_min, "--r-min and --r-max must satisfy 0 < r-min <= r-max");
  require(c.mu >= 0, "--mu must be >= 0");
  driver::check_overlap_options(c.overlap_limit, c.strict_overlap, driver::OverlapYardstick::Grain);
  require(c.shape == "disk" || c.shape == "pentagon", "--shape must be disk or pentagon, got '" + c.shape + "'");
  require(c.pressure > 0 && c.wall_density > 0 && c.inertial_number > 0 && c.dt > 0 && c.tol > 0, "--pressure, --wall-density, --inertial-number, --dt, --tol must be > 0");
  require(c.max_strain > 0 && c.max_strain <= 0.5, "--max-strain must lie in (0, 0.5]");
  require(c.compaction_tol > 0 && c.compaction_max_sweeps >= 1 && c.newton_tol > 0 && c.newton_presweeps >= 0,
          "--compaction-tol and --newton-tol must be > 0, --compaction-max-sweeps >= 1, --newton-presweeps >= 0");
  require(c.peak_from >= 0 && c.peak_from < c.max_strain, "--peak-from must lie in [0, --max-strain)");
  require(c.compaction_plateau >= 0 && c.compaction_plateau < 1, "--compaction-plateau must lie in [0, 1)");
  require(c.residual_check_every >= 0, "--residual-check-every must be >= 0");
  parse_solver_kind(c.solver, "--solver");  // each throws naming the valid choices
  parse_solver_kind(c.compaction_solver, "--compaction-solver");
  parse_convergence_policy(c.policy);
  parse_sweep_order(c.order);
  parse_sweep_order(c.compaction_order);
  driver::check_threads(c.threads, c.solve_threads, c.loop_threads, c.order);
  require(c.max_sweeps >= 1 && c.rows_every >= 1 && c.vtk_every >= 0, "--max-sweeps, --rows-every must be >= 1, --vtk-every >= 0");
  return true;
}

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// The forces on the two moving walls follow their lengths: σ₃ × current height on the right
// wall, σ₃ × current width on the top wall while the compaction lasts.
void push_walls(scenes::BiaxialBox& b, double sigma3, bool top_too) {
  scenes::BiaxialBox* p = &b;
  impose_force(b.reg, b.right, Dof::X, TimeFunction::lambda([p, sigma3](double) { return -sigma3 * scenes::wall_state(*p).height; }));
  if (top_too)
    impose_force(b.reg, b.top, Dof::Y, TimeFunction::lambda([p, sigma3](double) { return -sigma3 * scenes::wall_state(*p).width; }));
}

// 1. The grains on a lattice between the walls, frictionless for the compaction.
scenes::BiaxialBox make_box(const Config& c, scenes::BiaxialOptions& bo) {
  bo.grains = static_cast<std::size_t>(c.grains);
  bo.seed = c.seed;
  bo.r_min = c.r_min;
  bo.r_max = c.r_max;
  bo.wall_density = c.wall_density;
  bo.pentagons = c.shape == "pentagon";
  scenes::BiaxialBox box = scenes::biaxial_box(bo);
  Registry& reg = box.reg;
  reg.params.dt = c.dt;
  reg.params.alert = 0.1 * c.r_min;
  set_contact_law(reg, box.grain_material, box.wall_material, LawSpec{LawKind::IQS_CLB, 0.0});
  set_contact_law(reg, box.grain_material, box.grain_material, LawSpec{LawKind::IQS_CLB, 0.0});
  return box;
}

// The compaction's solver (frictionless grains, until at rest) and the compression's (sc).
StepperOptions compaction_options(const Config& c, StepperOptions& sc) {
  StepperOptions so;
  so.residual_check_every = static_cast<int>(c.residual_check_every);
  so.nlgs.policy = ConvergencePolicy::Quad;
  so.nlgs.tol = c.compaction_tol;
  so.nlgs.max_sweeps = static_cast<int>(c.compaction_max_sweeps);
  so.newton.tol = c.newton_tol;
  const bool newton_compaction = parse_solver_kind(c.compaction_solver, "--compaction-solver") == SolverKind::NEWTON_AC;
  so.solver = newton_compaction ? SolverKind::NEWTON_AC : SolverKind::NLGS;
  so.threads = c.threads;  // the loops around the solve
  so.loop_threads = c.loop_threads;
  so.nlgs.order = parse_sweep_order(c.compaction_order);
  if (is_colored(so.nlgs.order)) so.nlgs.threads = c.threads, so.solve_threads = c.solve_threads;
  so.nlgs.profile = c.solve_profile;  // (both phases' solves)
  sc = so;
  sc.solver = parse_solver_kind(c.solver, "--solver");
  sc.newton.presweeps = static_cast<int>(c.newton_presweeps);
  sc.nlgs.policy = parse_convergence_policy(c.policy);
  sc.nlgs.order = parse_sweep_order(c.order);
  sc.nlgs.tol = c.tol;
  sc.nlgs.max_sweeps = static_cast<int>(c.max_sweeps);
  sc.nlgs.threads = c.threads;  // (check_threads: more than one with a colored --order only)
  sc.solve_threads = c.solve_threads;
  return so;
}

// How the compaction ended.
struct Compaction {
  bool at_rest = false, dense = false;
  std::int64_t steps = 0;
  double elapsed = 0.0;
};

// 2. Isotropic compaction, frictionless grains, until at rest or the packing fraction steady.
Compaction compact(const Config& c, scenes::BiaxialBox& box, MoreauJean& mj, double density, scenes::OverlapBudget& budget) {
  Registry& reg = box.reg;
  push_walls(box, c.pressure, true);
  const double v_scale = std::sqrt(c.pressure / density);  // the speed a pressure gives (m/s)
  // The compaction ends when the grains are at rest (rms speed below rest_speed for `window`),
  // or, with --compaction-plateau > 0, when the packing fraction has changed by less than that
  // over the last `window` (frictionless disks near jamming creep on for long; the friction of
  // the compression stops that creep within its first steps), or at max_time.
  const double rest_speed = 5e-4 * v_scale;  // 1e-4 was not reached by 2000 disks in 2 s (a plateau near 1.5e-4)
  const double window = 0.02, min_time = 0.05, max_time = 2.0;
  const auto window_steps = static_cast<std::size_t>(std::ceil(window / c.dt));
  Compaction comp;
  std::vector<double> phi_hist;  // packing fraction of the last window_steps + 1 steps
  std::size_t slow_steps = 0;
  const double t_comp0 = reg.time;
  auto last_line = std::chrono::steady_clock::now();
  while (true) {
    const StepReport r = mj.step();
    budget.observe(reg, mj, r);
    ++comp.steps;
    comp.elapsed = reg.time - t_comp0;
    const double v = scenes::rms_speed(reg, box.grains);
    phi_hist.push_back(scenes::biaxial_packing_fraction(box, scenes::wall_state(box)));
    if (phi_hist.size() > window_steps + 1) phi_hist.erase(phi_hist.begin());
    const bool counted = comp.elapsed >= min_time;
    slow_steps = counted && v < rest_speed ? slow_steps + 1 : 0;
    comp.at_rest = slow_steps >= window_steps;
    const auto [lo, hi] = std::minmax_element(phi_hist.begin(), phi_hist.end());
    comp.dense = !comp.at_rest && c.compaction_plateau > 0.0 && counted && phi_hist.size() == window_steps + 1 &&
                 *hi - *lo < c.compaction_plateau;
    if (comp.at_rest || comp.dense || comp.elapsed >= max_time) break;
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_line).count() < c.progress_every) continue;
    last_line = now;  // no ETA: the compaction ends when the grains are at rest (at most max_time)
    std::printf("  compaction: %.3f s simulated (limit %.1f s), rms speed %.2e m/s (rest below %.2e), packing fraction %.4f "
                "(%.1e over %.2f s), %.0f sweeps a step\n", comp.elapsed, max_time, v, rest_speed, phi_hist.back(), *hi - *lo,
                window, static_cast<double>(r.sweeps));
  }
  return comp;
}

// The compression's course, for the summary: the rows' strains and friction angles, and the solver's sums.
struct Compression {
  double rate = 0.0;         // strain rate (1/s)
  std::int64_t steps = 0;
  std::vector<double> row_strain, row_phi, row_phi_internal;
  std::int64_t sweeps = 0, unconverged = 0, checked = 0;
  double res_log_sum = 0.0, res_max = 0.0;
};

// 3. The start of the compression: friction on, the top wall at constant speed (the strain
// rate from the inertial number), the right wall at σ₃.
void start_compression(const Config& c, scenes::BiaxialBox& box, MoreauJean& mj, const StepperOptions& sc, double density,
                       const scenes::WallState& w0, Compression& k) {
  Registry& reg = box.reg;
  set_contact_law(reg, box.grain_material, box.grain_material, LawSpec{LawKind::IQS_CLB, c.mu});
  mj.set_options(sc);
  free_dof(reg, box.top, Dof::Y);
  double mean_d = 0.0;
  for (double r : box.radius) mean_d += 2.0 * r / static_cast<double>(box.radius.size());  // a pentagon: its circumdiameter
  k.rate = c.inertial_number / (mean_d * std::sqrt(density / c.pressure));
  const double speed = k.rate * w0.height;
  impose_velocity(reg, box.top, Dof::Y, TimeFunction::constant(-speed));
  const double t_end = c.max_strain / k.rate;
  k.steps = static_cast<std::int64_t>(std::ceil(t_end / c.dt));
  std::printf("  compression: strain rate %.4g 1/s (I = %.1e), top wall %.4g m/s, %lld steps to strain %.3g\n", k.rate,
              c.inertial_number, speed, static_cast<long long>(k.steps), c.max_strain);
}

// One row of curves.csv at step n, from the averages over the row's steps (then cleared).
void write_row(scenes::BiaxialBox& box, CsvWriter& csv, std::int64_t n, const scenes::WallState& w, const scenes::WallState& w0,
               scenes::StressAverage& avg, std::int64_t row_sweeps, double row_residual, Compression& k) {
  const Registry& reg = box.reg;
  const double h0 = w0.height, a0 = w0.width * w0.height;
  const double strain = (h0 - w.height) / h0, ev = (a0 - w.width * w.height) / a0;
  const double s1 = avg.sigma1(), s3 = avg.sigma3();
  const scenes::Stress2 in = avg.internal();
  const double phi = scenes::mobilized_friction_deg(s1, s3);
  const double phi_in = scenes::mobilized_friction_deg(in.major(), in.minor());
  k.row_strain.push_back(strain), k.row_phi.push_back(phi), k.row_phi_internal.push_back(phi_in);
  csv.row({double(n), reg.time, strain, ev, s1, s3, std::sin(phi * kPi / 180.0), phi,
           scenes::mobilized_friction_deg(w.sigma1, w.sigma3), in.major(), in.minor(), phi_in,
           scenes::biaxial_packing_fraction(box, w), scenes::contact_network(reg, box.grains).coordination_number,
           kinetic_energy(reg), double(row_sweeps) / double(avg.steps()), row_residual});
  avg.clear();
}

// 3. The compression's steps: curves.csv, VTK frames, a progress line with an ETA.
void compress(const Config& c, scenes::BiaxialBox& box, MoreauJean& mj, VtkWriter& vtk, const std::string& out,
              const scenes::WallState& w0, Compression& k, scenes::OverlapBudget& budget) {
  Registry& reg = box.reg;
  // σ₁, σ₃ and φ of a row are time averages over its steps (the walls' impulse over the row /
  // its duration: scenes::StressAverage); phi_last_step_deg is the last step's alone, for comparison
  CsvWriter csv(out + "/curves.csv", {"step", "time", "strain", "volumetric_strain", "sigma1", "sigma3", "sin_phi", "phi_deg",
                                      "phi_last_step_deg", "sigma1_internal", "sigma3_internal", "phi_internal_deg",
                                      "packing_fraction", "coordination_number", "kinetic_energy", "sweeps", "residual"});
  scenes::StressAverage avg;
  std::int64_t row_sweeps = 0;
  double row_residual = -1.0;
  const auto compression0 = std::chrono::steady_clock::now();  // the ETA: this phase's cost per step so far
  auto last_progress = compression0;
  for (std::int64_t n = 1; n <= k.steps; ++n) {
    const StepReport r = mj.step();
    budget.observe(reg, mj, r);
    k.sweeps += r.sweeps, row_sweeps += r.sweeps;
    k.unconverged += r.converged ? 0 : 1;
    if (r.residual_checked) {
      ++k.checked, k.res_log_sum += std::log10(std::max(r.residual, 1e-300)), k.res_max = std::max(k.res_max, r.residual);
      row_residual = std::max(row_residual, r.residual);
    }
    const scenes::WallState w = scenes::wall_state(box);
    avg.add(c.dt, w.sigma1, w.sigma3, scenes::internal_stress(box, w));
    if (n % c.rows_every == 0 || n == k.steps) {
      write_row(box, csv, n, w, w0, avg, row_sweeps, row_residual, k);
      row_sweeps = 0, row_residual = -1.0;
    }
    if (c.vtk_every > 0 && n % c.vtk_every == 0) vtk.write_frame(reg);
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_progress).count() >= c.progress_every) {
      last_progress = now;
      const double done = static_cast<double>(n) / static_cast<double>(k.steps);
      const double el = std::chrono::duration<double>(now - compression0).count();
      std::printf("  step %lld/%lld (%.0f %%), strain %.4f, phi %.2f deg, %.0f sweeps a step, ETA %.0f s\n", static_cast<long long>(n),
                  static_cast<long long>(k.steps), 100.0 * done, k.row_strain.empty() ? 0.0 : k.row_strain.back(),
                  k.row_phi.empty() ? 0.0 : k.row_phi.back(), static_cast<double>(k.sweeps) / static_cast<double>(n), el / done * (1.0 - done));
    }
  }
  csv.flush();
}

// The run's times, for the summary.
struct Times {
  std::chrono::steady_clock::time_point wall0;
  double cpu0 = 0.0, cpu_compaction = 0.0;
};

// 4. The peak (the largest of a running mean over 5 rows) and residual (mean over the last
// quarter) friction angles, printed and written to summary.txt.
void write_summary(const Config& c, const scenes::BiaxialBox& box, const Compaction& comp, double phi0, const Compression& k,
                   const Times& t, const scenes::StepWatch& watch, const std::string& out) {
  const double res_from = 0.75 * c.max_strain;
  const double peak_from = std::min(c.peak_from, k.row_strain.back());
  const scenes::FrictionAngles fa = scenes::friction_angles(k.row_strain, k.row_phi, res_from, peak_from);
  const scenes::FrictionAngles fi = scenes::friction_angles(k.row_strain, k.row_phi_internal, res_from, peak_from);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t.wall0).count();
  std::printf("  peak friction angle %.2f deg at strain %.3f; residual %.2f +- %.2f deg (strain >= %.3f)\n", fa.peak, fa.peak_strain,
              fa.residual, fa.spread, res_from);
  std::printf("  from the internal stress: peak %.2f deg at strain %.3f; residual %.2f +- %.2f deg\n", fi.peak, fi.peak_strain,
              fi.residual, fi.spread);
  const std::int64_t steps = k.steps, sweeps = k.sweeps, checked = k.checked;
  driver::Summary s;
  s.add("grains", box.grains.size()).add("shape", c.shape).add("mu", c.mu).add("sigma3", c.pressure).add("inertial_number", c.inertial_number);
  s.add("strain_rate", k.rate).add("packing_fraction_compacted", phi0).add("compaction_at_rest", comp.at_rest ? 1 : 0);
  s.add("compaction_steady", comp.at_rest || comp.dense ? 1 : 0).add("compaction_time", comp.elapsed);
  s.add("peak_friction_angle", fa.peak).add("peak_strain", fa.peak_strain).add("peak_from", peak_from).add("residual_friction_angle", fa.residual);
  s.add("residual_spread", fa.spread).add("peak_friction_angle_internal", fi.peak).add("residual_friction_angle_internal", fi.residual);
  s.add("residual_spread_internal", fi.spread).add("rows_every", c.rows_every).add("max_strain", c.max_strain).add("steps", steps + comp.steps);
  s.add("mean_sweeps", static_cast<double>(sweeps) / static_cast<double>(std::max<std::int64_t>(1, steps)));
  s.add("residual_checked_steps", checked).add("residual_geomean", checked > 0 ? std::pow(10.0, k.res_log_sum / checked) : -1.0);
  s.add("residual_max", k.res_max);
  s.add("unconverged_steps", k.unconverged).add("wall_time", wall).add("cpu_time", cpu_seconds() - t.cpu0);
  s.add("cpu_time_compaction", t.cpu_compaction).add("compaction_steps", comp.steps);
  s.stream() << watch.summary();
  s.write(out + "/summary.txt");
}

// 5. The plot, when Python's matplotlib is there (contrib/plots/plot_biaxial.py).
void plot(const std::string& out) {
  const std::string script = std::string(NSCD_SOURCE_DIR) + "/contrib/plots/plot_biaxial.py";
  if (std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") == 0) {
    const std::string cmd = "/usr/bin/python3 '" + script + "' '" + out + "/curves.csv' '" + out + "/curves.png' >/dev/null 2>&1";
    if (std::system(cmd.c_str()) != 0) std::printf("  (curves.png not made: %s failed)\n", script.c_str());
  }
}

int run(const Config& c) {
  const std::string out = c.output;
  scenes::claim_output_folder(out, {"curves.csv", "curves.png", "summary.txt", "vtk", "stopped_state.nscd"}, c.overwrite, false);
  Times t;
  t.wall0 = std::chrono::steady_clock::now();
  t.cpu0 = cpu_seconds();
  scenes::BiaxialOptions bo;
  scenes::BiaxialBox box = make_box(c, bo);
  StepperOptions sc;
  const StepperOptions so = compaction_options(c, sc);
  MoreauJean mj(box.reg, so);
  VtkWriter vtk(out + "/vtk");
  driver::input_accepted();
  if (const std::string w = driver::threads_warning("biaxial", c.threads); !w.empty()) std::fprintf(stderr, "%s\n", w.c_str());
  std::printf("biaxial: %zu %ss, radii %.3g-%.3g m, mu %.3g, sigma3 %.4g Pa; compaction by %s, compression by %s\n",
              box.grains.size(), c.shape.c_str(), c.r_min, c.r_max, c.mu, c.pressure,
              so.solver == SolverKind::NEWTON_AC ? "NEWTON_AC" : "NLGS Quad", sc.solver == SolverKind::NEWTON_AC ? "NEWTON_AC" : "NLGS");
  scenes::OverlapBudget budget{{}, c.strict_overlap, out};
  budget.watch.overlap_limit = scenes::overlap_budget(c.overlap_limit, scenes::smallest_grain_size(box.reg, box.grains));
  const Compaction comp = compact(c, box, mj, bo.density, budget);
  t.cpu_compaction = cpu_seconds() - t.cpu0;
  const scenes::WallState w0 = scenes::wall_state(box);
  const double phi0 = scenes::biaxial_packing_fraction(box, w0);
  std::printf("  compaction: %s after %.3f s simulated, packing fraction %.4f, sigma1 %.4g sigma3 %.4g Pa\n",
              comp.at_rest ? "at rest" : comp.dense ? "packing fraction steady" : "NOT at rest (time limit)", comp.elapsed, phi0, w0.sigma1, w0.sigma3);
  Compression k;
  start_compression(c, box, mj, sc, bo.density, w0, k);
  compress(c, box, mj, vtk, out, w0, k, budget);
  write_summary(c, box, comp, phi0, k, t, budget.watch, out);
  plot(out);
  std::fputs(budget.watch.solve_profile_table().c_str(), stdout);
  std::printf("  outputs in %s (curves.csv, summary.txt%s)\n", out.c_str(), c.vtk_every > 0 ? ", vtk/" : "");
  return driver::kExitOk;
}

}  // namespace

int main(int argc, char** argv) { return driver::run_main("biaxial", argc, argv, Config{}, parse, run); }
