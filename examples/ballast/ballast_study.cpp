// examples/ballast/ballast_study.cpp — the run, step by step:
//   1. the sample: load it (--sample, --resume) or prepare it: grains deposited on the
//      sublayer until rest, the sleeper placed and settled; saved as sample.nscd
//   2. the load: F(t) on the sleeper from t0 (the start of the cycles), with a ramp-in
//   3. the cycles: steps.csv (thinned), cycles.csv, VTK frames, a progress line with ETA,
//      checkpoints every K cycles (checkpoint.nscd, atomic)
//   4. summary.txt and the final checkpoint
#include "ballast_study.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/atomic_file.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/io/csv.hpp"
#include "nscd/io/vtk_writer.hpp"
#include "nscd/shared/analysis.hpp"
#include "nscd/io/text_reader.hpp"
#include "nscd/shared/ballast.hpp"
#include "nscd/shared/driver/run_main.hpp"
#include "nscd/shared/driver/settle.hpp"
#include "nscd/shared/driver/summary.hpp"
#include "nscd/shared/driver_checks.hpp"
#include "nscd/shared/overlap_growth.hpp"
#include "nscd/shared/postpro.hpp"
#include "nscd/shared/progress.hpp"
#include "nscd/shared/step_watch.hpp"
#include "nscd/solvers/moreau_jean.hpp"

namespace fs = std::filesystem;
using namespace nscd;
using nscd::scenes::format_duration;
using nscd::scenes::mean_speed;
using nscd::scenes::rms_speed;
using Clock = std::chrono::steady_clock;

namespace ballast {
namespace {

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// SIGTERM during the cycles (a batch scheduler's notice before it kills the job, GNU parallel
// stopping its jobs): the run ends at the end of the current cycle with a checkpoint. The
// handler is installed for the cycles only (the preparation has no checkpoint: it dies as
// before) and the previous one put back after them.
volatile std::sig_atomic_t g_terminate = 0;
void on_sigterm(int) { g_terminate = 1; }
class SigtermCheckpoint {
 public:
  SigtermCheckpoint() {
    g_terminate = 0;
    struct sigaction sa {};
    sa.sa_handler = on_sigterm;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGTERM, &sa, &old_);
  }
  ~SigtermCheckpoint() { sigaction(SIGTERM, &old_, nullptr); }
  SigtermCheckpoint(const SigtermCheckpoint&) = delete;
  SigtermCheckpoint& operator=(const SigtermCheckpoint&) = delete;
  bool requested() const { return g_terminate != 0; }

 private:
  struct sigaction old_ {};
};

bool has_line(const fs::path& file, const std::string& line) {
  std::ifstream in(file);
  for (std::string l; std::getline(in, l);)
    if (l == line) return true;
  return false;
}

// --continue (batch jobs, requeued or rerun): resume the run in --output when it has a
// checkpoint, else start it there replacing ballast's own files. Returns false when the run
// there has already finished its --cycles (summary.txt says so): nothing to do.
bool apply_continue(Config& c) {
  const fs::path out(c.output);
  if (!fs::exists(out / "checkpoint.nscd")) {
    c.overwrite = true;
    return true;
  }
  if (has_line(out / "summary.txt", "cycles = " + std::to_string(c.cycles)) && has_line(out / "summary.txt", "result = valid")) {
    std::printf("ballast: --continue: %s has finished its %d cycles: nothing to do\n", c.output.c_str(), c.cycles);
    return false;
  }
  c.resume = c.output;
  c.sample.clear();
  c.overwrite = false;
  c.continue_run = false;
  return true;
}

std::string hex(double v) {
  std::ostringstream s;
  s << std::hexfloat << v;
  return s.str();
}
// The files a ballast run writes in its output folder (--overwrite deletes them first).
const std::vector<std::string> kOutputs = {"summary.txt", "cycles.csv", "steps.csv", "checkpoint.nscd", "sample.nscd",
                                           "vtk", "cycles.csv.tmp", "steps.csv.tmp", "checkpoint.nscd.tmp", "sample.nscd.tmp",
                                           "refused_step_problem.txt", "summary.txt.tmp"};

scenes::BallastOptions sample_options(const Config& c) {
  scenes::BallastOptions o;
  o.seed = c.seed;
  o.box_width = c.box_width;
  o.grading_fraction = c.grading_fraction;
  o.mu = c.mu;
  o.pads = c.pads;
  o.k = c.k;
  o.nu = c.nu;
  o.spring_length = c.spring_length;
  // a pad of another height keeps the default pad's mass (density scaled): only its sides change
  const scenes::BallastOptions d;
  o.pad_height = c.pad_height;
  o.pad_density = d.pad_density * d.pad_height / c.pad_height;
  o.sleeper_width = c.sleeper_width;
  o.bars = c.bars;
  return o;
}

StepperOptions stepper_options(const Config& c) {
  StepperOptions s;
  s.solver = parse_solver_kind(c.solver, "--solver");
  s.newton.tol = c.newton_tol;
  s.newton.max_iterations = c.newton_max_iterations;
  s.newton.presweeps = c.newton_presweeps;
  s.newton.presweep_tol = c.newton_presweep_tol;
  s.nlgs.policy = parse_convergence_policy(c.policy);
  s.nlgs.tol = c.tol;
  s.nlgs.check_every = c.check_every;
  s.nlgs.min_sweeps = c.min_sweeps;
  s.nlgs.max_sweeps = c.max_sweeps;
  s.nlgs.relaxation = c.relaxation;
  s.nlgs.anderson = c.anderson;
  s.nlgs.order = parse_sweep_order(c.order);
  s.nlgs.threads = c.threads;
  s.strict_alert = c.strict_alert;
  s.residual_check_every = c.residual_check_every;
  s.residual_flag = c.residual_flag;
  s.residual_limit = c.residual_limit;
  s.projection.enabled = c.projection;
  s.projection.slop = c.projection_slop;
  s.projection.share = c.projection_share;
  s.failure_dump = (fs::path(c.output) / "refused_step_problem.txt").string();  // a refused step's problem
  return s;
}

// Steps until the given bodies are at rest (rms speed < v for 0.05 s, counted after 0.05 s) or
// t_max (nscd::driver::settle), with a progress line every progress_every wall seconds.
void settle(Registry& reg, MoreauJean& mj, const std::vector<BodyId>& bodies, double v, double t_max, const char* what,
            double progress_every, scenes::StepWatch& watch) {
  driver::SettleRule rule;
  rule.speed = v;
  rule.window = 0.05;
  rule.min_time = std::nextafter(0.05, 1.0);  // strictly after 0.05 s
  rule.max_time = t_max;
  auto last = Clock::now();
  const auto t0 = Clock::now();
  // ETA from the cost per step of the current phase, to the time limit: not a bound (the steps
  // left can cost more), and the phase usually ends sooner, at rest
  scenes::StepCostEta eta(std::max(10.0, 2.0 * progress_every));
  const auto steps_max = static_cast<std::int64_t>(std::ceil(t_max / reg.params.dt - 1e-9));
  std::int64_t n = 0;
  eta.observe(0, 0.0);
  const driver::SettleResult res = driver::settle(
      reg, bodies, rule,
      [&] {
        const StepReport r = mj.step();
        eta.observe(++n, since(t0));
        watch.observe(reg, r, mj.options());
        return r;
      },
      [&](const driver::SettleStep& st) {
        if (since(last) < progress_every) return;
        last = Clock::now();
        std::printf("  %s: t %.3f s  contacts %zu  sweeps %d  rms speed %.2e m/s  elapsed %s  ETA %s at %.3g ms/step to the %g s "
                    "limit (sooner at rest)\n",
                    what, st.elapsed, st.report.contacts, st.report.sweeps, st.rms_speed, format_duration(since(t0)).c_str(),
                    format_duration(eta.eta(steps_max - n)).c_str(), 1e3 * eta.seconds_per_step(), t_max);
        std::fflush(stdout);
      });
  if (res.at_rest)
    std::printf("  %s: at rest after %.3f s simulated (%s)\n", what, res.elapsed, format_duration(since(t0)).c_str());
  else
    std::printf("  %s: WARNING not at rest after %.3f s simulated (rms speed above %g m/s); continuing\n", what, t_max, v);
}

// Keeps the header and the complete rows whose first column is <= last (a resumed run rewrites
// the rest). A run killed while writing can leave its last row cut short, with no end of line:
// that row is dropped whatever it reads as ("42" cut from step 4248 would read as step 42 and
// stay otherwise). A file written by an earlier version, whose columns are the first of
// `columns`, gets the new header and its rows "nan" in the new columns, so that every row has
// every column. The file is rewritten whole or not at all (atomic_write), so a kill during the
// truncation leaves the old file.
void truncate_csv(const fs::path& file, double last, const std::vector<std::string>& columns) {
  std::ifstream in(file);
  if (!in) return;
  std::vector<std::string> keep;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (in.eof()) break;  // no '\n' after it: a row cut short
    char* end = nullptr;
    const double first = std::strtod(line.c_str(), &end);
    if (header || (end != line.c_str() && *end == ',' && first <= last)) keep.push_back(line);
    header = false;
  }
  in.close();
  std::string names;
  for (const auto& c : columns) names += (names.empty() ? "" : ",") + c;
  if (!keep.empty() && keep[0] != names) {
    if (names.rfind(keep[0] + ",", 0) != 0)
      throw Error("cannot resume into " + file.string() + ": its columns (" + keep[0] + ") are not the first of this version's (" +
                  names + ")");
    const auto added = std::count(names.begin() + static_cast<std::ptrdiff_t>(keep[0].size()), names.end(), ',');
    std::string pad;
    for (std::ptrdiff_t i = 0; i < added; ++i) pad += ",nan";
    keep[0] = names;
    for (std::size_t i = 1; i < keep.size(); ++i) keep[i] += pad;
  }
  atomic_write(file, [&](std::ostream& out) {
    for (const auto& l : keep) out << l << '\n';
  });
}

// The values of the options added since the first checkpoints, as runs had them before: the
// paper's fixed order, plain sweeps, no mixing, no projection (defaults since issue #36).
const std::map<std::string, std::string> kBeforeTheOption = {
    {"order", "fixed"}, {"relaxation", "1"}, {"anderson", "0"}, {"projection", "0"}};

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

std::map<std::string, std::string> state_map(const Config& c, const RunState& s, const std::string& sample) {
  std::map<std::string, std::string> m = to_map(c);
  m["state.cycles_done"] = std::to_string(s.cycles_done);
  m["state.t0"] = hex(s.t0);
  m["state.y_ref"] = hex(s.y_ref);
  m["state.x_ref"] = hex(s.x_ref);
  m["state.sweeps"] = std::to_string(s.sweeps);
  m["state.steps"] = std::to_string(s.steps);
  m["state.unconverged"] = std::to_string(s.unconverged);
  m["state.max_overlap"] = hex(s.max_overlap);
  m["state.sum_mean_overlap"] = hex(s.sum_mean_overlap);
  m["state.sum_total_overlap"] = hex(s.sum_total_overlap);
  m["state.cpu_seconds"] = hex(s.cpu_seconds);
  m["state.max_sweeps"] = std::to_string(s.max_sweeps);
  m["state.presweeps"] = std::to_string(s.presweeps);
  m["state.settlement_min"] = hex(s.last_settlement_min);
  m["state.settlement_max"] = hex(s.last_settlement_max);
  m["state.contact_dissipation"] = hex(s.contact_dissipation);
  m["state.damper_dissipation"] = hex(s.damper_dissipation);
  if (!sample.empty()) m["state.sample"] = sample;
  return m;
}

// Read strictly: each value whole, finite, in range; errors name the file and the key.
RunState state_from(const std::map<std::string, std::string>& m, const std::string& file) {
  auto get = [&](const char* k) {
    const auto it = m.find(k);
    if (it == m.end()) throw Error("checkpoint '" + file + "' has no '" + k + "': not a ballast run checkpoint");
    return it->second;
  };
  auto what = [&](const char* k) { return "checkpoint '" + file + "', key '" + k + "'"; };
  auto count = [&](const char* k) { return parse_integer(get(k), what(k), 0, std::int64_t(1) << 50); };
  auto real = [&](const char* k) { return parse_real(get(k), what(k), -kMaxLength, kMaxLength); };
  RunState s;
  s.cycles_done = static_cast<int>(parse_integer(get("state.cycles_done"), what("state.cycles_done"), 0, 1'000'000'000));
  s.t0 = parse_real(get("state.t0"), what("state.t0"), -kMaxTime, kMaxTime);
  s.y_ref = real("state.y_ref");
  s.x_ref = real("state.x_ref");
  s.sweeps = count("state.sweeps");
  s.steps = count("state.steps");
  s.unconverged = count("state.unconverged");
  s.max_overlap = real("state.max_overlap");
  s.sum_mean_overlap = parse_real(get("state.sum_mean_overlap"), what("state.sum_mean_overlap"));
  s.last_settlement_min = real("state.settlement_min");
  // A sum a checkpoint written before it existed lacks is unknown: NaN, stored as "nan" by the
  // checkpoints that follow (read back as NaN, not refused as a bad number).
  auto maybe_unknown = [&](const char* k) {
    return !m.count(k) || m.at(k) == "nan" || m.at(k) == "-nan" ? std::nan("") : parse_real(get(k), what(k));
  };
  // added with issue #10: a checkpoint written before has neither; the totals are then unknown (NaN)
  s.sum_total_overlap = maybe_unknown("state.sum_total_overlap");
  s.cpu_seconds = m.count("state.cpu_seconds") ? parse_real(get("state.cpu_seconds"), what("state.cpu_seconds"), 0.0, 1e15) : std::nan("");
  s.max_sweeps = m.count("state.max_sweeps") ? parse_integer(get("state.max_sweeps"), what("state.max_sweeps"), -1, std::int64_t(1) << 50) : -1;
  s.presweeps = m.count("state.presweeps") ? parse_integer(get("state.presweeps"), what("state.presweeps"), -1, std::int64_t(1) << 50) : -1;
  s.last_settlement_max = real("state.settlement_max");
  // added with issue #11 (NaN when absent, as above)
  s.contact_dissipation = maybe_unknown("state.contact_dissipation");
  s.damper_dissipation = maybe_unknown("state.damper_dissipation");
  if (s.unconverged > s.steps) throw Error(what("state.unconverged") + ": more unconverged steps than steps");
  return s;
}

// What a loaded sample is, whatever the options said: its pads, springs, friction and box.
// measure_pad_height: the sample does not record its pads' height (written before --pad-height).
void sample_facts(const scenes::BallastScene& s, Config& c, bool measure_pad_height) {
  const Registry& reg = s.scene.reg;
  c.pads = static_cast<int>(s.pads.size());
  if (!reg.links.empty()) {
    c.k = reg.links.law[0].k;
    c.nu = reg.links.law[0].nu;
    c.spring_length = reg.links.law[0].L0;
  }
  if (reg.contact_laws.default_law >= 0) c.mu = reg.contact_laws.laws[static_cast<std::size_t>(reg.contact_laws.default_law)].mu;
  c.box_width = s.scene.box_width;
  if (measure_pad_height && !s.pads.empty())
    for (std::uint32_t k = 0; k < reg.polyg.size(); ++k)
      if (reg.polyg.body[k] == s.pads.front()) {
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const Vec2& v : world_polygon(reg, PolygId(k))) {
          lo = std::min(lo, v.y);
          hi = std::max(hi, v.y);
        }
        c.pad_height = hi - lo;
        break;
      }
}

// 2. The sleeper load, from t0: F = A + B cos(2π f (t − t0) − φ) along (sin β, −cos β)·(−1).
void impose_load(Registry& reg, BodyId sleeper, const Config& c, double t0) {
  const double beta = c.inclination * kPi / 180.0, ramp = c.ramp_cycles / c.frequency;
  impose_force(reg, sleeper, Dof::Y,
               TimeFunction::cosine(c.load_mean * std::cos(beta), c.load_amplitude * std::cos(beta), c.frequency, c.phase, ramp, t0));
  if (beta != 0.0)
    impose_force(reg, sleeper, Dof::X,
                 TimeFunction::cosine(-c.load_mean * std::sin(beta), -c.load_amplitude * std::sin(beta), c.frequency, c.phase, ramp, t0));
}

}  // namespace

int run(Config c) {
  const auto wall0 = Clock::now();
  if (c.continue_run && !apply_continue(c)) return 0;
  const Config cli = c;
  check(c);  // Config built by hand (tests, other drivers) gets the same checks as the command line
  scenes::BallastScene s;
  RunState st;
  std::vector<MoreauJean::WarmStartEntry> warm;
  bool resumed = false, cycles_started = false;
  std::string sample_used = c.sample;  // the sample file this run started from (empty: prepared)

  // 0. The output folder: never mixed with an earlier run's files.
  if (c.resume.empty()) {
    const std::string note = scenes::claim_output_folder(c.output, kOutputs, c.overwrite, true, c.sample);
    if (!note.empty()) std::printf("ballast: %s\n", note.c_str());
  } else if (cli.given.count("output") && fs::path(c.output).lexically_normal() != fs::path(c.resume).lexically_normal()) {
    throw std::invalid_argument("--output " + c.output + " cannot go with --resume " + c.resume + ": a resumed run writes into its own folder");
  }

  // 1. The sample.
  if (!c.resume.empty()) {
    const fs::path cp_file = fs::path(c.resume) / "checkpoint.nscd";
    Checkpoint cp = load_checkpoint(cp_file);
    const std::string source = "checkpoint '" + cp_file.string() + "'";
    // a checkpoint written before an option existed resumes as its run ran: without it
    for (const auto& [key, before] : kBeforeTheOption)
      if (!cp.extra.count(key)) cp.extra[key] = before;
    from_map(cp.extra, c, source);
    c.cycles = cli.cycles;  // the command line may extend the run
    c.stop_after_cycles = cli.stop_after_cycles;
    c.progress_every = cli.progress_every;
    c.output = c.resume;
    refuse_changes(cli, cp.extra, false, "the resumed run's " + source);
    try {
      check(c);
    } catch (const std::invalid_argument& e) {
      throw Error(source + " holds an option out of range: " + e.what());
    }
    if (c.threads > 1 && c.order != "colored" && c.order != "colored-rows")
      throw std::invalid_argument("--threads " + std::to_string(c.threads) + " needs --order colored or colored-rows, and the resumed run sweeps in order " +
                                  c.order + " (its checkpoint's order; a resumed run keeps it)");
    st = state_from(cp.extra, cp_file.string());
    if (const auto it = cp.extra.find("state.sample"); it != cp.extra.end()) sample_used = it->second;
    if (c.cycles < st.cycles_done)
      throw std::invalid_argument("--cycles " + std::to_string(c.cycles) + " is below the " + std::to_string(st.cycles_done) +
                                  " cycles the resumed run has already done");
    warm = std::move(cp.warm_start);
    s = scenes::recognise_ballast(std::move(cp.reg));
    if (!s.sleeper.valid()) throw Error(source + " has no sleeper: not a ballast run checkpoint");
    resumed = cycles_started = true;
    std::printf("ballast: resuming %s at cycle %d (t = %s s)\n", c.resume.c_str(), st.cycles_done, exact(s.scene.reg.time).c_str());
  } else if (!c.sample.empty()) {
    Checkpoint cp = load_checkpoint(c.sample);
    const std::string source = "the sample '" + c.sample + "'";
    if (cp.extra.count("state.cycles_done"))
      throw Error(source + " is the checkpoint of a run (its load is already applied), not a prepared sample: continue it with --resume");
    refuse_changes(cli, cp.extra, true, source);
    std::map<std::string, std::string> recorded;
    for (const auto& [k, v] : scene_map(c))
      if (const auto it = cp.extra.find(k); it != cp.extra.end()) recorded[k] = it->second;
    from_map(recorded, c, source);
    warm = std::move(cp.warm_start);
    s = scenes::recognise_ballast(std::move(cp.reg));
    if (!s.sleeper.valid()) throw Error(source + " has no sleeper: not a prepared ballast sample");
    sample_facts(s, c, !cp.extra.count("pad-height"));
    std::printf("ballast: loaded the prepared sample %s (%zu grains, %zu pads)\n", c.sample.c_str(), s.scene.grains.size(), s.pads.size());
  } else {
    s = scenes::ballast_sample(sample_options(c));
    std::printf("ballast: preparing the sample (seed %llu): %zu-grain deposit on %d pads, then the sleeper\n",
                static_cast<unsigned long long>(c.seed), s.scene.grains.size(), c.pads);
  }
  Registry& reg = s.scene.reg;
  // the sample's own stiffness (before any --k-factor) and seed, for the summary
  const double k_sample = reg.links.empty() ? c.k : reg.links.law[0].k / (cycles_started ? c.k_factor : 1.0);
  // The largest load the sublayer can carry: its springs squeezed to zero length. A heavier
  // load pushes the pads through the floor (a settlement of kilometres, not a result).
  const double capacity = double(s.springs.size()) * k_sample * c.k_factor * c.spring_length;
  const double peak = std::abs(c.load_mean) + std::abs(c.load_amplitude);
  if (!c.prepare_only && !(peak <= capacity))
    throw std::invalid_argument("the load |load-mean| + |load-amplitude| = " + exact(peak) + " N/m exceeds what the sublayer can carry (" +
                                std::to_string(s.springs.size()) + " springs x k " + exact(k_sample) + " N/m x k-factor " +
                                exact(c.k_factor) + " x spring length " + exact(c.spring_length) + " m = " + exact(capacity) +
                                " N/m, the springs squeezed to zero length)");
  reg.params.dt = c.dt;
  reg.params.theta = c.theta;
  reg.params.alert = c.alert;
  validate(reg.params);
  MoreauJean mj(reg, stepper_options(c));
  mj.set_warm_start_memory(warm);
  driver::input_accepted();  // options, sample and checkpoint accepted: from here, errors are the run's (exit 1)
  if (c.pad_height < c.spring_length)
    std::printf("WARNING: the pads (%g m) are shorter than the springs (%g m): a pad sinking more than its height below a "
                "neighbour opens a way under that neighbour, and grains can leave the layer through the sublayer "
                "(--pad-height %g closes it)\n", c.pad_height, c.spring_length, c.spring_length);
  scenes::StepWatch watch;  // counts of this process's steps (not carried by checkpoints)
  const double overlap_limit = c.overlap_limit < 0.0 ? scenes::kOverlapLimitFraction * scenes::smallest_grain_size(reg, s.scene.grains)
                                                   : c.overlap_limit;
  watch.overlap_limit = overlap_limit;
  const fs::path out(c.output);

  if (c.resume.empty() && c.sample.empty()) {
    settle(reg, mj, s.scene.grains, c.equilibrium_speed, c.prep_max_time, "deposit", c.progress_every, watch);
    scenes::place_sleeper(s, sample_options(c));
    std::vector<BodyId> moving = s.scene.grains;
    moving.push_back(s.sleeper);
    settle(reg, mj, moving, c.equilibrium_speed, c.settle_time, "sleeper", c.progress_every, watch);
    std::map<std::string, std::string> record = scene_map(c);
    record["kind"] = "ballast-sample";
    save_checkpoint(out / "sample.nscd", reg, mj.warm_start_memory(), record);
    std::printf("  sample saved: %s (reuse it with --sample)\n", (out / "sample.nscd").string().c_str());
  }
  const double prep_wall = since(wall0);
  if (c.prepare_only) return 0;

  // 2. The load and the sublayer stiffness of this run.
  if (c.guided_sleeper && !resumed) {
    fix_dof(reg, s.sleeper, Dof::X);
    fix_dof(reg, s.sleeper, Dof::Rot);
  }
  if (!cycles_started) {
    if (c.k_factor != 1.0) scenes::scale_sublayer_stiffness(s, c.k_factor);
    st.t0 = reg.time;
    st.y_ref = reg.bodies.y[s.sleeper.index()];
    st.x_ref = reg.bodies.x[s.sleeper.index()];
    impose_load(reg, s.sleeper, c, st.t0);
  }
  const int n_cycle = static_cast<int>(std::lround(1.0 / (c.frequency * c.dt)));

  // 3. Outputs (a resumed run drops what was written after its checkpoint).
  // the POSTPRO series (issue #11, docs/output.md) come after the columns of before
  std::vector<std::string> cycle_columns = {"cycle", "time", "settlement_min_load", "settlement_max_load", "lateral_displacement",
                                            "mean_grain_speed", "mean_overlap", "max_overlap", "mean_sweeps", "unconverged_steps",
                                            "wall_time", "total_overlap", "kinetic_energy", "contact_dissipation",
                                            "contact_dissipation_cycle", "damper_dissipation", "damper_dissipation_cycle"};
  std::vector<std::string> step_columns = {"step", "time", "load", "settlement", "contacts", "active", "sweeps", "converged",
                                           "quad_dv", "maxm_dv", "mean_overlap", "max_overlap", "rms_grain_speed", "detect_s",
                                           "solve_s", "kinetic_energy", "contact_dissipation", "damper_dissipation"};
  cycle_columns.insert(cycle_columns.end(), scenes::network_columns().begin(), scenes::network_columns().end());
  step_columns.insert(step_columns.end(), scenes::network_columns().begin(), scenes::network_columns().end());
  // NEWTON_AC's hybrid: the NLGS sweeps before Newton, which `sweeps` (Newton iterations) leaves out
  cycle_columns.push_back("mean_presweeps");
  step_columns.push_back("presweeps");
  if (resumed) {
    truncate_csv(out / "cycles.csv", st.cycles_done, cycle_columns);
    truncate_csv(out / "steps.csv", static_cast<double>(reg.step), step_columns);
  }
  CsvWriter cycles_csv(out / "cycles.csv", cycle_columns, resumed, 1);
  CsvWriter steps_csv(out / "steps.csv", step_columns, resumed, 100);
  const scenes::NetworkMeter network(reg, s.scene.grains);
  std::vector<double> row;  // reused: no allocation per row
  std::unique_ptr<VtkWriter> vtk;
  if (c.vtk_every > 0) {
    vtk = std::make_unique<VtkWriter>(out / "vtk");
    if (resumed) vtk->resume(reg.time);  // frames up to the checkpoint stay listed
    else vtk->write_frame(reg);
  }
  const int last_cycle = c.stop_after_cycles > 0 ? std::min(c.cycles, st.cycles_done + c.stop_after_cycles) : c.cycles;
  const bool newton = c.solver == "NEWTON_AC";
  // the sweep's order and relaxation are named when they are not the paper's (fixed, 1)
  std::string sweep;
  if (!newton && c.order != "fixed") sweep += ", order " + c.order;
  if (!newton && c.relaxation != 1.0) sweep += ", relaxation " + exact(c.relaxation);
  if (!newton && c.anderson != 0) sweep += ", Anderson mixing depth " + std::to_string(c.anderson);
  std::printf("ballast: %d cycles of %d steps (f = %g Hz, dt = %g s), k = %g N/m x %g, %s %s tol %g%s, output %s\n", c.cycles, n_cycle,
              c.frequency, c.dt, c.k, c.k_factor, c.solver.c_str(), newton ? "" : c.policy.c_str(),
              newton ? c.newton_tol : c.tol, sweep.c_str(), out.string().c_str());
  const auto cycles_wall0 = Clock::now();
  auto last_checkpoint = Clock::now();
  const SigtermCheckpoint sigterm;
  bool terminated = false;
  const std::clock_t cycles_cpu0 = std::clock();
  const int first_cycle = st.cycles_done;
  auto last_print = Clock::now();
  const BodyId sl = s.sleeper;
  double s_max = 0.0, s_min = 0.0;
  std::string impossible;  // a physically impossible state, found at the end of a cycle
  bool over_budget = false;  // --strict-overlap: the overlap budget was passed in the cycle just done

  for (int cycle = st.cycles_done; cycle < last_cycle; ++cycle) {
    const auto cw = Clock::now();
    double speed_sum = 0.0, overlap_sum = 0.0, overlap_max = 0.0, total_sum = 0.0, contact_diss = 0.0, damper_diss = 0.0;
    const std::clock_t cc = std::clock();
    std::int64_t sweeps = 0, unconverged = 0, max_sweeps = 0, presweeps = 0;
    for (int j = 1; j <= n_cycle; ++j) {
      const StepReport r = mj.step();
      watch.observe(reg, r, mj.options());
      const double settlement = st.y_ref - reg.bodies.y[sl.index()];
      const double v = mean_speed(reg, s.scene.grains);
      speed_sum += v;
      overlap_sum += r.mean_overlap;
      total_sum += r.total_overlap;
      overlap_max = std::max(overlap_max, r.max_overlap);
      sweeps += r.sweeps;
      max_sweeps = std::max<std::int64_t>(max_sweeps, r.sweeps);
      presweeps += r.presweeps;
      unconverged += r.converged ? 0 : 1;
      contact_diss += r.contact_dissipation;
      damper_diss += r.damper_dissipation;
      st.contact_dissipation += r.contact_dissipation;
      st.damper_dissipation += r.damper_dissipation;
      if (j == n_cycle / 2) s_max = settlement;  // F = A + B: the largest load of the cycle
      if (j == n_cycle) s_min = settlement;      // F = A − B: the smallest
      if (reg.step % c.steps_every == 0) {
        const double load = external_force(reg, sl, reg.time).fy + reg.bodies.mass[sl.index()] * (-reg.params.gravity.y);
        row = {double(reg.step), reg.time, load, settlement, double(r.contacts), double(r.active), double(r.sweeps),
               r.converged ? 1.0 : 0.0, r.criteria.quad_dv, r.criteria.maxm_dv, r.mean_overlap, r.max_overlap,
               rms_speed(reg, s.scene.grains), r.detect_seconds, r.solve_seconds,
               kinetic_energy(reg), st.contact_dissipation, st.damper_dissipation};
        scenes::append_network_values(network.measure(reg), row);
        row.push_back(double(r.presweeps));
        steps_csv.row(row);
      }
      if (vtk && reg.step % c.vtk_every == 0) vtk->write_frame(reg);
    }
    st.cycles_done = cycle + 1;
    st.sweeps += sweeps;
    st.steps += n_cycle;
    st.unconverged += unconverged;
    if (st.max_sweeps >= 0) st.max_sweeps = std::max(st.max_sweeps, max_sweeps);
    if (st.presweeps >= 0) st.presweeps += presweeps;
    st.max_overlap = std::max(st.max_overlap, overlap_max);
    st.sum_mean_overlap += overlap_sum;
    st.sum_total_overlap += total_sum;
    st.cpu_seconds += double(std::clock() - cc) / CLOCKS_PER_SEC;
    st.last_settlement_min = s_min;
    st.last_settlement_max = s_max;
    row = {double(st.cycles_done), reg.time, s_min, s_max, reg.bodies.x[sl.index()] - st.x_ref, speed_sum / n_cycle,
           overlap_sum / n_cycle, overlap_max, double(sweeps) / n_cycle, double(unconverged), since(cw), total_sum / n_cycle,
           kinetic_energy(reg), st.contact_dissipation, contact_diss, st.damper_dissipation, damper_diss};
    scenes::append_network_values(network.measure(reg), row);
    row.push_back(double(presweeps) / n_cycle);
    cycles_csv.row(row);
    impossible = scenes::implausible(reg, s.scene.grains, s.scene.box_width, 0.0);
    if (impossible.empty()) impossible = scenes::grain_below_sublayer(s);
    if (impossible.empty() && !(std::abs(s_min) <= st.y_ref && std::abs(s_max) <= st.y_ref))
      impossible = "the settlement (" + exact(s_min) + " m) is larger than the whole layer (the sleeper started " + exact(st.y_ref) +
                   " m above the floor)";
    if (!impossible.empty()) {
      impossible = "cycle " + std::to_string(st.cycles_done) + ": " + impossible;
      break;  // the last checkpoint (before this state) is kept
    }
    over_budget = c.strict_overlap && watch.over_limit_steps > 0;
    // Checkpoints at cycle ends only (a checkpoint carries no partial cycle): every
    // --checkpoint-every cycles, at the first cycle end --checkpoint-wall seconds after the
    // last one, and on SIGTERM, which then ends the run.
    terminated = sigterm.requested();
    if ((c.checkpoint_every > 0 && st.cycles_done % c.checkpoint_every == 0) ||
        (c.checkpoint_wall > 0 && since(last_checkpoint) >= c.checkpoint_wall) || terminated || over_budget) {
      steps_csv.flush();
      save_checkpoint(out / "checkpoint.nscd", reg, mj.warm_start_memory(), state_map(c, st, sample_used));
      last_checkpoint = Clock::now();
    }
    if (over_budget) break;
    if (terminated) {
      std::printf("ballast: SIGTERM: stopped after cycle %d with its checkpoint; continue with --resume %s\n", st.cycles_done,
                  out.string().c_str());
      break;
    }
    if (since(last_print) >= c.progress_every || st.cycles_done == last_cycle) {
      last_print = Clock::now();
      const double per = since(cycles_wall0) / double(st.cycles_done - first_cycle);
      char pre[48] = "";  // the hybrid's NLGS sweeps, which the Newton iterations leave out
      if (presweeps > 0) std::snprintf(pre, sizeof pre, " (+%.1f NLGS)", double(presweeps) / n_cycle);
      std::printf("cycle %5d/%d  settlement %.4f mm (max load %.4f mm)  sweeps/step %.1f%s  max overlap %.2e m  %.2f s/cycle  ETA %s\n",
                  st.cycles_done, c.cycles, 1e3 * s_min, 1e3 * s_max, double(sweeps) / n_cycle, pre, overlap_max, per,
                  format_duration(per * (last_cycle - st.cycles_done)).c_str());
      std::fflush(stdout);
    }
  }
  steps_csv.flush();
  cycles_csv.flush();

  // 4. Summary and final checkpoint (none of an impossible state).
  if (impossible.empty()) save_checkpoint(out / "checkpoint.nscd", reg, mj.warm_start_memory(), state_map(c, st, sample_used));
  if (vtk && st.cycles_done > first_cycle && reg.step % c.vtk_every != 0) vtk->write_frame(reg);
  const int run_cycles = st.cycles_done - first_cycle;
  const double cycles_wall = since(cycles_wall0);
  const double cycles_cpu = double(std::clock() - cycles_cpu0) / CLOCKS_PER_SEC;
  driver::Summary summary;  // written whole at the end (atomic_write), 17 significant digits
  std::ostream& sum = summary.stream();
  // what the run used (a loaded sample's own values, a resumed run's stored options)
  sum << "result = " << (!impossible.empty() ? "impossible: " + impossible : over_budget ? "stopped: overlap budget passed" : "valid") << "\n"
      << "sample = " << (sample_used.empty() ? "prepared by this run" : sample_used) << "\n"
      << "solver = " << c.solver << "\n"
      << "order = " << c.order << "\n"
      << "relaxation = " << exact(c.relaxation) << "\n"
      << "anderson = " << c.anderson << "\n"
      << "cycles = " << st.cycles_done << "\n"
      << "final_settlement = " << st.last_settlement_min << "\n"
      << "final_settlement_max_load = " << st.last_settlement_max << "\n"
      << "mean_sweeps = " << (st.steps ? double(st.sweeps) / double(st.steps) : 0.0) << "\n"
      << "max_sweeps = " << (st.max_sweeps >= 0 ? double(st.max_sweeps) : std::nan("")) << "\n"
      << "mean_presweeps = " << (st.presweeps >= 0 && st.steps ? double(st.presweeps) / double(st.steps) : std::nan("")) << "\n"
      << "max_overlap = " << st.max_overlap << "\n"
      << "mean_overlap = " << (st.steps ? st.sum_mean_overlap / double(st.steps) : 0.0) << "\n"
      << "cumulated_overlap = " << (st.steps ? st.sum_total_overlap / double(st.steps) : 0.0) << "\n"
      << "projection = " << (c.projection ? "on" : "off") << "\n"
      << "projection_slop = " << c.projection_slop * c.alert << "\n"
      << "unconverged_steps = " << st.unconverged << "\n"
      << "steps_per_cycle = " << n_cycle << "\n"
      << "grains = " << s.scene.grains.size() << "\n"
      << "pads = " << s.pads.size() << "\n"
      << "pad_height = " << exact(c.pad_height) << "\n"
      << "k = " << k_sample << "\n"
      << "k_factor = " << c.k_factor << "\n"
      << "seed = " << c.seed << "\n"
      << "mu = " << c.mu << "\n"
      << "nu = " << c.nu << "\n"
      << "box_width = " << c.box_width << "\n"
      << "dt = " << c.dt << "\n"
      << "frequency = " << c.frequency << "\n"
      << "load_mean = " << c.load_mean << "\n"
      << "load_amplitude = " << c.load_amplitude << "\n"
      << "wall_time = " << since(wall0) << "\n"
      << "preparation_wall_time = " << prep_wall << "\n"
      << "time_per_cycle = " << (run_cycles > 0 ? cycles_wall / run_cycles : 0.0) << "\n"
      << "cpu_time_per_cycle = " << (run_cycles > 0 ? cycles_cpu / run_cycles : 0.0) << "\n"
      << "cpu_time_cycles = " << st.cpu_seconds << "\n"
      << watch.summary();
  if (st.cycles_done > 0) {
    const int block = scenes::overlap_block_length(st.cycles_done);
    summary.lines(scenes::overlap_growth_lines(scenes::overlap_blocks(out / "cycles.csv", block), block));
  }
  summary.write(out / "summary.txt");
  if (over_budget) {
    std::fflush(stdout);
    std::fprintf(stderr, "ballast: error: the overlap budget %g m was passed (first at step %lld; --strict-overlap): the run stops after "
                 "cycle %d with its checkpoint (exit 3)\n", overlap_limit, static_cast<long long>(watch.first_over_limit), st.cycles_done);
    return driver::kExitImpossible;
  }
  if (!impossible.empty()) {
    std::fflush(stdout);
    std::fprintf(stderr, "ballast: error: physically impossible result at %s; the run stops (exit 3), its last checkpoint is kept\n",
                 impossible.c_str());
    return driver::kExitImpossible;
  }
  if (terminated) {
    std::fflush(stdout);
    std::fprintf(stderr, "ballast: stopped by SIGTERM after cycle %d of %d (exit 143); %s/checkpoint.nscd holds it\n", st.cycles_done,
                 c.cycles, out.string().c_str());
    return driver::kExitTerminated;
  }
  std::printf("done: %d cycles, settlement %.4f mm at the smallest load (%.4f mm at the largest), %.2f s/cycle, mean sweeps %.1f,\n"
              "      max overlap %.2e m; outputs in %s (summary.txt, cycles.csv, steps.csv, checkpoint.nscd%s)\n",
              st.cycles_done, 1e3 * st.last_settlement_min, 1e3 * st.last_settlement_max,
              run_cycles > 0 ? cycles_wall / run_cycles : 0.0, st.steps ? double(st.sweeps) / double(st.steps) : 0.0,
              st.max_overlap, out.string().c_str(), vtk ? ", vtk/" : "");
  std::fputs(watch.closing_line().c_str(), stdout);
  return 0;
}

}  // namespace ballast
