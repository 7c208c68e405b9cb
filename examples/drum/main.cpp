// examples/drum/main.cpp — `drum`: a rotating drum two-fifths full of polydisperse frictional
// disks; the dynamic angle of repose of the free surface against the rotation speed (issue #12).
//
// What it shows
//   DISKx grains inside an xKSID ring (DKKDx contacts) whose rotation is imposed: the wall's
//   velocity enters the contacts' relative velocity and its friction drags the bed up, the
//   surface flows back down. In the rolling regime the surface stays flat at a steady angle
//   that grows with the Froude number Fr = ω² R / g (docs/studies.md §6.2).
//   1. The disks (radii uniform in [r_min, r_max]) on a lattice in the lower part of the drum,
//      whose radius R makes the settled bed fill --fill of it; they settle, the drum at rest.
//      The wall is rough by default: DISKx bumps of the mean grain radius fixed on the ring (a
//      smooth ring lets the outer grains roll along it like bearings, and the bed swings).
//   2. For each Froude number, in the order given, the drum turns at ω = sqrt(Fr g / R)
//      (counter-clockwise) from the state the previous speed left: --transient radians of drum
//      rotation to reach the steady flow, then --window radians during which the angle is
//      sampled --samples times and averaged.
//   3. The angle: the line from the drum's centre O to the bed's centre of mass G is
//      perpendicular to a flat free surface, so the surface's inclination is the angle between
//      OG and the vertical (shared/drum.hpp); a straight-line fit of the top grains cross-checks it.
//
// Build
//   cmake -S . -B build && cmake --build build --target drum
// Run
//   build/examples/drum/drum --output out/drum                   (400 disks, 3 speeds, minutes)
//   build/examples/drum/drum --grains 100 --froude 0.01 --output out/drum_small
//   build/examples/drum/drum --help
// Outputs under --output
//   angles.csv    per speed: Froude number, ω (rad/s), mean angle and its std over the window
//                 (degrees), the top-grain fit's mean, the fill fraction the angle measure sees,
//                 the bed's spin / ω and the wall's sliding speed / ωR (window means),
//                 steps, unconverged steps, mean sweeps, CPU time (s)
//   series.csv    every sample: time, Froude number, drum rotation (rad), both angles, the bed's
//                 spin / ω, the wall's mean sliding speed (m/s), measured or not
//   angles.png    angle against Froude number and the angle's history (when matplotlib is found)
//   summary.txt   froude_K and angle_K (degrees) for each speed K = 1, 2, ..., the settling, times
//   vtk/          frames for ParaView (--vtk-every)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <sstream>
#include <string>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/io/csv.hpp"
#include "nscd/io/text_reader.hpp"
#include "nscd/io/vtk_writer.hpp"
#include "nscd/shared/analysis.hpp"
#include "nscd/shared/drum.hpp"
#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/overlap_options.hpp"
#include "nscd/shared/driver/run_main.hpp"
#include "nscd/shared/driver/settle.hpp"
#include "nscd/shared/driver/summary.hpp"
#include "nscd/shared/driver_checks.hpp"
#include "nscd/shared/step_watch.hpp"
#include "nscd/solvers/moreau_jean.hpp"

using namespace nscd;

namespace {

struct Config {
  std::int64_t grains = 400;
  std::uint64_t seed = 2012;
  double r_min = 2e-3, r_max = 4e-3;
  double fill = 0.4;
  double mu = 0.5;
  double mu_wall = 0.5;
  std::string wall = "rough";
  std::string shape = "disk";
  std::string froude = "0.002,0.008,0.032";
  double transient = 1.0;  // rad of drum rotation before the window
  double window = 1.5;     // rad of drum rotation averaged
  std::int64_t samples = 60;
  double dt = 5e-4;
  double tol = 1e-4;
  std::int64_t max_sweeps = 3000;
  std::string order = "fixed";
  int threads = 1, solve_threads = 0, loop_threads = 0;
  bool solve_profile = false;
  std::int64_t vtk_every = 0;
  double progress_every = 10.0;
  std::string output = "out/drum";
  bool overwrite = false;
  double overlap_limit = -1.0;  // the overlap budget (m; -1: 5e-4 x the smallest grain; 0: none)
  bool strict_overlap = false;
};

const driver::OptionTable<Config> kOptions(
    "drum", "a rotating drum of polydisperse disks: the dynamic angle of repose against the Froude number",
    {{"grains", &Config::grains, "number of disks, in [10, 100000]"},
     {"seed", &Config::seed, "random seed of the radii"},
     {"r-min", &Config::r_min, "smallest disk radius (m)"},
     {"r-max", &Config::r_max, "largest disk radius (m)"},
     {"fill", &Config::fill, "share of the drum's area the settled bed fills, in (0, 0.5]; sets the drum radius"},
     {"mu", &Config::mu, "grain-grain friction coefficient"},
     {"mu-wall", &Config::mu_wall, "grain-drum friction coefficient"},
     {"wall", &Config::wall, "rough (DISKx bumps of the mean grain radius on the ring) or smooth (the bare xKSID)"},
     {"shape", &Config::shape, "disk (DISKx of radius r) or pentagon (regular POLYG pentagons of circumradius r, PLKDx on the ring)"},
     {"froude", &Config::froude, "Froude numbers Fr = omega^2 R / g, comma-separated, each in (0, 1); run in this order"},
     {"transient", &Config::transient, "drum rotation (rad) at each speed before the angle is measured"},
     {"window", &Config::window, "drum rotation (rad) over which the angle is averaged"},
     {"samples", &Config::samples, "angle samples in each window, >= 2"},
     {"dt", &Config::dt, "time step (s)"},
     {"tol", &Config::tol, "NLGS tolerance (Quad policy)"},
     {"max-sweeps", &Config::max_sweeps, "NLGS sweeps per step, at most"},
     {"order", &Config::order, "NLGS sweep order: fixed, reversed, shuffled, alternating, colored, colored-rows, colored-cells (the orders --threads needs; another order, other numbers)"},
     driver::threads_option<Config>(),
     driver::solve_threads_option<Config>(),
     driver::loop_threads_option<Config>(),
     driver::solve_profile_option<Config>(),
     {"vtk-every", &Config::vtk_every, "steps between VTK frames (0: none)"},
     {"progress-every", &Config::progress_every, "wall seconds between progress lines"},
     {"output", &Config::output, "output folder"},
     {"overwrite", &Config::overwrite, "replace an earlier run in --output", driver::Kind::Free, driver::kSwitch},
     driver::overlap_limit_option<Config>(driver::OverlapYardstick::Grain),
     driver::strict_overlap_option<Config>(driver::StrictStop::AtStep)});

std::vector<double> froude_list(const std::string& text) {
  std::vector<double> fr;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      fr.push_back(parse_real(item, "--froude", 0.0, 1.0));
    } catch (const std::exception&) {
      throw driver::InputError("--froude takes numbers in (0, 1) separated by commas, got '" + text + "'");
    }
    if (!(fr.back() > 0.0 && fr.back() < 1.0)) throw driver::InputError("--froude values must lie in (0, 1), got " + item);
  }
  if (fr.empty() || (!text.empty() && text.back() == ','))
    throw driver::InputError("--froude takes numbers in (0, 1) separated by commas, got '" + text + "'");
  return fr;
}

bool parse(int argc, char** argv, Config& c) {
  if (!kOptions.parse(argc, argv, c)) return false;
  kOptions.require_finite(c);
  using driver::require;
  require(c.grains >= 10 && c.grains <= 100000, "--grains must lie in [10, 100000], got " + std::to_string(c.grains));
  require(c.r_min > 0 && c.r_max >= c.r_min, "--r-min and --r-max must satisfy 0 < r-min <= r-max");
  require(c.fill > 0 && c.fill <= 0.5, "--fill must lie in (0, 0.5]");
  require(c.mu >= 0 && c.mu_wall >= 0, "--mu and --mu-wall must be >= 0");
  require(c.wall == "rough" || c.wall == "smooth", "--wall must be rough or smooth, got '" + c.wall + "'");
  require(c.shape == "disk" || c.shape == "pentagon", "--shape must be disk or pentagon, got '" + c.shape + "'");
  froude_list(c.froude);
  require(c.transient >= 0 && c.window > 0, "--transient must be >= 0 and --window > 0 (radians)");
  require(c.samples >= 2, "--samples must be >= 2");
  require(c.dt > 0 && c.tol > 0, "--dt and --tol must be > 0");
  driver::check_overlap_options(c.overlap_limit, c.strict_overlap, driver::OverlapYardstick::Grain);
  require(c.max_sweeps >= 1 && c.vtk_every >= 0, "--max-sweeps must be >= 1, --vtk-every >= 0");
  parse_sweep_order(c.order);  // (throws naming the valid choices)
  driver::check_threads(c.threads, c.solve_threads, c.loop_threads, c.order);
  return true;
}

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

struct SpeedResult {
  double froude = 0.0, omega = 0.0, mean = 0.0, std = 0.0, fit = 0.0, fill = 0.0, sweeps = 0.0, cpu = 0.0;
  double spin = 0.0, slip = 0.0;  // the bed's spin / ω and the wall slip / ωR, window means
  std::int64_t steps = 0, unconverged = 0;
};

// 1. The grains on a lattice inside the drum, the drum at rest.
scenes::DrumScene make_drum(const Config& c) {
  scenes::DrumOptions o;
  o.grains = static_cast<std::size_t>(c.grains);
  o.seed = c.seed;
  o.r_min = c.r_min;
  o.r_max = c.r_max;
  o.fill = c.fill;
  o.bump_radius = c.wall == "rough" ? 0.5 * (c.r_min + c.r_max) : 0.0;
  o.pentagons = c.shape == "pentagon";
  scenes::DrumScene d = scenes::drum_scene(o);
  Registry& reg = d.reg;
  reg.params.dt = c.dt;
  reg.params.alert = 0.25 * c.r_min;
  set_contact_law(reg, d.grain_material, d.grain_material, LawSpec{LawKind::IQS_CLB, c.mu});
  set_contact_law(reg, d.grain_material, d.wall_material, LawSpec{LawKind::IQS_CLB, c.mu_wall});
  return d;
}

StepperOptions stepper_options(const Config& c) {
  StepperOptions so;
  so.nlgs.policy = ConvergencePolicy::Quad;
  so.nlgs.tol = c.tol;
  so.nlgs.max_sweeps = static_cast<int>(c.max_sweeps);
  so.nlgs.order = parse_sweep_order(c.order);
  so.nlgs.threads = so.threads = c.threads;  // the solve's, and the rest of the step's
  so.solve_threads = c.solve_threads;
  so.loop_threads = c.loop_threads;
  so.nlgs.profile = c.solve_profile;
  return so;
}

// One step, watched by the overlap budget.
StepReport advance(scenes::DrumScene& d, MoreauJean& mj, scenes::OverlapBudget& budget) {
  const StepReport r = mj.step();
  budget.observe(d.reg, mj, r);
  return r;
}

// The grains settle in the drum at rest, until at rest or 3 s.
driver::SettleResult settle_bed(const Config& c, scenes::DrumScene& d, MoreauJean& mj, scenes::OverlapBudget& budget,
                                double g) {
  driver::SettleRule rule;
  rule.speed = 1e-3 * std::sqrt(g * c.r_max);  // well below the speed of a grain falling its radius
  rule.window = 0.05;
  rule.min_time = 0.1;
  rule.max_time = 3.0;
  return driver::settle(d.reg, d.grains, rule, [&] { return advance(d, mj, budget); });
}

// The steps of each speed: the transient (the drum turning c.transient rad), then the window
// (c.window rad, at least c.samples steps).
struct Plan {
  std::vector<std::int64_t> transient_steps, window_steps;
  std::int64_t total_steps = 0;
};

Plan plan_speeds(const Config& c, const std::vector<double>& froude, double g, double R) {
  Plan p;
  for (double fr : froude) {
    const double w = std::sqrt(fr * g / R);
    p.transient_steps.push_back(static_cast<std::int64_t>(std::ceil(c.transient / (w * c.dt))));
    p.window_steps.push_back(std::max<std::int64_t>(c.samples, static_cast<std::int64_t>(std::ceil(c.window / (w * c.dt)))));
    p.total_steps += p.transient_steps.back() + p.window_steps.back();
  }
  return p;
}

// The sums over a speed's window samples.
struct WindowSums {
  double sum = 0.0, sq = 0.0, fit_sum = 0.0, fill_sum = 0.0, spin_sum = 0.0, slip_sum = 0.0;
  int n = 0, n_fit = 0;
};

// A row of series.csv (measured: a window sample, added to the sums); returns the bed angle.
double sample_bed(scenes::DrumScene& d, CsvWriter& series, const SpeedResult& s, double rot0, bool measured, WindowSums& w) {
  const Registry& reg = d.reg;
  const scenes::BedAngle a = scenes::bed_angle(d);
  const double fit = scenes::surface_fit_angle(d);
  const scenes::BedMotion bm = scenes::bed_motion(d);
  series.row({reg.time, s.froude, reg.bodies.angle[d.drum.index()] - rot0, a.angle_deg, fit, bm.spin / s.omega, bm.wall_slip,
              measured ? 1.0 : 0.0});
  if (measured) {
    w.sum += a.angle_deg, w.sq += a.angle_deg * a.angle_deg, ++w.n;
    w.fill_sum += scenes::segment_fill(d.inner_radius, a.distance);
    w.spin_sum += bm.spin / s.omega, w.slip_sum += bm.wall_slip / (s.omega * d.radius);
    if (std::isfinite(fit)) w.fit_sum += fit, ++w.n_fit;
  }
  return a.angle_deg;
}

// The progress of the speeds, over all of them: steps done and the ETA's origin.
struct Progress {
  std::int64_t done_steps = 0, total_steps = 0;
  std::chrono::steady_clock::time_point turning0, last;
};

// 2. One speed (the k-th of `speeds`): its transient, then its window, sampled.
SpeedResult turn_at(const Config& c, scenes::DrumScene& d, MoreauJean& mj, scenes::OverlapBudget& budget, VtkWriter& vtk,
                    CsvWriter& series, double froude, std::size_t k, std::size_t speeds, std::int64_t n_t, std::int64_t n_w,
                    double angle0, Progress& pr) {
  Registry& reg = d.reg;
  const double g = norm(reg.params.gravity), R = d.radius;
  SpeedResult s;
  s.froude = froude;
  s.omega = std::sqrt(s.froude * g / R);
  impose_velocity(reg, d.drum, Dof::Rot, TimeFunction::constant(s.omega));
  const std::int64_t every = n_w / c.samples;
  const double cpu_k = cpu_seconds(), rot0 = reg.bodies.angle[d.drum.index()];
  WindowSums w;
  double sweeps = 0.0;
  double last_angle = angle0;
  for (std::int64_t step = 1; step <= n_t + n_w; ++step) {
    const StepReport rep = advance(d, mj, budget);
    sweeps += rep.sweeps;
    s.unconverged += rep.converged ? 0 : 1;
    ++pr.done_steps;
    const bool measured = step > n_t && (step - n_t) % every == 0;
    if (measured || step % std::max<std::int64_t>(1, every) == 0) last_angle = sample_bed(d, series, s, rot0, measured, w);
    if (c.vtk_every > 0 && pr.done_steps % c.vtk_every == 0) vtk.write_frame(reg);
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - pr.last).count() >= c.progress_every) {
      pr.last = now;
      const double el = std::chrono::duration<double>(now - pr.turning0).count();
      const double left = el / static_cast<double>(pr.done_steps) * static_cast<double>(pr.total_steps - pr.done_steps);
      std::printf("  Fr %.3g (%zu/%zu): drum turned %.2f of %.2f rad, angle %.2f deg, ETA %.0f s\n", s.froude, k + 1,
                  speeds, reg.bodies.angle[d.drum.index()] - rot0, c.transient + c.window, last_angle, left);
    }
  }
  s.steps = n_t + n_w;
  s.mean = w.sum / w.n;
  s.std = std::sqrt(std::max(0.0, w.sq / w.n - s.mean * s.mean));
  s.fit = w.n_fit > 0 ? w.fit_sum / w.n_fit : std::nan("");
  s.fill = w.fill_sum / w.n;
  s.spin = w.spin_sum / w.n;
  s.slip = w.slip_sum / w.n;
  s.sweeps = sweeps / static_cast<double>(s.steps);
  s.cpu = cpu_seconds() - cpu_k;
  std::printf("  Fr %.3g (omega %.4g rad/s): angle %.2f +- %.2f deg (top-grain fit %.2f), bed spin %.2f omega, wall slip %.3f "
              "omega R, %lld steps (%lld unconverged), %.0f sweeps a step, %.1f s CPU\n", s.froude, s.omega, s.mean, s.std, s.fit,
              s.spin, s.slip, static_cast<long long>(s.steps), static_cast<long long>(s.unconverged), s.sweeps, s.cpu);
  return s;
}

// 3. The checks: a grain outside the drum, an angle that is not a number ("" if none).
std::string impossible_result(const scenes::DrumScene& d, const Config& c, const std::vector<SpeedResult>& results) {
  std::string bad = scenes::grains_outside(d, c.r_min);
  for (const SpeedResult& s : results)
    if (bad.empty() && !std::isfinite(s.mean)) bad = "the angle at Fr " + std::to_string(s.froude) + " is not finite";
  return bad;
}

// 3. The table (angles.csv) and the summary.
void write_results(const Config& c, const scenes::DrumScene& d, const driver::SettleResult& settled, double angle0,
                   const scenes::StepWatch& watch,
                   const std::vector<SpeedResult>& results, std::int64_t total_steps, std::chrono::steady_clock::time_point wall0,
                   double cpu0) {
  const std::string& out = c.output;
  CsvWriter table(out + "/angles.csv", {"froude", "omega", "angle_deg", "angle_std_deg", "fit_angle_deg", "fill_seen", "bed_spin_ratio",
                                         "wall_slip_ratio", "steps", "unconverged_steps", "mean_sweeps", "cpu_time"});
  for (const SpeedResult& s : results)
    table.row({s.froude, s.omega, s.mean, s.std, s.fit, s.fill, s.spin, s.slip, double(s.steps), double(s.unconverged), s.sweeps, s.cpu});
  table.flush();
  driver::Summary sum;
  sum.add("grains", d.grains.size()).add("shape", c.shape).add("drum_radius", d.radius).add("wall_bumps", d.bumps).add("mu", c.mu).add("mu_wall", c.mu_wall).add("dt", c.dt);
  sum.add("settled_at_rest", settled.at_rest ? 1 : 0).add("settled_angle", angle0).add("speeds", results.size());
  for (std::size_t k = 0; k < results.size(); ++k) {
    const std::string K = std::to_string(k + 1);
    sum.add("froude_" + K, results[k].froude).add("omega_" + K, results[k].omega).add("angle_" + K, results[k].mean);
    sum.add("angle_std_" + K, results[k].std).add("fit_angle_" + K, results[k].fit).add("wall_slip_" + K, results[k].slip);
  }
  sum.add("steps", settled.steps + total_steps).add("wall_time", std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count());
  sum.add("cpu_time", cpu_seconds() - cpu0);
  sum.stream() << watch.summary();
  sum.write(out + "/summary.txt");
}

// 4. The plot, when Python's matplotlib is there (contrib/plots/plot_drum.py).
void plot(const std::string& out) {
  const std::string script = std::string(NSCD_SOURCE_DIR) + "/contrib/plots/plot_drum.py";
  if (std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") == 0) {
    const std::string cmd = "/usr/bin/python3 '" + script + "' '" + out + "' '" + out + "/angles.png' >/dev/null 2>&1";
    if (std::system(cmd.c_str()) != 0) std::printf("  (angles.png not made: %s failed)\n", script.c_str());
  }
}

int run(const Config& c) {
  const std::string out = c.output;
  scenes::claim_output_folder(out, {"angles.csv", "series.csv", "angles.png", "summary.txt", "vtk", "stopped_state.nscd"}, c.overwrite, false);
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = cpu_seconds();
  const std::vector<double> froude = froude_list(c.froude);
  scenes::DrumScene d = make_drum(c);
  Registry& reg = d.reg;
  MoreauJean mj(reg, stepper_options(c));
  scenes::OverlapBudget budget{{}, c.strict_overlap, out};
  budget.watch.overlap_limit = scenes::overlap_budget(c.overlap_limit, scenes::smallest_grain_size(reg, d.grains));
  VtkWriter vtk(out + "/vtk");
  const double g = norm(reg.params.gravity), R = d.radius;
  driver::input_accepted();
  if (const std::string w = driver::threads_warning("drum", c.threads); !w.empty()) std::fprintf(stderr, "%s\n", w.c_str());
  std::printf("drum: %zu %ss, radii %.3g-%.3g m, drum radius %.4g m (%s wall%s), mu %.3g (wall %.3g), dt %.3g s\n",
              d.grains.size(), c.shape.c_str(), c.r_min, c.r_max, R, c.wall.c_str(), d.bumps > 0 ? (", " + std::to_string(d.bumps) + " bumps").c_str() : "",
              c.mu, c.mu_wall, c.dt);
  const driver::SettleResult settled = settle_bed(c, d, mj, budget, g);
  const scenes::BedAngle a0 = scenes::bed_angle(d);
  std::printf("  settling: %s after %.3f s simulated, angle %.2f deg, fill fraction seen %.3f\n",
              settled.at_rest ? "at rest" : "NOT at rest (time limit)", settled.elapsed, a0.angle_deg,
              scenes::segment_fill(d.inner_radius, a0.distance));

  // 2. each speed: the transient, then the window, sampled
  CsvWriter series(out + "/series.csv",
                   {"time", "froude", "drum_rotation", "angle_deg", "fit_angle_deg", "bed_spin_ratio", "wall_slip", "measured"});
  const Plan plan = plan_speeds(c, froude, g, R);
  std::printf("  %zu speeds, %lld steps in all\n", froude.size(), static_cast<long long>(plan.total_steps));
  Progress pr;
  pr.total_steps = plan.total_steps;
  pr.turning0 = pr.last = std::chrono::steady_clock::now();
  std::vector<SpeedResult> results;
  for (std::size_t k = 0; k < froude.size(); ++k)
    results.push_back(turn_at(c, d, mj, budget, vtk, series, froude[k], k, froude.size(), plan.transient_steps[k], plan.window_steps[k],
                              a0.angle_deg, pr));
  series.flush();

  // 3. the checks, the table, the summary
  if (const std::string bad = impossible_result(d, c, results); !bad.empty()) {
    std::printf("drum: impossible result: %s\n", bad.c_str());
    return driver::kExitImpossible;
  }
  write_results(c, d, settled, a0.angle_deg, budget.watch, results, plan.total_steps, wall0, cpu0);
  plot(out);
  std::fputs(budget.watch.solve_profile_table().c_str(), stdout);
  std::printf("  outputs in %s (angles.csv, series.csv, summary.txt%s)\n", out.c_str(), c.vtk_every > 0 ? ", vtk/" : "");
  return driver::kExitOk;
}

}  // namespace

int main(int argc, char** argv) { return driver::run_main("drum", argc, argv, Config{}, parse, run); }
