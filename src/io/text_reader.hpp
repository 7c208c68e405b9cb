// nscd/io/text_reader.hpp — the strict number parser and the validating line reader that every
// nscd reader uses (checkpoints and samples, driver config files, the key → value state of a
// run), so that they all refuse the same things in the same words.
//
//   parse_real / parse_integer / parse_bool   one token → one value: the whole token must be
//       consumed ("1.5" is not an integer, "12abc" not a number), reals must be finite, integers
//       within [lo, hi]. They throw nscd::Error naming `what` (a key, a field) and the text.
//   exact(v)                                  a double as the shortest text that reads back
//       to the same bits (for messages: 0.4999999, not 0.500000).
//   LineReader                                a text split into lines; fail(rule) throws
//       nscd::Error "<kind> '<file>', line <n>: <rule>".
//   read_key_value_file                       'key = value' lines ('#' comments, blank lines):
//       each key once, a key on every line, file and line in every error.
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace nscd {

/// The shortest decimal text that reads back to exactly `v` ("inf", "-inf", "nan" for those).
std::string exact(double v);

/// A finite real in [lo, hi]. The token may be decimal or hexadecimal (std::hexfloat's
/// "0x1.8p+3"); no spaces, no trailing characters. Throws nscd::Error naming `what`.
double parse_real(std::string_view text, std::string_view what,
                  double lo = -std::numeric_limits<double>::max(), double hi = std::numeric_limits<double>::max());

/// An integer in [lo, hi] (decimal, an optional '-' only), the whole token. Throws nscd::Error.
long long parse_integer(std::string_view text, std::string_view what,
                        long long lo = std::numeric_limits<long long>::min(),
                        long long hi = std::numeric_limits<long long>::max());
/// The same for unsigned 64-bit values (seeds, keys), no sign allowed.
std::uint64_t parse_unsigned(std::string_view text, std::string_view what);

/// "1", "true" → true; "0", "false" → false; anything else throws nscd::Error.
bool parse_bool(std::string_view text, std::string_view what);

/// A text split into lines, read one at a time, that knows where it is.
class LineReader {
 public:
  /// `kind` names the format in messages ("checkpoint", "config file").
  LineReader(std::string text, std::filesystem::path file, std::string kind);
  /// Reads the whole file; throws nscd::Error if it cannot be read.
  static LineReader from_file(const std::filesystem::path& file, std::string kind);

  /// The next line (without its '\n', a trailing '\r' removed); false at the end.
  bool next(std::string& line);
  /// The number of the line last returned (1-based; 0 before the first).
  std::size_t line_number() const { return line_; }
  bool at_end() const { return pos_ >= text_.size(); }
  const std::filesystem::path& file() const { return file_; }

  /// Throws nscd::Error "<kind> '<file>', line <n>: <rule>".
  [[noreturn]] void fail(const std::string& rule) const;
  /// The prefix of fail()'s messages, for errors raised elsewhere.
  std::string where() const;

 private:
  std::string text_;
  std::filesystem::path file_;
  std::string kind_;
  std::size_t pos_ = 0, line_ = 0;
};

struct KeyValue {
  std::string key, value;
  std::size_t line = 0;
};

/// Reads 'key = value' lines (spaces around key and value ignored). '#' starts a comment (a
/// whole line or the end of one); blank lines are skipped. A key given twice, a line without
/// '=', an empty key, a NUL or another control character are refused with the file and the line.
std::vector<KeyValue> read_key_value_file(const std::filesystem::path& file, const std::string& kind = "config file");

}  // namespace nscd
