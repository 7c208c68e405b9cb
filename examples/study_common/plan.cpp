// examples/study_common/plan.cpp — the plan files, the manifest, GNU parallel's joblog and the
// state of each task (see plan.hpp).
#include "plan.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace fs = std::filesystem;

namespace study {
namespace {

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

void write_file(const fs::path& f, const std::string& text) {
  std::ofstream out(f, std::ios::trunc);
  out << text;
  if (!out.flush()) throw std::runtime_error("cannot write " + f.string());
}

std::string last_line(const fs::path& log) {
  std::ifstream in(log, std::ios::binary);
  if (!in) return "";
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg(), from = std::max<std::streamoff>(0, size - 4096);
  in.seekg(from);
  std::string s(static_cast<std::size_t>(size - from), '\0');
  in.read(s.data(), static_cast<std::streamsize>(s.size()));
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  const auto nl = s.find_last_of('\n');
  return nl == std::string::npos ? s : s.substr(nl + 1);
}

// Complete data rows of a cycles.csv (a row cut short by a kill has no end of line).
int complete_rows(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  int n = -1;  // the header
  while (std::getline(in, line))
    if (!in.eof() && !line.empty()) ++n;
  return std::max(n, 0);
}

std::string summary_result(const fs::path& summary) {
  std::ifstream in(summary);
  for (std::string l; std::getline(in, l);)
    if (l.rfind("result = ", 0) == 0) return l.substr(9);
  return "";
}

std::string exit_text(const JoblogEntry& e) {
  if (e.signal != 0) return "killed by signal " + std::to_string(e.signal);
  return "exit status " + std::to_string(e.exit_value);
}

}  // namespace

std::vector<std::string> csv_cells(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (quoted) {
      if (ch == '"' && i + 1 < line.size() && line[i + 1] == '"') cells.back() += '"', ++i;
      else if (ch == '"') quoted = false;
      else cells.back() += ch;
    } else if (ch == '"') quoted = true;
    else if (ch == ',') cells.emplace_back();
    else if (ch != '\r') cells.back() += ch;
  }
  return cells;
}

std::string shell_quote(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-+=./:,@%") == std::string::npos)
    return s;
  std::string q = "'";
  for (char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

std::string command_line(const Job& j) {
  std::string s = "mkdir -p " + shell_quote(j.folder.string()) + " && exec";
  for (const std::string& a : j.argv) s += " " + shell_quote(a);
  return s + (j.append_log ? " >> " : " > ") + shell_quote((j.folder / "log.txt").string()) + " 2>&1";
}

void write_plan(const Plan& p) {
  std::error_code ec;
  fs::create_directories(p.dir, ec);
  if (ec) throw std::runtime_error("cannot create the study folder " + p.dir.string() + ": " + ec.message());
  std::string prepare, runs, manifest = "phase,task,name";
  for (const std::string& c : p.columns) manifest += "," + c;
  manifest += ",cycles,needs,output,command\n";
  const auto add = [&](const std::vector<Job>& jobs, const char* phase, std::string& file) {
    int task = 0;
    for (const Job& j : jobs) {
      if (j.values.size() != p.columns.size()) throw std::logic_error("job " + j.name + ": not one value per manifest column");
      const std::string line = command_line(j);
      file += line + "\n";
      manifest += std::string(phase) + "," + std::to_string(++task) + "," + csv_field(j.name);
      for (const std::string& v : j.values) manifest += "," + csv_field(v);
      manifest += "," + std::to_string(j.cycles) + "," + csv_field(j.needs) + "," + csv_field(j.folder.string()) + "," + csv_field(line) + "\n";
    }
  };
  add(p.prepare, "prepare", prepare);
  add(p.runs, "run", runs);
  // GNU parallel's --resume-failed finds the tasks of its joblog by line number: a joblog of
  // other plan lines would skip the wrong tasks
  for (const auto& [file, text, joblog] : {std::tuple{"prepare.txt", &prepare, "joblog_prepare.txt"}, std::tuple{"commands.txt", &runs, "joblog.txt"}}) {
    std::ifstream in(p.dir / file);
    if (in && std::string(std::istreambuf_iterator<char>(in), {}) != *text) fs::remove(p.dir / joblog, ec);
  }
  write_file(p.dir / "prepare.txt", prepare);
  write_file(p.dir / "commands.txt", runs);
  write_file(p.dir / "manifest.csv", manifest);
}

const std::string& ManifestRow::at(const std::string& column) const {
  const auto it = cell.find(column);
  if (it == cell.end()) throw std::runtime_error("manifest.csv has no column '" + column + "'");
  return it->second;
}

std::vector<ManifestRow> read_manifest(const fs::path& dir) {
  const fs::path file = dir / "manifest.csv";
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file.string() + " (write the plan first: --plan-only --output " + dir.string() + ")");
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(file.string() + " is empty");
  const std::vector<std::string> header = csv_cells(line);
  for (const char* need : {"phase", "task", "name", "cycles", "needs", "output", "command"})
    if (std::find(header.begin(), header.end(), need) == header.end())
      throw std::runtime_error(file.string() + " has no column '" + need + "': not a study manifest");
  std::vector<ManifestRow> rows;
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = csv_cells(line);
    if (cells.size() != header.size())
      throw std::runtime_error(file.string() + ":" + std::to_string(n) + ": " + std::to_string(cells.size()) + " cells, the header has " +
                               std::to_string(header.size()));
    ManifestRow r;
    for (std::size_t i = 0; i < header.size(); ++i) r.cell[header[i]] = cells[i];
    if (r.at("phase") != "prepare" && r.at("phase") != "run")
      throw std::runtime_error(file.string() + ":" + std::to_string(n) + ": phase '" + r.at("phase") + "' is not prepare or run");
    rows.push_back(std::move(r));
  }
  return rows;
}

std::map<std::string, JoblogEntry> read_joblog(const fs::path& file) {
  std::map<std::string, JoblogEntry> m;
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);  // Seq Host Starttime JobRuntime Send Receive Exitval Signal Command
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::size_t from = 0;
    for (int i = 0; i < 8; ++i) {
      const auto tab = line.find('\t', from);
      if (tab == std::string::npos) break;
      f.push_back(line.substr(from, tab - from));
      from = tab + 1;
    }
    if (f.size() != 8) continue;  // not a joblog row (a line cut short)
    m[line.substr(from)] = JoblogEntry{std::atoi(f[6].c_str()), std::atoi(f[7].c_str())};
  }
  return m;
}

const char* kind_name(TaskState::Kind k) {
  switch (k) {
    case TaskState::ok: return "ok";
    case TaskState::failed: return "FAILED";
    case TaskState::missing: return "MISSING";
    case TaskState::unfinished: return "UNFINISHED";
    case TaskState::not_run: return "NOT RUN";
  }
  return "?";
}

std::vector<std::pair<std::string, TaskState>> check_tasks(const fs::path& dir, const std::vector<ManifestRow>& rows) {
  std::map<std::string, JoblogEntry> log = read_joblog(dir / "joblog_prepare.txt");
  for (const auto& [cmd, e] : read_joblog(dir / "joblog.txt")) log[cmd] = e;
  std::vector<std::pair<std::string, TaskState>> out;
  std::map<std::string, TaskState::Kind> by_name;
  for (const ManifestRow& r : rows) {
    TaskState t;
    const fs::path folder = r.at("output");
    t.log = folder / "log.txt";
    const auto jl = log.find(r.at("command"));
    const bool exit_failed = jl != log.end() && (jl->second.exit_value != 0 || jl->second.signal != 0);
    if (!r.is_run()) {
      if (exit_failed) t.kind = TaskState::failed, t.why = exit_text(jl->second);
      else if (!fs::exists(folder / "sample.nscd")) t.why = "no " + (folder / "sample.nscd").string();
      else t.kind = TaskState::ok;
    } else {
      const int cycles = std::atoi(r.at("cycles").c_str());
      const std::string& needs = r.at("needs");
      const auto prep = by_name.find(needs);
      const bool prep_bad = !needs.empty() && prep != by_name.end() && prep->second != TaskState::ok;
      t.cycles_done = complete_rows(folder / "cycles.csv");
      const std::string result = summary_result(folder / "summary.txt");
      if (prep_bad && (exit_failed || t.cycles_done == 0))
        t.kind = TaskState::not_run, t.why = "not run: " + needs + (prep->second == TaskState::failed ? " failed" : " not done");
      else if (exit_failed) t.kind = TaskState::failed, t.why = exit_text(jl->second) + " after " + std::to_string(t.cycles_done) + " cycles";
      else if (!result.empty() && result != "valid") t.kind = TaskState::failed, t.why = "result = " + result;
      else if (!fs::exists(folder / "cycles.csv")) t.why = "no " + (folder / "cycles.csv").string() + " (not run yet?)";
      else if (t.cycles_done < cycles)
        t.kind = TaskState::unfinished, t.why = std::to_string(t.cycles_done) + " of " + std::to_string(cycles) + " cycles";
      else t.kind = TaskState::ok;
    }
    by_name[r.at("name")] = t.kind;
    out.emplace_back(r.at("name"), std::move(t));
  }
  return out;
}

int report_tasks(const std::vector<std::pair<std::string, TaskState>>& states) {
  int bad = 0;
  for (const auto& [name, t] : states) {
    if (t.kind == TaskState::ok) continue;
    if (bad++ == 0) std::printf("\ntasks not done:\n");
    std::printf("  %-10s %-16s %s; log: %s\n", kind_name(t.kind), name.c_str(), t.why.c_str(), t.log.string().c_str());
    if (t.kind != TaskState::not_run && fs::exists(t.log)) std::printf("             last log line: %s\n", last_line(t.log).c_str());
  }
  if (bad > 0) std::printf("%d of %zu tasks not done\n", bad, states.size());
  std::fflush(stdout);
  return bad;
}

}  // namespace study
