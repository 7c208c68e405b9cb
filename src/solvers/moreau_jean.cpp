// nscd/solvers/moreau_jean.cpp — see moreau_jean.hpp.
#include "nscd/solvers/moreau_jean.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <chrono>
#include <cmath>
#include <sstream>
#include <utility>

#include "nscd/bodies/rbdy2.hpp"
#include "nscd/core/error.hpp"
#include "nscd/interactions/ptpt2.hpp"
#include "nscd/laws/contact_laws.hpp"
#include "nscd/solvers/step_guard.hpp"
#include "nscd/solvers/thread_range.hpp"

namespace nscd {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

MoreauJean::MoreauJean(Registry& reg, const StepperOptions& options) : reg_(reg) { set_options(options); }

void MoreauJean::set_options(const StepperOptions& o) {
  validate(o.nlgs);
  validate(o.projection);
  if (o.solver == SolverKind::NEWTON_AC) {
    if (!newton_ac_available())
      throw Error("solver NEWTON_AC is not available in this build (it needs SuiteSparse: configure with "
                  "-DNSCD_WITH_SUITESPARSE=ON); use NLGS");
    validate(o.newton);
  }
  if (o.threads < 1 || o.threads > 256) throw Error("threads must lie in [1, 256]");
  if (o.loop_threads < 0 || o.loop_threads > o.threads)
    throw Error("loop_threads must lie in [0, threads] (0: chosen step by step)");
  if (o.solve_threads < 0 || o.solve_threads > o.nlgs.threads)
    throw Error("solve_threads must lie in [0, nlgs.threads] (0: chosen step by step)");
  if (!(o.big_ratio > 1.0)) throw Error("big_ratio must be > 1");
  if (o.residual_check_every < 0) throw Error("residual_check_every must be >= 0 (0: no check)");
  if (!(o.residual_flag > 0.0) || !std::isfinite(o.residual_flag)) throw Error("residual_flag must be > 0 and finite");
  if (!(o.residual_limit >= 0.0) || !std::isfinite(o.residual_limit))
    throw Error("residual_limit must be >= 0 (0: none)");
  reset_thread_choices(o);
  opt_ = o;
  det_.big_ratio = o.big_ratio;
  det_.threads = o.threads;
  // the same solver keeps its buffers; another one is made anew
  const std::string_view name = contact_solver_name(o.solver, o.nlgs);
  if (solver_ && solver_->name() == name) solver_->configure({o.nlgs, o.newton});
  else solver_ = make_contact_solver(name, {o.nlgs, o.newton});
}

// New rounds when the counts to choose among change. Only the colored sweep runs on threads.
// The solve's rounds come first, with the loops on the solve's count: an idle thread spins after
// each parallel region and would slow a one-thread solve beside two-thread loops, and a
// two-thread solve beside one-thread loops fetches half the bodies from the other core. Then the
// loops' rounds, with the solve on its choice, since the loops' cost depends on where the solve
// left the data; until then the loops run on the solve's choice (or their own, if fewer), which
// their rounds try first. The loops' epochs start with the solve's, and a drift in either starts
// both again.
void MoreauJean::reset_thread_choices(const StepperOptions& o) {
  const auto solve_most = [](const StepperOptions& x) {
    return contact_solver_name(x.solver, x.nlgs) == "NLGS_COLORED" ? x.nlgs.threads : 1;
  };
  const bool first = !solver_;
  if (!first && solve_most(o) == solve_most(opt_) && o.threads == opt_.threads &&
      o.solve_threads == opt_.solve_threads && o.loop_threads == opt_.loop_threads)
    return;
  solve_choice_.reset(o.solve_threads == 0 ? solve_most(o) : 1, 0, ThreadChoice::kFavourAsked);
  const bool both = solve_choice_.candidates() > 1;
  loop_choice_.reset(o.loop_threads == 0 ? o.threads : 1, both ? solve_choice_.exploring_steps() : 0);
  if (both) loop_choice_.follow();
}

// The loops' count for this step: the solve's during its rounds, then the solve's choice (or the
// loops' own, if fewer) until the loops' rounds, which it leads.
int MoreauJean::next_loop_threads() {
  if (!loop_choice_.pending()) return loop_choice_.next();
  if (solve_choice_.exploring()) return std::min(solve_choice_.next(), opt_.threads);
  loop_choice_.lead(std::min(solve_choice_.next(), loop_choice_.chosen()));
  return loop_choice_.next();
}

void MoreauJean::require(Phase p, const char* call) const {
  if (phase_ != p)
    throw Error(std::string("MoreauJean::") + call +
                " called out of order (begin_step, detect, prepare, solve, end_step)");
}

void MoreauJean::refuse(const std::string& what, bool dump) {
  phase_ = Phase::Idle;
  std::ostringstream m;
  m.precision(17);
  m << "step " << reg_.step + 1 << " (t = " << reg_.time << " to " << reg_.time + reg_.params.dt
    << " s) refused: " << what
    << ". Positions, velocities, time and warm-start memory are left as at the start of the step";
  if (dump && !opt_.failure_dump.empty()) {
    try {
      write_problem(opt_.failure_dump, sys_.local_problem(), sys_.impulses(false));
      m << "; the step's contact problem is in " << opt_.failure_dump;
    } catch (const std::exception& e) {
      m << "; the contact problem could not be written (" << e.what() << ")";
    }
  }
  throw Error(m.str());
}

void MoreauJean::begin_step() {
  require(Phase::Idle, "begin_step");
  // Refuse bad input before anything is touched, so a refused step changes nothing. The laws
  // are public data a driver may write directly, bypassing set_contact_law's check.
  validate(reg_.params);
  for (const LawSpec& law : reg_.contact_laws.laws) validate(law);
  const auto t0 = Clock::now();
  loops_ = opt_.loop_threads > 0 ? opt_.loop_threads : next_loop_threads();
  if (const std::string bad = check_start_state(reg_, loops_); !bad.empty()) refuse(bad, false);
  report_ = {};
  report_.loop_threads = loops_;
  const double h = reg_.params.dt, theta = reg_.params.theta;
  const BodyTable& b = reg_.bodies;
  const std::size_t n = b.size();
  t_m_ = reg_.time + (1.0 - theta) * h;
  qm_x_.resize(n);
  qm_y_.resize(n);
  qm_a_.resize(n);
  free_.resize(n);
  auto start = [&](std::size_t i, const BodyForce& f) {
    // q_m = q_i + (1 − θ) h u_i
    qm_x_[i] = b.x[i] + (1.0 - theta) * h * b.vx[i];
    qm_y_[i] = b.y[i] + (1.0 - theta) * h * b.vy[i];
    qm_a_[i] = b.angle[i] + (1.0 - theta) * h * b.spin[i];
    // u_free = u_i + h M⁻¹ F(t_m); kinematic dofs have zero inverse mass here
    SolverBody& s = free_[i];
    s.inv_mx = b.inv_mass_x[i];
    s.inv_my = b.inv_mass_y[i];
    s.inv_i = b.inv_inertia[i];
    s.vx = b.vx[i] + h * s.inv_mx * f.fx;
    s.vy = b.vy[i] + h * s.inv_my * f.fy;
    s.w = b.spin[i] + h * s.inv_i * f.m;
  };
  // each body on its own, on the threads; a driven body's force (a time function, which may be
  // a user's callable) on this thread only
  const Vec2 g = reg_.params.gravity;
  each_index(n, light_threads(n, loops_), [&](std::size_t i) {
    if (!b.is_driven[i]) start(i, BodyForce{b.mass[i] * g.x, b.mass[i] * g.y, 0.0});  // external_force's
  });
  for (std::size_t i = 0; i < n; ++i)
    if (b.is_driven[i]) start(i, external_force(reg_, BodyId(static_cast<std::uint32_t>(i)), t_m_));
  // imposed velocities take their end-of-step value, fixed dofs 0
  const double t_f = reg_.time + h;
  for (const DofDrive& d : b.drives) {
    if (d.drive != Drive::Fixed && d.drive != Drive::Velocity) continue;
    const double v = d.drive == Drive::Fixed ? 0.0 : d.value(t_f);
    SolverBody& s = free_[d.body.index()];
    (d.dof == Dof::X ? s.vx : d.dof == Dof::Y ? s.vy : s.w) = v;
  }
  if (const std::string bad = check_free_state(reg_, qm_x_, qm_y_, qm_a_, free_, t_m_, loops_); !bad.empty())
    refuse(bad, false);
  report_.step_seconds = begin_seconds_ = seconds_since(t0);
  phase_ = Phase::Begun;
}

void MoreauJean::detect() {
  require(Phase::Begun, "detect");
  const auto t0 = Clock::now();
  if (reg_.polyg.size() + reg_.diskx.size() != det_.classified_count) {
    classify_big_polygons(reg_, det_.big_ratio);
    det_.classified_count = reg_.polyg.size() + reg_.diskx.size();
  }
  det_.threads = loops_;
  report_.detection = detect_plplx(reg_, det_, Configuration{qm_x_, qm_y_, qm_a_});
  report_.contacts = reg_.contacts.size();
  // spring links: frames at q_m
  Ptpt2Table& links = reg_.links;
  for (std::uint32_t k = 0; k < links.size(); ++k) {
    const LinkFrame f = link_frame(reg_, LinkId(k), qm_x_, qm_y_, qm_a_);
    links.length[k] = f.length;
    links.normal[k] = f.n;
  }
  report_.detect_seconds = seconds_since(t0);
  phase_ = Phase::Detected;
}

void MoreauJean::prepare() {
  require(Phase::Detected, "prepare");
  const auto t0 = Clock::now();
  // the solver's bodies start from u_free (the links condensed into it); copied on the threads
  // from kLightParallelMin bodies on
  const int copy_threads = light_threads(free_.size(), loops_);
  copy_on_threads(sys_.bodies, free_, copy_threads);
  prepare_links();
  copy_on_threads(sys_.free, sys_.bodies, copy_threads);
  copy_on_threads(sys_.body_x, qm_x_, copy_threads);
  copy_on_threads(sys_.body_y, qm_y_, copy_threads);
  build_contacts();
  // 3. Iterated links start from their last impulse.
  const double h = reg_.params.dt;
  for (SolverLink& l : sys_.links) {
    l.w = link_delassus(l, sys_.free[l.cd], sys_.free[l.an]);
    l.p = opt_.warm_start ? reg_.links.rn[l.row] * h : 0.0;
    if (l.p != 0.0) apply_link_impulse(l, sys_.bodies[l.cd], sys_.bodies[l.an], l.p);
  }
  if (opt_.warm_start && !previous_.empty()) warm_start_contacts();
  // 5. The solver lays the system out in its own order now (the colored sweep: blocks colour by
  //    colour), so that the step's problem reads the same before and after the solve.
  solver_->prepare(sys_, loops_);
  report_.prepare_seconds = seconds_since(t0);
  report_.step_seconds += report_.prepare_seconds;
  phase_ = Phase::Prepared;
}

void MoreauJean::solve() {
  require(Phase::Prepared, "solve");
  const auto t0 = Clock::now();
  report_.solver = opt_.solver;
  const int threads = opt_.solve_threads > 0 ? opt_.solve_threads : solve_choice_.next();
  solver_->solve(sys_, threads);
  report_.solve_threads = threads;
  const SolveReport& r = solver_->report();
  report_.sweeps = r.sweeps;
  report_.mixes = r.mixes;
  report_.mix_returns = r.mix_returns;
  report_.converged = r.converged;
  report_.criteria = r.criteria;
  report_.residual = r.residual;
  report_.line_search_steps = r.line_search_steps;
  report_.presweeps = r.presweeps;
  report_.factorizations = r.factorizations;
  report_.factor_seconds = r.factor_seconds;
  report_.solve_parts = r.parts;
  if (solver_->reports_residual()) {
    report_.residual_checked = report_.residual >= 0.0;
  } else if (const int every = opt_.residual_check_every; every > 0 && (reg_.step + 1) % every == 0) {
    // the independent check (reads only): natural-map residual over ‖q‖ every N steps
    report_.residual = natural_map_error(sys_.local_problem(), sys_.impulses(false)).relative_q;
    report_.residual_checked = true;
  }
  report_.false_converged = report_.residual_checked && report_.converged && !(report_.residual <= opt_.residual_flag);
  report_.solve_seconds = seconds_since(t0);
  // what the solve's threads changed: the time a sweep and a contact (the sweeps are the same on
  // any count; a growing system's steps are then alike, and only the machine's drift is a drift)
  if (opt_.solve_threads == 0)
    solve_choice_.record(report_.solve_seconds / (std::max(report_.sweeps, 1) * (sys_.contacts.size() + 1.0)),
                         static_cast<double>(sys_.contacts.size()));
  phase_ = Phase::Solved;
}

void MoreauJean::end_step() {
  require(Phase::Solved, "end_step");
  const auto t0 = Clock::now();
  const double h = reg_.params.dt;
  guard_solution();
  project_overlaps();
  // forces back into the registry, end-of-step gaps, the warm-start memory, and the work of
  // the impulses over the step: P·U_θ, U_θ = (1 − θ) U⁻ + θ U⁺ (docs/theory.md §7.1)
  const ContactSums sums = finish_contacts();
  previous_index_.build(previous_, light_threads(previous_.size(), loops_));
  const double damper = finish_links();
  advance_bodies();
  report_.contact_dissipation = -sums.work;
  report_.damper_dissipation = damper;
  report_.mean_overlap = sums.overlaps ? sums.overlap / static_cast<double>(sums.overlaps) : 0.0;
  report_.total_overlap = sums.overlap;
  reg_.time += h;
  ++reg_.step;
  report_.step = reg_.step;
  report_.time = reg_.time;
  report_.end_seconds = seconds_since(t0);
  report_.step_seconds += report_.end_seconds;
  // what the loops' threads changed: the step but its solve, a body or contact
  if (opt_.loop_threads == 0)
    loop_choice_.record((begin_seconds_ + report_.detect_seconds + report_.prepare_seconds + report_.end_seconds) /
                        (reg_.bodies.size() + sys_.contacts.size() + 1.0),
                        static_cast<double>(sys_.contacts.size()));
  if (loop_choice_.restarted()) solve_choice_.restart();
  if (solve_choice_.began() && !loop_choice_.restarted()) loop_choice_.restart(solve_choice_.restarted());
  phase_ = Phase::Idle;
}

void MoreauJean::guard_solution() {
  const double h = reg_.params.dt, theta = reg_.params.theta;
  // the guard: nothing is written unless the step is finite (and within the options' limits)
  if (const std::string bad = check_solution(reg_, sys_, qm_x_, qm_y_, qm_a_, h, theta, loops_); !bad.empty())
    refuse(bad, true);
  const AlertTravel travel = alert_travel(reg_, sys_.bodies, h, loops_);
  report_.alert_skips = travel.skips;
  report_.max_travel = travel.max_travel;
  report_.fastest_body = travel.fastest;
  report_.position_resolution = travel.resolution;
  report_.coarse_positions = travel.resolution > 1e-3 * reg_.params.alert && reg_.params.alert > 0.0;
  if (opt_.strict_alert && travel.skips > 0) {
    std::ostringstream m;
    m.precision(6);
    m << travel.skips << " polygon(s) travel farther than the alert distance " << reg_.params.alert << " m, body "
      << body_label(reg_, static_cast<std::size_t>(travel.fastest)) << " by " << travel.max_travel
      << " m: contacts can be missed (strict_alert; keep h * fastest speed below the alert distance, docs/theory.md)";
    refuse(m.str(), true);
  }
  if (opt_.residual_limit > 0.0 && report_.residual_checked && !(report_.residual <= opt_.residual_limit)) {
    std::ostringstream m;
    m.precision(6);
    m << "natural-map residual / |q| = " << report_.residual << " above residual_limit " << opt_.residual_limit
      << " (the solver reported " << (report_.converged ? "converged" : "not converged") << " after " << report_.sweeps
      << (opt_.solver == SolverKind::NLGS ? " sweeps)" : " iterations)");
    refuse(m.str(), true);
  }
}

// A contact's own figures at the end of a step, from its record and its bodies only: forces and
// status into its row, the work of its impulse, its end gap, and what the warm start will
// remember of it (forces zero: nothing). The registry still holds u_i here (u_f is written
// after): the start-of-step velocity U⁻ = H* u_i of a contact, in the frame of the step, for the
// work of its impulse.
inline __attribute__((always_inline)) MoreauJean::ContactEnd MoreauJean::end_of_contact(std::size_t a) {
  const double h = reg_.params.dt, theta = reg_.params.theta;
  const BodyTable& b = reg_.bodies;
  ContactTable& c = reg_.contacts;
  auto u_begin = [&b](std::uint32_t i) { return SolverBody{b.vx[i], b.vy[i], b.spin[i]}; };
  const SolverContact& s = sys_.contacts[a];
  const std::uint32_t row = sys_.rows[a];
  const double rn = s.pn / h, rt = s.pt / h;
  c.rn[row] = rn;
  c.rt[row] = rt;
  c.status[row] = s.pn > 0.0 ? sys_.status[a] : ContactStatus::Open;
  double un, ut;
  contact_velocity(s, sys_.bodies[s.cd], sys_.bodies[s.an], un, ut);
  double work = 0.0;
  if (s.pn != 0.0 || s.pt != 0.0) {
    double un0, ut0;
    contact_velocity(s, u_begin(s.cd), u_begin(s.an), un0, ut0);
    work = s.pn * ((1.0 - theta) * un0 + theta * un) + s.pt * ((1.0 - theta) * ut0 + theta * ut);
  }
  const double g_f = c.gap[row] + theta * h * un + projection_.normal_shift(sys_, a);
  ContactEnd e{work, g_f, {0, 0, rn, rt}, s.pn > 0.0, s.pn != 0.0 || s.pt != 0.0};
  if (e.remembered) {  // its key, read only then
    e.memory.pair = contact_pair_key(c.candidate[row], c.antagonist[row]);
    e.memory.feature = c.feature[row];
  }
  return e;
}

// Every contact's end_of_contact; the sums, block by block of kEndBlock contacts and then the
// blocks in order (the same sums for any threads); the warm-start memory in the contacts' order.
MoreauJean::ContactSums MoreauJean::finish_contacts() {
  const std::size_t nc = sys_.contacts.size(), blocks = (nc + kEndBlock - 1) / kEndBlock;
  end_blocks_.resize(blocks);  // (each block stored whole below)
  auto block_sums = [&](std::size_t k, auto&& each) {
    ContactSums s;  // (stored once: two threads' blocks may share a cache line)
    for (std::size_t a = k * kEndBlock; a < std::min(nc, (k + 1) * kEndBlock); ++a) s.add(each(a));
    end_blocks_[k] = s;
  };
  previous_.clear();
  if (const int threads = light_threads(nc, loops_); threads > 1) {
    // on the threads, each a range of whole blocks: the contacts' ends into end_own_ and the
    // blocks' sums, then the memory written from each thread's first row (as ordered_fill does)
    end_own_.resize(nc);
    ContactEnd* out = end_own_.data();
    std::vector<std::size_t>& first = end_first_;
    first.assign(static_cast<std::size_t>(threads) + 1, 0);
#pragma omp parallel num_threads(threads)
    {
      const auto [k0, k1] = thread_range(blocks);
      const std::size_t t = thread_index(), a0 = std::min(nc, k0 * kEndBlock), a1 = std::min(nc, k1 * kEndBlock);
      auto end_into_out = [&](std::size_t a) -> const ContactEnd& { return out[a] = end_of_contact(a); };
      for (std::size_t k = k0; k < k1; ++k) block_sums(k, end_into_out);
      std::size_t kept = 0;
      for (std::size_t k = k0; k < k1; ++k) kept += end_blocks_[k].remembered;
      first[t + 1] = kept;
#pragma omp barrier
#pragma omp single
      {
        for (std::size_t u = 0; u + 1 < first.size(); ++u) first[u + 1] += first[u];
        previous_.resize(first.back());
      }
      std::size_t at = first[t];
      for (std::size_t a = a0; a < a1; ++a)
        if (out[a].remembered) previous_[at++] = out[a].memory;
    }
  } else {
    for (std::size_t k = 0; k < blocks; ++k)
      block_sums(k, [&](std::size_t a) {
        const ContactEnd e = end_of_contact(a);
        if (e.remembered) previous_.push_back(e.memory);
        return e;
      });
  }
  ContactSums sums;
  for (const ContactSums& s : end_blocks_) sums.merge(s);
  report_.active += sums.active;
  report_.max_overlap = std::max(report_.max_overlap, sums.max_overlap);
  return sums;
}

double MoreauJean::finish_links() {
  const double h = reg_.params.dt, theta = reg_.params.theta;
  const BodyTable& b = reg_.bodies;
  const std::vector<SolverBody>& bodies_ = sys_.bodies;
  auto u_begin = [&b](std::uint32_t i) { return SolverBody{b.vx[i], b.vy[i], b.spin[i]}; };
  // springs: the force, and the work of the viscous part −h ν U⁺ of the impulse over the step
  double damper = 0.0;
  auto damper_work = [&](const SolverLink& l, double u_end) {
    const double nu = reg_.links.law[l.row].nu;
    if (nu != 0.0)
      damper += h * nu * u_end * ((1.0 - theta) * link_velocity(l, u_begin(l.cd), u_begin(l.an)) + theta * u_end);
  };
  for (const SolverLink& l : sys_.links) {
    reg_.links.rn[l.row] = l.p / h;
    damper_work(l, link_velocity(l, bodies_[l.cd], bodies_[l.an]));
  }
  for (const SolverLink& l : sys_.condensed) {  // P = h a − h b U at the final velocities
    const double u_end = link_velocity(l, bodies_[l.cd], bodies_[l.an]);
    reg_.links.rn[l.row] = (l.law.ha - l.law.hb * u_end) / h;
    damper_work(l, u_end);
  }
  return damper;
}

void MoreauJean::advance_bodies() {
  const double h = reg_.params.dt, theta = reg_.params.theta;
  BodyTable& b = reg_.bodies;
  // q_f = q_m + θ h u_f (+ Δq, the projection's correction); each body on its own, on the threads
  const bool moved = projection_.moved();
  each_index(b.size(), light_threads(b.size(), loops_), [&](std::size_t i) {
    const SolverBody& s = sys_.bodies[i];
    b.vx[i] = s.vx;
    b.vy[i] = s.vy;
    b.spin[i] = s.w;
    b.x[i] = qm_x_[i] + theta * h * s.vx;
    b.y[i] = qm_y_[i] + theta * h * s.vy;
    b.angle[i] = qm_a_[i] + theta * h * s.w;
    if (!moved) return;
    const SolverBody& d = projection_.shift(i);
    b.x[i] += d.vx;
    b.y[i] += d.vy;
    b.angle[i] += d.w;
  });
}

void MoreauJean::project_overlaps() {
  const ProjectionOptions& o = opt_.projection;
  if (!o.enabled) {
    projection_.reset();
    return;
  }
  gaps_.resize(sys_.contacts.size());
  each_index(gaps_.size(), light_threads(gaps_.size(), loops_),
             [&](std::size_t a) { gaps_[a] = reg_.contacts.gap[sys_.rows[a]]; });
  const ProjectionReport r = projection_.project(sys_, gaps_, reg_.params.dt, reg_.params.theta,
                                                 o.slop * reg_.params.alert, o, loops_, solver_->colors(sys_));
  report_.projection_sweeps = r.sweeps;
  report_.projected = r.beyond;
  report_.projection_excess = r.max_excess;
  report_.projection_shift = r.max_shift;
}

StepReport MoreauJean::step() {
  const auto t0 = Clock::now();
  begin_step();
  detect();
  prepare();
  solve();
  end_step();
  report_.step_seconds = seconds_since(t0);
  return report_;
}

FrictionProblem2D MoreauJean::local_problem() const {
  if (phase_ != Phase::Prepared && phase_ != Phase::Solved)
    throw Error("MoreauJean::local_problem: call after prepare()");
  return sys_.local_problem();
}

void MoreauJean::set_warm_start_memory(ContactHistory m) {
  previous_ = std::move(m);
  previous_index_.build(previous_);
}

ContactHistory MoreauJean::warm_start_memory() const {
  ContactHistory sorted = previous_;
  std::sort(sorted.begin(), sorted.end());
  return sorted;
}

std::vector<double> MoreauJean::impulses() const {
  return sys_.impulses(false);
}

}  // namespace nscd
