// nscd/io/text_reader.cpp — see text_reader.hpp.
#include "nscd/io/text_reader.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "nscd/core/error.hpp"

namespace nscd {
namespace {

std::string shown(std::string_view text) {
  // at most 40 characters of the offending text, control bytes as '?'
  std::string s(text.substr(0, 40));
  for (char& ch : s)
    if (static_cast<unsigned char>(ch) < 32 || static_cast<unsigned char>(ch) == 127) ch = '?';
  return "'" + s + (text.size() > 40 ? "...'" : "'");
}

[[noreturn]] void bad(std::string_view what, const std::string& rule) { throw Error(std::string(what) + ": " + rule); }

}  // namespace

std::string exact(double v) {
  char b[64];
  const auto r = std::to_chars(b, b + sizeof b, v);
  return std::string(b, r.ptr);
}

double parse_real(std::string_view text, std::string_view what, double lo, double hi) {
  if (text.empty()) bad(what, "expected a number, found nothing");
  if (text.size() > 200) bad(what, "bad number " + shown(text) + " (too long)");
  const std::string s(text);
  const char c0 = s[0];
  if (!(std::isdigit(static_cast<unsigned char>(c0)) || c0 == '-' || c0 == '+' || c0 == '.'))
    bad(what, "bad number " + shown(text));
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0') bad(what, "bad number " + shown(text));
  if (!std::isfinite(v)) bad(what, shown(text) + " is not a finite number");
  if (!(v >= lo && v <= hi))
    throw Error(std::string(what) + " " + exact(v) + " is out of range [" + exact(lo) + ", " + exact(hi) + "]");
  return v;
}

long long parse_integer(std::string_view text, std::string_view what, long long lo, long long hi) {
  long long v = 0;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  const auto r = std::from_chars(first, last, v);
  // "1.5" and "1e9" stop early (r.ptr != last): not integers, not read as 1
  if (text.empty() || r.ec == std::errc::invalid_argument || r.ptr != last)
    bad(what, shown(text) + " is not an integer");
  if (r.ec == std::errc::result_out_of_range || v < lo || v > hi)
    throw Error(std::string(what) + " " + std::string(text.substr(0, 40)) + " is out of range [" + std::to_string(lo) +
                ", " + std::to_string(hi) + "]");
  return v;
}

std::uint64_t parse_unsigned(std::string_view text, std::string_view what) {
  std::uint64_t v = 0;
  const char* last = text.data() + text.size();
  const auto r = std::from_chars(text.data(), last, v);
  if (text.empty() || r.ec == std::errc::invalid_argument || r.ptr != last)
    bad(what, shown(text) + " is not an unsigned integer");
  if (r.ec == std::errc::result_out_of_range) bad(what, shown(text) + " is out of range [0, 18446744073709551615]");
  return v;
}

bool parse_bool(std::string_view text, std::string_view what) {
  if (text == "1" || text == "true") return true;
  if (text == "0" || text == "false") return false;
  bad(what, shown(text) + " is not a boolean (1, 0, true or false)");
}

LineReader::LineReader(std::string text, std::filesystem::path file, std::string kind)
    : text_(std::move(text)), file_(std::move(file)), kind_(std::move(kind)) {}

LineReader LineReader::from_file(const std::filesystem::path& file, std::string kind) {
  std::ifstream is(file, std::ios::binary);
  if (!is) throw Error("cannot open " + kind + " '" + file.string() + "'");
  std::ostringstream all;
  all << is.rdbuf();
  if (is.bad()) throw Error("cannot read " + kind + " '" + file.string() + "'");
  return LineReader(std::move(all).str(), file, std::move(kind));
}

bool LineReader::next(std::string& line) {
  if (pos_ >= text_.size()) return false;
  const std::size_t nl = text_.find('\n', pos_);
  const std::size_t end = nl == std::string::npos ? text_.size() : nl;
  line.assign(text_, pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  pos_ = nl == std::string::npos ? text_.size() : nl + 1;
  ++line_;
  return true;
}

std::string LineReader::where() const {
  return kind_ + " '" + file_.string() + "', line " + std::to_string(line_);
}

void LineReader::fail(const std::string& rule) const { throw Error(where() + ": " + rule); }

std::vector<KeyValue> read_key_value_file(const std::filesystem::path& file, const std::string& kind) {
  LineReader in = LineReader::from_file(file, kind);
  std::vector<KeyValue> out;
  std::map<std::string, std::size_t> seen;
  auto trim = [](std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return std::string(s);
  };
  std::string line;
  while (in.next(line)) {
    for (const char ch : line)
      if ((static_cast<unsigned char>(ch) < 32 && ch != '\t') || ch == 127) in.fail("control character in the line");
    // '#' starts a comment, on its own line or after a value (as Boost.Program_options reads it)
    const std::string t = trim(std::string_view(line).substr(0, line.find('#')));
    if (t.empty()) continue;
    const auto eq = t.find('=');
    if (eq == std::string::npos) in.fail("expected 'key = value', found " + shown(t));
    KeyValue kv{trim(std::string_view(t).substr(0, eq)), trim(std::string_view(t).substr(eq + 1)), in.line_number()};
    if (kv.key.empty()) in.fail("no key before '='");
    if (const auto it = seen.find(kv.key); it != seen.end())
      in.fail("'" + kv.key + "' is given twice (first on line " + std::to_string(it->second) + ")");
    seen[kv.key] = kv.line;
    out.push_back(std::move(kv));
  }
  return out;
}

}  // namespace nscd
