// nscd/shared/driver/summary.hpp — a run's summary.txt: "key = value" lines, written whole
// (nscd::atomic_write). Values are formatted as a std::ostream with precision 17 formats them
// (doubles to 17 significant digits, integers and text as they are), as every driver's
// summary always was.
//
//   driver::Summary s;
//   s.add("result", "valid").add("steps", done).add("wall_time", wall);
//   s.lines(watch.summary());          // lines already formatted "key = value\n"
//   s.stream() << "packing_window = " << x0 << " " << y0 << "\n";   // or by hand
//   s.write(out / "summary.txt");
#pragma once

#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>

namespace nscd::driver {

class Summary {
 public:
  Summary() { text_.precision(17); }

  template <class T>
  Summary& add(std::string_view key, const T& value) {
    text_ << key << " = " << value << '\n';
    return *this;
  }
  /// Appends lines already formatted ("key = value\n" each).
  Summary& lines(const std::string& text) {
    text_ << text;
    return *this;
  }
  /// The stream itself, for "key = " << value << "\n" lines written by hand.
  std::ostream& stream() { return text_; }
  std::string str() const { return text_.str(); }
  /// Writes the file atomically; throws nscd::Error naming it on failure.
  void write(const std::filesystem::path& file) const;

 private:
  std::ostringstream text_;
};

}  // namespace nscd::driver
