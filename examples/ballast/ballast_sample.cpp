// examples/ballast/ballast_sample.cpp — steps 0 and 1 of a ballast run: the output folder and
// the sample (see ballast_sample.hpp).
#include "ballast_sample.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/io/text_reader.hpp"
#include "nscd/shared/analysis.hpp"
#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/settle.hpp"
#include "nscd/shared/driver_checks.hpp"
#include "nscd/shared/progress.hpp"

namespace fs = std::filesystem;
using namespace nscd;
using nscd::scenes::format_duration;

namespace ballast {
namespace {

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

// 1a. The sample of a resumed run: its checkpoint, with the options and the state it stored.
void resume_from_checkpoint(Run& r) {
  Config& c = r.c;
  const fs::path cp_file = fs::path(c.resume) / "checkpoint.nscd";
  Checkpoint cp = load_checkpoint(cp_file);
  const std::string source = "checkpoint '" + cp_file.string() + "'";
  // a checkpoint written before an option existed resumes as its run ran: without it
  for (const auto& [key, before] : kBeforeTheOption)
    if (!cp.extra.count(key)) cp.extra[key] = before;
  from_map(cp.extra, c, source);
  c.cycles = r.cli.cycles;  // the command line may extend the run
  c.stop_after_cycles = r.cli.stop_after_cycles;
  c.progress_every = r.cli.progress_every;
  c.output = c.resume;
  refuse_changes(r.cli, cp.extra, false, "the resumed run's " + source);
  try {
    check(c);
  } catch (const std::invalid_argument& e) {
    throw Error(source + " holds an option out of range: " + e.what());
  }
  if (c.threads > 1 && !nscd::driver::is_colored_order(c.order))
    throw std::invalid_argument("--threads " + std::to_string(c.threads) + " needs --order colored, colored-rows or colored-cells, and the resumed run sweeps in order " +
                                c.order + " (its checkpoint's order; a resumed run keeps it)");
  r.st = state_from(cp.extra, cp_file.string());
  if (const auto it = cp.extra.find("state.sample"); it != cp.extra.end()) r.sample_used = it->second;
  if (c.cycles < r.st.cycles_done)
    throw std::invalid_argument("--cycles " + std::to_string(c.cycles) + " is below the " + std::to_string(r.st.cycles_done) +
                                " cycles the resumed run has already done");
  r.warm = std::move(cp.warm_start);
  r.s = scenes::recognise_ballast(std::move(cp.reg));
  if (!r.s.sleeper.valid()) throw Error(source + " has no sleeper: not a ballast run checkpoint");
  r.resumed = r.cycles_started = true;
  std::printf("ballast: resuming %s at cycle %d (t = %s s)\n", c.resume.c_str(), r.st.cycles_done, exact(r.s.scene.reg.time).c_str());
}

// 1b. A prepared sample (--sample): its own scene options replace the command line's.
void load_sample(Run& r) {
  Config& c = r.c;
  Checkpoint cp = load_checkpoint(c.sample);
  const std::string source = "the sample '" + c.sample + "'";
  if (cp.extra.count("state.cycles_done"))
    throw Error(source + " is the checkpoint of a run (its load is already applied), not a prepared sample: continue it with --resume");
  refuse_changes(r.cli, cp.extra, true, source);
  std::map<std::string, std::string> recorded;
  for (const auto& [k, v] : scene_map(c))
    if (const auto it = cp.extra.find(k); it != cp.extra.end()) recorded[k] = it->second;
  from_map(recorded, c, source);
  r.warm = std::move(cp.warm_start);
  r.s = scenes::recognise_ballast(std::move(cp.reg));
  if (!r.s.sleeper.valid()) throw Error(source + " has no sleeper: not a prepared ballast sample");
  sample_facts(r.s, c, !cp.extra.count("pad-height"));
  std::printf("ballast: loaded the prepared sample %s (%zu grains, %zu pads)\n", c.sample.c_str(), r.s.scene.grains.size(), r.s.pads.size());
}

}  // namespace

void claim_output(const Run& r) {
  const Config& c = r.c;
  if (c.resume.empty()) {
    const std::string note = scenes::claim_output_folder(c.output, kOutputs, c.overwrite, true, c.sample);
    if (!note.empty()) std::printf("ballast: %s\n", note.c_str());
  } else if (r.cli.given.count("output") && fs::path(c.output).lexically_normal() != fs::path(c.resume).lexically_normal()) {
    throw std::invalid_argument("--output " + c.output + " cannot go with --resume " + c.resume + ": a resumed run writes into its own folder");
  }
}

void obtain_sample(Run& r) {
  if (!r.c.resume.empty()) {
    resume_from_checkpoint(r);
  } else if (!r.c.sample.empty()) {
    load_sample(r);
  } else {
    r.s = scenes::ballast_sample(sample_options(r.c));
    std::printf("ballast: preparing the sample (seed %llu): %zu-grain deposit on %d pads, then the sleeper\n",
                static_cast<unsigned long long>(r.c.seed), r.s.scene.grains.size(), r.c.pads);
  }
}

void refuse_excess_load(const Run& r, double k_sample) {
  const Config& c = r.c;
  const double capacity = double(r.s.springs.size()) * k_sample * c.k_factor * c.spring_length;
  const double peak = std::abs(c.load_mean) + std::abs(c.load_amplitude);
  if (!c.prepare_only && !(peak <= capacity))
    throw std::invalid_argument("the load |load-mean| + |load-amplitude| = " + exact(peak) + " N/m exceeds what the sublayer can carry (" +
                                std::to_string(r.s.springs.size()) + " springs x k " + exact(k_sample) + " N/m x k-factor " +
                                exact(c.k_factor) + " x spring length " + exact(c.spring_length) + " m = " + exact(capacity) +
                                " N/m, the springs squeezed to zero length)");
}

void prepare_sample(Run& r, MoreauJean& mj, scenes::StepWatch& watch, const fs::path& out) {
  const Config& c = r.c;
  Registry& reg = r.s.scene.reg;
  settle(reg, mj, r.s.scene.grains, c.equilibrium_speed, c.prep_max_time, "deposit", c.progress_every, watch);
  scenes::place_sleeper(r.s, sample_options(c));
  std::vector<BodyId> moving = r.s.scene.grains;
  moving.push_back(r.s.sleeper);
  settle(reg, mj, moving, c.equilibrium_speed, c.settle_time, "sleeper", c.progress_every, watch);
  std::map<std::string, std::string> record = scene_map(c);
  record["kind"] = "ballast-sample";
  save_checkpoint(out / "sample.nscd", reg, mj.warm_start_memory(), record);
  std::printf("  sample saved: %s (reuse it with --sample)\n", (out / "sample.nscd").string().c_str());
}

}  // namespace ballast
