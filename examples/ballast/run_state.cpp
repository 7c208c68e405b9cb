// examples/ballast/run_state.cpp — a ballast run's state in its checkpoints, and what a resumed
// or continued run takes up again: see run_state.hpp.
#include "run_state.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "nscd/core/error.hpp"
#include "nscd/io/atomic_file.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/io/text_reader.hpp"

namespace fs = std::filesystem;
using namespace nscd;

namespace ballast {
namespace {

bool has_line(const fs::path& file, const std::string& line) {
  std::ifstream in(file);
  for (std::string l; std::getline(in, l);)
    if (l == line) return true;
  return false;
}

std::string hex(double v) {
  std::ostringstream s;
  s << std::hexfloat << v;
  return s.str();
}

}  // namespace

const std::map<std::string, std::string> kBeforeTheOption = {
    {"order", "fixed"}, {"relaxation", "1"}, {"anderson", "0"}, {"projection", "0"}};

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

}  // namespace ballast
