// nscd/io/csv.hpp — a small CSV time-series writer: a header line, then one row per call,
// values at full precision (17 significant digits), flushed every `flush_every` rows so that a
// long run can be plotted while it goes.
#pragma once

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <vector>

namespace nscd {

class CsvWriter {
 public:
  /// Creates (truncates) the file, or appends to it when `append` is true (resumed runs: the
  /// header is then not written again). Throws nscd::Error if the file cannot be opened.
  CsvWriter(const std::filesystem::path& file, std::vector<std::string> columns, bool append = false,
            int flush_every = 100);
  /// One row; throws nscd::Error if the number of values differs from the columns.
  void row(std::initializer_list<double> values);
  void row(const std::vector<double>& values);
  void flush();
  const std::vector<std::string>& columns() const { return columns_; }

 private:
  std::filesystem::path file_;
  std::vector<std::string> columns_;
  std::ofstream out_;
  int flush_every_ = 100;
  int pending_ = 0;
};

}  // namespace nscd
