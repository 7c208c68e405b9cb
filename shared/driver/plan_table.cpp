// nscd/shared/driver/plan_table.cpp — a step's plan on a model, for the drivers' --plan-model
// (plan_table.hpp), and their lists of thread counts.
#include "nscd/shared/driver/plan_table.hpp"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>

#include "nscd/solvers/nlgs_blocks.hpp"
#include "nscd/solvers/nlgs_colored.hpp"
#include "nscd/solvers/nlgs_lanes.hpp"
#include "nscd/solvers/nlgs_plan_model.hpp"
#include "nscd/shared/driver/options.hpp"

namespace nscd::driver {
namespace {

// A scalar contact update of share 0's tail, in the model's units (an AVX2 bundle of 8): about
// a fifth (13 ns a scalar update against 8 × 7.7 ns a bundle on the development machine,
// docs/benchmarks.md §6).
constexpr double kScalarUnits = 0.2;
// A wait not met when reached, in units: a cache line between cores costs about 100 ns, about
// two bundles (docs/record/benchmarks-history.md §11.12).
constexpr double kLatencyUnits = 2.0;

struct Planned {
  PlanModel model, late;  ///< without, and with kLatencyUnits a wait
  bool field = false;  ///< laid out in strips or cells (else blocks of consecutive contacts: never planned)
  std::size_t stops = 0, min_bundles = 0, max_bundles = 0;
  std::size_t blocks = 0, longest = 0, colours = 0;  ///< the layout's (the overflow left out)
  double dealt = 0.0;  ///< a sweep of the colours dealt one after the other, and the tail (units)
  std::size_t dealt_bundles = 0;  ///< … its bundles
};

// `threads` threads' plan of a copy of `sys` and its models; false where the solve plans none
bool plan_for(const ContactSystem& sys, NlgsOptions opt, int threads, Planned& out) {
  ContactSystem copy = sys;
  NlgsColoredWorkspace ws;
  opt.threads = threads;
  const LanePlan* plan = plan_colored(copy, opt, ws);
  out.field = ws.strips || ws.cells;
  if (plan == nullptr) return false;
  const std::size_t overflow = copy.contacts.size() - ws.block_start[ws.color_start[colored::kOverflow]];
  for (std::size_t k = 0; k < colored::kOverflow; ++k)
    for (std::uint32_t b = ws.color_start[k]; b < ws.color_start[k + 1]; ++b) {
      const std::size_t length = ws.block_start[b + 1] - ws.block_start[b];
      out.blocks += length > 0 ? 1 : 0;
      out.longest = std::max(out.longest, length);
      out.colours = length > 0 ? k + 1 : out.colours;
    }
  const double tail = kScalarUnits * static_cast<double>(overflow + copy.links.size());
  std::vector<std::uint32_t> scratch;  // (one thread sweeps the fewer of the plan's and the deal's passes)
  for (std::size_t k = 0; k < out.colours; ++k) {
    const std::uint32_t b0 = ws.color_start[k], b1 = ws.color_start[k + 1];
    out.dealt += 0.5 * dealt_passes(ws.block_start.data(), b0, b1, true, scratch);
    out.dealt_bundles += dealt_passes(ws.block_start.data(), b0, b1, false, scratch);
  }
  out.dealt += tail;
  out.model = model_plan(*plan, tail, 16, 0.0);
  out.late = model_plan(*plan, tail, 16, kLatencyUnits);
  out.min_bundles = out.max_bundles = plan->shares.front().bundles;
  for (const SharePlan& s : plan->shares) {
    out.stops += static_cast<std::size_t>(std::count_if(
        s.stops.begin(), s.stops.end(), [](const ShareStop& x) { return x.share != ShareStop::kPublish; }));
    out.min_bundles = std::min<std::size_t>(out.min_bundles, s.bundles);
    out.max_bundles = std::max<std::size_t>(out.max_bundles, s.bundles);
  }
  return true;
}

}  // namespace

void print_plan_table(const ContactSystem& sys, const NlgsOptions& opt, const std::vector<int>& counts) {
  std::printf("plan model: %zu contacts, %zu links; a unit is a bundle of 8 contacts (half where lanes 4-7 idle)\n",
              sys.contacts.size(), sys.links.size());
  if (sys.contacts.empty()) {
    std::printf("  no contact in this step's system: nothing to plan (give a settled sample, or more steps before)\n");
    return;
  }
  Planned one;
  const bool base = plan_for(sys, opt, 1, one);
  if (base)
    std::printf(
        "  layout: %zu blocks in %zu colours, the longest %zu contacts (a block's contacts follow one another in a lane)\n",
        one.blocks, one.colours, one.longest);
  if (!base) std::printf("  one thread sweeps colour by colour here (not planned): against contacts / 8 units\n");
  const bool dealt = base && one.dealt < one.model.sweep;
  if (dealt)
    std::printf("  one thread sweeps the colours dealt one after the other here: fewer units than its plan's %.1f\n",
                one.model.sweep);
  const double one_sweep =
      !base ? static_cast<double>(sys.contacts.size()) / 8.0 : std::min(one.model.sweep, one.dealt);
  std::printf("  %7s %9s %8s %8s %8s %9s %8s %8s %10s %10s\n", "threads", "bundles", "waits", "units", "busiest",
              "sweep", "unmet", "idle", "speed-up", "+latency");
  for (const int t : counts) {
    Planned p;
    if (!plan_for(sys, opt, t, p)) {
      std::printf("  %7d  not planned: swept colour by colour (%s)\n", t,
                  !p.field ? "too few strips or cells across this system: its blocks are runs of contacts"
                  : t == 1 ? "one thread plans strips or cells below 8,192 contacts"
                           : "threads plan strips or cells up to 16,384 contacts");
      continue;
    }
    char range[32];
    if (t == 1 && dealt) {  // (the deal: no stops, no waits)
      std::snprintf(range, sizeof range, "%zu-%zu", p.dealt_bundles, p.dealt_bundles);
      std::printf("  %7d %9s %8d %8.1f %8.1f %9.1f %8.1f %8.1f %9.2fx %9.2fx\n", t, range, 0, p.dealt, p.dealt, p.dealt,
                  0.0, 0.0, 1.0, 1.0);
      continue;
    }
    const double busiest = *std::max_element(p.model.work.begin(), p.model.work.end());
    std::snprintf(range, sizeof range, "%zu-%zu", p.min_bundles, p.max_bundles);
    std::printf("  %7d %9s %8zu %8.1f %8.1f %9.1f %8.1f %8.1f %9.2fx %9.2fx\n", t, range, p.stops, p.model.total,
                busiest, p.model.sweep, p.model.waits, p.model.idle, one_sweep / p.model.sweep,
                one_sweep / p.late.sweep);
  }
  std::printf(
      "  bundles: the shares' fewest and most; waits: stops a sweep, every share's; units: every share's work a sweep;\n"
      "  busiest: the busiest share's; sweep: a sweep's time modelled; unmet: waits not met when reached, and idle:\n"
      "  the units the shares wait, a sweep; speed-up: one thread's sweep against it; +latency: each unmet wait %.0f\n"
      "  units longer (a cache line between cores). Barriers of checked sweeps and mixings, and the step around\n"
      "  the solve, are not modelled (nscd/solvers/nlgs_plan_model.hpp).\n",
      kLatencyUnits);
}

void print_next_step_plan(MoreauJean& mj, const std::vector<int>& counts) {
  const NlgsOptions& opt = mj.options().nlgs;
  if (!is_colored(opt.order) || mj.options().solver != SolverKind::NLGS) {
    std::printf("plan model: only NLGS in the colored orders plans its sweeps (this run: %s, order %s)\n",
                std::string(name_of(mj.options().solver)).c_str(), std::string(name_of(opt.order)).c_str());
    return;
  }
  mj.begin_step();
  mj.detect();
  mj.prepare();
  print_plan_table(mj.system(), opt, counts);
}

std::vector<int> parse_thread_list(const std::string& text, const std::string& option) {
  std::vector<int> out;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, comma - at);
    std::size_t used = 0;
    int t = 0;
    try {
      t = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (item.empty() || used != item.size() || t < 1 || t > 256)
      throw InputError(option + " must be a count in [1, 256] or a comma-separated list of them, got '" + text + "'");
    if (std::find(out.begin(), out.end(), t) != out.end())
      throw InputError(option + " lists " + std::to_string(t) + " twice: '" + text + "'");
    out.push_back(t);
    at = comma + 1;
  }
  if (out.size() > 8) throw InputError(option + " lists at most 8 counts, got '" + text + "'");
  return out;
}

}  // namespace nscd::driver
