// nscd/io/csv.cpp — see csv.hpp.
#include "nscd/io/csv.hpp"

#include <charconv>

#include "nscd/core/error.hpp"

namespace nscd {

CsvWriter::CsvWriter(const std::filesystem::path& file, std::vector<std::string> columns, bool append, int flush_every)
    : file_(file), columns_(std::move(columns)), flush_every_(flush_every < 1 ? 1 : flush_every) {
  if (!file.parent_path().empty()) {
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
  }
  const bool had_content = append && std::filesystem::exists(file) && std::filesystem::file_size(file) > 0;
  out_.open(file, append ? std::ios::app : std::ios::trunc);
  if (!out_) throw Error("cannot open CSV file '" + file.string() + "' for writing");
  if (!had_content) {
    for (std::size_t i = 0; i < columns_.size(); ++i) out_ << (i ? "," : "") << columns_[i];
    out_ << '\n';
  }
}

void CsvWriter::row(std::initializer_list<double> values) { row(std::vector<double>(values)); }

void CsvWriter::row(const std::vector<double>& values) {
  if (values.size() != columns_.size())
    throw Error("CSV '" + file_.string() + "': row has " + std::to_string(values.size()) + " values for " +
                std::to_string(columns_.size()) + " columns");
  char buf[32];
  for (std::size_t i = 0; i < values.size(); ++i) {
    const auto r = std::to_chars(buf, buf + sizeof buf, values[i]);  // shortest round-trip form
    if (i) out_.put(',');
    out_.write(buf, r.ptr - buf);
  }
  out_.put('\n');
  if (++pending_ >= flush_every_) flush();
}

void CsvWriter::flush() {
  out_.flush();
  pending_ = 0;
  if (!out_) throw Error("error while writing CSV file '" + file_.string() + "'");
}

}  // namespace nscd
