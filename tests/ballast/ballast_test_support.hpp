// tests/ballast/ballast_test_support.hpp — helpers shared by the ballast study's tests: a
// temporary output directory per test, the tiny sample's configuration, and CSV / summary
// readers that keep the values as the text the driver wrote (the driver writes the shortest
// round-trip form of each double, so equal text means equal bits).
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "ballast_study.hpp"

namespace ballast_test {

namespace fs = std::filesystem;

/// A fresh directory under the system's temporary directory, removed at the end of the test
/// (kept when NSCD_KEEP_TEST_OUTPUT is set, to look at a failure).
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    static std::atomic<int> counter{0};
    std::random_device rd;
    const std::string name = "nscd_ballast_" + tag + "_" + std::to_string(rd()) + "_" + std::to_string(counter++);
    path_ = fs::temp_directory_path() / name;
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    if (std::getenv("NSCD_KEEP_TEST_OUTPUT") == nullptr) {
      std::error_code ec;
      fs::remove_all(path_, ec);
    }
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& s) const { return path_ / s; }

 private:
  fs::path path_;
};

/// The tiny sample (36 grains: 5 % of the paper's 361/242/121, a 0.2 m box, 10 pads, a 6 cm
/// sleeper) under a load scaled to it: A = −100 N, B = −50 N (the paper's −1000/−500 N act on a
/// 15 cm sleeper over a 1 m box). A cycle is 250 steps (f = 20 Hz, dt = 2e-4 s); the whole run
/// takes well under a second.
inline ballast::Config tiny_config(const fs::path& out, int cycles) {
  ballast::Config c;
  c.grading_fraction = 0.05;
  c.box_width = 0.2;
  c.pads = 10;
  c.sleeper_width = 0.06;
  c.load_mean = -100.0;
  c.load_amplitude = -50.0;
  c.cycles = cycles;
  c.vtk_every = 0;
  c.steps_every = 1;
  c.output = out.string();
  c.progress_every = 1e9;  // no progress lines: the test output stays short
  return c;
}

/// A CSV file as text: the header's column names and each row's fields.
struct Csv {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;

  std::size_t column(const std::string& name) const {
    for (std::size_t i = 0; i < columns.size(); ++i)
      if (columns[i] == name) return i;
    ADD_FAILURE() << "no column '" << name << "'";
    return 0;
  }
  double value(std::size_t row, const std::string& name) const { return std::stod(rows.at(row).at(column(name))); }
  /// The same table without the named columns (wall-clock timings differ between runs).
  Csv without(const std::vector<std::string>& drop) const {
    std::vector<bool> keep(columns.size(), true);
    for (const auto& d : drop) keep[column(d)] = false;
    Csv r;
    for (std::size_t i = 0; i < columns.size(); ++i)
      if (keep[i]) r.columns.push_back(columns[i]);
    for (const auto& row : rows) {
      std::vector<std::string> f;
      for (std::size_t i = 0; i < row.size() && i < keep.size(); ++i)
        if (keep[i]) f.push_back(row[i]);
      r.rows.push_back(std::move(f));
    }
    return r;
  }
  /// The same table without what differs between runs of the same numbers: the timings
  /// (wall_time, the columns named *_s) and the threads each step chose (*_threads); the rule
  /// of tools/run_files.sh's untimed_csv.
  Csv untimed() const {
    std::vector<std::string> drop;
    for (const auto& c : columns)
      if (c == "wall_time" || c.ends_with("_s") || c.ends_with("_threads")) drop.push_back(c);
    return without(drop);
  }
};

inline std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> f;
  std::stringstream s(line);
  std::string x;
  while (std::getline(s, x, ',')) f.push_back(x);
  return f;
}

inline Csv read_csv(const fs::path& file) {
  std::ifstream in(file);
  EXPECT_TRUE(in.good()) << "cannot read " << file;
  Csv c;
  std::string line;
  if (std::getline(in, line)) c.columns = split(line);
  while (std::getline(in, line)) {
    c.rows.push_back(split(line));
    EXPECT_EQ(c.rows.back().size(), c.columns.size()) << file << " row " << c.rows.size() << ": '" << line << "'";
  }
  return c;
}

/// summary.txt as key → value text.
inline std::map<std::string, std::string> read_summary(const fs::path& file) {
  std::ifstream in(file);
  EXPECT_TRUE(in.good()) << "cannot read " << file;
  std::map<std::string, std::string> m;
  std::string line;
  while (std::getline(in, line)) {
    const auto eq = line.find(" = ");
    if (eq != std::string::npos) m[line.substr(0, eq)] = line.substr(eq + 3);
  }
  return m;
}

inline std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void append_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::app | std::ios::binary);
  out << text;
  ASSERT_TRUE(out.good()) << "cannot append to " << file;
}

}  // namespace ballast_test
