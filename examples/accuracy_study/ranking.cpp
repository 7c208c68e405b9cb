// examples/accuracy_study/ranking.cpp — two studies' rankings of the same settings compared
// (see ranking.hpp).
#include "ranking.hpp"
#include "table.hpp"
#include "../study_common/plan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace accuracy {

namespace fs = std::filesystem;

const std::vector<std::string>& ranked_measures() {
  static const std::vector<std::string> m = {"cpu_per_cycle",    "mean_iterations", "unconverged_steps", "mean_overlap",
                                             "max_overlap",      "cumulated_overlap", "settlement_error"};
  return m;
}

namespace {

double to_number(const std::string& s) {
  if (s == "nan" || s.empty()) return std::nan("");
  std::size_t used = 0;
  try {
    const double v = std::stod(s, &used);
    return used == s.size() ? v : std::nan("");
  } catch (const std::exception&) {
    return std::nan("");
  }
}

// Each row of a CSV file with a header, as column → text; the first column keys the row.
std::map<std::string, std::map<std::string, std::string>> read_csv(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file.string() + " (is it a finished study's folder?)");
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = study::csv_cells(line);
  std::map<std::string, std::map<std::string, std::string>> rows;
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    const std::vector<std::string> f = study::csv_cells(line);
    if (f.size() != header.size())
      throw std::runtime_error(file.string() + ":" + std::to_string(n) + ": " + std::to_string(f.size()) + " fields, the header has " +
                               std::to_string(header.size()));
    for (std::size_t i = 0; i < f.size(); ++i) rows[f[0]][header[i]] = f[i];
  }
  return rows;
}

// Ranks 1..n, ties given the mean of the ranks they span.
std::vector<double> ranks(const std::vector<double>& v) {
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  std::vector<double> r(v.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
    for (std::size_t k = i; k <= j; ++k) r[order[k]] = 0.5 * double(i + j) + 1.0;
    i = j + 1;
  }
  return r;
}

}  // namespace

StudyMeasures read_study(const fs::path& dir) {
  const auto table = read_csv(dir / "table.csv");
  const auto trade = read_csv(dir / "trade.csv");
  StudyMeasures out;
  for (const auto& [label, cols] : table) {
    const auto t = trade.find(label);
    Measures& m = out[label];
    for (const std::string& name : ranked_measures()) {
      std::string text;  // from table.csv, else trade.csv; "" (NaN) in neither
      if (const auto it = cols.find(name); it != cols.end())
        text = it->second;
      else if (t != trade.end())
        if (const auto jt = t->second.find(name); jt != t->second.end()) text = jt->second;
      m.value[name] = to_number(text);
    }
    if (t != trade.end() && t->second.count("within_spread") && std::isfinite(m.value["settlement_error"]))
      m.within_spread = t->second.at("within_spread") == "1" ? 1 : 0;
  }
  return out;
}

double spearman(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size() || a.size() < 3) return std::nan("");
  const std::vector<double> ra = ranks(a), rb = ranks(b);
  const double mean = 0.5 * double(a.size() + 1);
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (ra[i] - mean) * (rb[i] - mean);
    saa += (ra[i] - mean) * (ra[i] - mean);
    sbb += (rb[i] - mean) * (rb[i] - mean);
  }
  if (saa == 0.0 || sbb == 0.0) return std::nan("");
  return sab / std::sqrt(saa * sbb);
}

PairOrder pair_order(const std::vector<double>& a, const std::vector<double>& b) {
  PairOrder p;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = i + 1; j < a.size() && j < b.size(); ++j) {
      if (a[i] == a[j] || b[i] == b[j]) continue;
      ++p.comparable;
      if ((a[i] < a[j]) == (b[i] < b[j])) ++p.same;
    }
  return p;
}

int RankComparison::verdicts_same() const {
  int n = 0;
  for (const Verdict& v : verdicts) n += (v.here >= 0 && v.here == v.other) ? 1 : 0;
  return n;
}

RankComparison compare_rankings(const std::vector<Setting>& settings, const StudyMeasures& here, const StudyMeasures& other) {
  // the groups, each a list of labels in the settings' order (the reference row is in study 1 and
  // is study 2's dt 2e-4 vertical row)
  std::vector<std::pair<std::string, std::vector<std::string>>> groups;
  const auto add = [&](const std::string& group, const std::string& label) {
    auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first == group; });
    if (it == groups.end()) it = groups.insert(groups.end(), {group, {}});
    it->second.push_back(label);
  };
  const auto any = [&](Role r) { return std::any_of(settings.begin(), settings.end(), [r](const Setting& s) { return s.role == r; }); };
  const bool has_criteria = any(Role::criterion), has_steps = any(Role::step);
  for (const Setting& s : settings) {
    switch (s.role) {
      case Role::spread: break;  // the spread, not a setting
      case Role::criterion: add("study 1 (criterion)", s.label); break;
      case Role::reference:
        if (has_criteria) add("study 1 (criterion)", s.label);
        if (has_steps) add("study 2, vertical", s.label);
        break;
      case Role::step: add(s.inclination == 0.0 ? "study 2, vertical" : "study 2, inclined 5°", s.label); break;
    }
  }
  RankComparison out;
  for (const auto& [group, labels] : groups) {
    for (const std::string& measure : ranked_measures()) {
      std::vector<double> a, b;
      for (const std::string& label : labels) {
        const auto h = here.find(label), o = other.find(label);
        if (h == here.end() || o == other.end()) continue;
        const double x = h->second.value.at(measure), y = o->second.value.at(measure);
        if (!std::isfinite(x) || !std::isfinite(y)) continue;
        a.push_back(x);
        b.push_back(y);
      }
      out.agreements.push_back({group, measure, static_cast<int>(a.size()), spearman(a, b), pair_order(a, b)});
    }
  }
  for (const Setting& s : settings) {
    if (s.role == Role::spread) continue;
    const auto h = here.find(s.label), o = other.find(s.label);
    if (h == here.end() || o == other.end()) continue;
    out.verdicts.push_back({s.label, h->second.within_spread, o->second.within_spread});
  }
  return out;
}

void write_ranking(const fs::path& file, const RankComparison& c) {
  std::ofstream out(file);
  out << "group,measure,settings,spearman,pairs_same,pairs_comparable\n";
  for (const RankAgreement& a : c.agreements)
    out << a.group << ',' << a.measure << ',' << a.settings << ',' << (std::isfinite(a.spearman) ? fixed(a.spearman, "%.4f") : "nan")
        << ',' << a.pairs.same << ',' << a.pairs.comparable << '\n';
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

std::string ranking_section(const RankComparison& c, const std::string& other_name) {
  std::ostringstream o;
  o << "## Ranking against " << other_name << "\n\n"
    << "Each group's settings ranked by each measure in this study and in that one: Spearman's rank correlation (1: the "
       "same order) and the pairs of settings put in the same order, of the pairs without a tie in either "
       "(`ranking.csv`). Settings without a finite value in both are left out.\n\n"
    << "| group | measure | settings | Spearman | pairs in the same order |\n|---|---|---|---|---|\n";
  for (const RankAgreement& a : c.agreements)
    o << "| " << a.group << " | " << a.measure << " | " << a.settings << " | " << fixed(a.spearman, "%.3f") << " | " << a.pairs.same
      << " / " << a.pairs.comparable << " |\n";
  int known = 0;
  for (const Verdict& v : c.verdicts) known += (v.here >= 0 && v.other >= 0) ? 1 : 0;
  o << "\n**Within the spread between samples:** the same verdict for " << c.verdicts_same() << " of " << known
    << " settings known in both";
  std::string differ;
  for (const Verdict& v : c.verdicts)
    if (v.here >= 0 && v.other >= 0 && v.here != v.other)
      differ += (differ.empty() ? "" : ", ") + v.setting + " (" + (v.here ? "within" : "outside") + " here)";
  o << (differ.empty() ? "." : "; they differ on " + differ + ".") << "\n\n";
  return o.str();
}

}  // namespace accuracy
