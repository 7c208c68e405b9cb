// examples/accuracy_study/settings.cpp — the lists of settings of the accuracy studies (see
// settings.hpp). The tolerances are the paper's (§3.2); nscd's policies are the LMGC90 measures
// closest to the paper's words (docs/theory.md §9.3), so equal numbers need not mean equal work.
#include "settings.hpp"

#include <algorithm>
#include <charconv>
#include <set>
#include <stdexcept>

namespace accuracy {

Study parse_study(const std::string& s) {
  if (s == "criterion") return Study::criterion;
  if (s == "step") return Study::step;
  if (s == "trade") return Study::trade;
  throw std::invalid_argument("--study must be criterion, step or trade, got '" + s + "'");
}

const char* study_name(Study s) {
  switch (s) {
    case Study::criterion: return "criterion";
    case Study::step: return "step";
    case Study::trade: return "trade";
  }
  return "?";
}

const char* role_name(Role r) {
  switch (r) {
    case Role::criterion: return "criterion";
    case Role::reference: return "reference";
    case Role::spread: return "spread";
    case Role::step: return "step";
  }
  return "?";
}

std::string number_text(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general);
  return std::string(buf, r.ptr);
}

Setting reference_setting(std::uint64_t seed) {
  Setting s;
  s.label = "NonStrict 1.666e-4 (reference)";
  s.role = Role::reference;
  s.seed = seed;
  return s;
}

const std::vector<double>& step_lengths() {
  static const std::vector<double> dts = {1e-4, 1.25e-4, 2e-4, 2.5e-4, 3.125e-4, 4e-4, 5e-4, 6.25e-4, 7.8125e-4, 1e-3};
  return dts;
}

namespace {

Setting nlgs(const std::string& label, const std::string& policy, double tol, std::uint64_t seed, int min_sweeps = 0) {
  Setting s;
  s.label = label;
  s.policy = policy;
  s.tol = tol;
  s.min_sweeps = min_sweeps;
  s.seed = seed;
  return s;
}

Setting newton(const std::string& label, double tol, std::uint64_t seed) {
  Setting s;
  s.label = label;
  s.solver = "NEWTON_AC";
  s.policy = "-";
  s.tol = tol;
  s.newton_presweeps = kNewtonPresweeps;
  s.newton_presweep_tol = kNewtonPresweepTol;
  s.seed = seed;
  return s;
}

// The reference setting on the other samples (seed + 1 …): the spread between samples.
void add_spread(std::vector<Setting>& v, std::uint64_t seed, int samples) {
  for (int i = 1; i < samples; ++i) {
    Setting s = reference_setting(seed + std::uint64_t(i));
    s.label = "reference sample " + std::to_string(seed + std::uint64_t(i));
    s.role = Role::spread;
    v.push_back(s);
  }
}

std::vector<Setting> criterion(std::uint64_t seed, int samples) {
  std::vector<Setting> v = {
      nlgs("Energy 1.66e-3", "Energy", 1.66e-3, seed),
      nlgs("Energy 1.66e-4", "Energy", 1.66e-4, seed),
      nlgs("Energy 1.66e-5", "Energy", 1.66e-5, seed),
      nlgs("Strict 1e-4", "Strict", 1e-4, seed),
      nlgs("Strict 1e-5", "Strict", 1e-5, seed),
      nlgs("NonStrict 1e-5", "NonStrict", 1e-5, seed),
      nlgs("NonStrict 1e-6", "NonStrict", 1e-6, seed),
      nlgs("NonStrict 1e-7", "NonStrict", 1e-7, seed),
      reference_setting(seed),
      nlgs("NonStrict 1.666e-4 min " + std::to_string(kMinSweepsVariant), "NonStrict", 1.666e-4, seed, kMinSweepsVariant),
      newton("NEWTON_AC 1e-6", 1e-6, seed),
      newton("NEWTON_AC 1e-8", 1e-8, seed),
  };
  add_spread(v, seed, samples);
  return v;
}

std::vector<Setting> step(std::uint64_t seed, int samples) {
  std::vector<Setting> v;
  for (double inclination : {0.0, 5.0})
    for (double dt : step_lengths()) {
      Setting s = reference_setting(seed);
      s.role = Role::step;
      s.dt = dt;
      s.inclination = inclination;
      s.label = "dt " + number_text(dt) + (inclination == 0.0 ? " vertical" : " inclined " + number_text(inclination));
      v.push_back(s);
    }
  add_spread(v, seed, samples);
  return v;
}

}  // namespace

std::vector<std::string> parse_solvers(const std::string& list) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = list.find(',', start);
    const std::string item = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (item != "NLGS" && item != "NEWTON_AC")
      throw std::invalid_argument("--solvers: '" + item + "' is not a solver (NLGS, NEWTON_AC, comma-separated)");
    if (std::find(out.begin(), out.end(), item) != out.end()) throw std::invalid_argument("--solvers: " + item + " given twice");
    out.push_back(item);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

std::vector<Setting> keep_solvers(const std::vector<Setting>& settings, const std::vector<std::string>& solvers) {
  std::vector<Setting> out;
  for (const Setting& s : settings)  // the reference, spread and step rows are the study's frame: always kept
    if (s.role != Role::criterion || std::find(solvers.begin(), solvers.end(), s.solver) != solvers.end()) out.push_back(s);
  return out;
}

std::vector<Setting> settings_of(Study s, std::uint64_t seed, int samples) {
  if (samples < 1) throw std::invalid_argument("--samples must be >= 1");
  if (s == Study::criterion) return criterion(seed, samples);
  if (s == Study::step) return step(seed, samples);
  // trade: study 1's rows, then study 2's that are not already there (its dt 2e-4 vertical run
  // is study 1's reference run, its spread runs study 1's)
  std::vector<Setting> v = criterion(seed, samples);
  std::set<std::string> names;
  for (const Setting& x : v) names.insert(run_name(x));
  for (const Setting& x : step(seed, samples))
    if (names.insert(run_name(x)).second) v.push_back(x);
  return v;
}

std::string run_name(const Setting& s) {
  std::string n = s.solver == "NEWTON_AC" ? "newton_" + number_text(s.tol) : s.policy + "_" + number_text(s.tol);
  if (s.solver == "NEWTON_AC" && s.newton_presweeps > 0)
    n += "_ps" + std::to_string(s.newton_presweeps) + "_pt" + number_text(s.newton_presweep_tol);
  if (s.min_sweeps > 0) n += "_min" + std::to_string(s.min_sweeps);
  n += "_dt" + number_text(s.dt) + "_inc" + number_text(s.inclination) + "_s" + std::to_string(s.seed);
  for (char& c : n)
    if (c == '/' || c == ' ') c = '_';
  return n;
}

std::vector<std::string> run_arguments(const Setting& s) {
  std::vector<std::string> a = {"--solver", s.solver, "--dt", number_text(s.dt), "--inclination", number_text(s.inclination)};
  if (s.solver == "NEWTON_AC") {
    a.insert(a.end(), {"--newton-tol", number_text(s.tol)});
    if (s.newton_presweeps > 0)
      a.insert(a.end(), {"--newton-presweeps", std::to_string(s.newton_presweeps), "--newton-presweep-tol",
                         number_text(s.newton_presweep_tol)});
  } else {
    a.insert(a.end(), {"--policy", s.policy, "--tol", number_text(s.tol)});
    if (s.min_sweeps > 0) a.insert(a.end(), {"--min-sweeps", std::to_string(s.min_sweeps)});
  }
  return a;
}

}  // namespace accuracy
