// nscd/io/datbox_format.cpp — the fixed columns of LMGC90's DATBOX files (datbox_format.hpp).
#include "nscd/io/datbox_format.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "nscd/core/error.hpp"
#include "nscd/io/text_reader.hpp"

namespace nscd::datbox {

Lines::Lines(const std::filesystem::path& file, bool required) : file_(file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    if (required) throw Error("DATBOX file '" + file.string() + "': cannot be read (missing?)");
    return;
  }
  exists_ = true;
  for (std::string l; std::getline(in, l);) {
    if (!l.empty() && l.back() == '\r') l.pop_back();
    for (char c : l)
      if (c == '\0' || (static_cast<unsigned char>(c) < 32 && c != '\t'))
        throw Error("DATBOX file '" + file.string() + "', line " + std::to_string(lines_.size() + 1) +
                    ": a control character");
    lines_.push_back(std::move(l));
  }
}

bool Lines::next() {
  if (i_ >= lines_.size()) return false;
  ++i_;
  return true;
}

std::string Lines::where() const { return "DATBOX file '" + file_.string() + "', line " + std::to_string(i_); }

void Lines::fail(const std::string& what) const { throw Error(where() + ": " + what); }

std::string_view Lines::column(std::size_t from, std::size_t width) const {
  const std::string& l = line();
  if (from >= l.size()) return {};
  return std::string_view(l).substr(from, width);
}

bool parse_fortran_real(std::string_view text, double& v) {
  std::size_t a = 0, b = text.size();
  while (a < b && text[a] == ' ') ++a;
  while (b > a && text[b - 1] == ' ') --b;
  if (a == b) return false;
  std::string s(text.substr(a, b - a));
  for (char& c : s) {
    if (c == 'D' || c == 'd') c = 'E';
    if (c == ' ') return false;
  }
  try {
    v = parse_real(s, "value");
  } catch (const Error&) {
    return false;
  }
  return true;
}

double Lines::real_at(std::size_t from, std::string_view what) const {
  const std::string_view f = column(from, 14);
  double v = 0.0;
  if (f.size() < 14 && f.find_first_not_of(' ') == std::string_view::npos)
    fail(std::string(what) + ": missing (the line ends at column " + std::to_string(line().size()) + ")");
  if (!parse_fortran_real(f, v)) fail(std::string(what) + ": '" + std::string(f) + "' is not a finite number");
  return v;
}

double Lines::value(std::size_t base, int k, std::string_view label) const {
  // LMGC90 skips the label's columns unread (7X): 'ax1 =' reads as 'axe1=' does
  const std::size_t at = base + kFieldStride * static_cast<std::size_t>(k);
  return real_at(at, std::string(label.substr(0, label.find_first_of(" ="))));
}

long long Lines::integer_at(std::size_t from, std::size_t width, std::string_view what) const {
  std::string_view f = column(from, width);
  while (!f.empty() && f.front() == ' ') f.remove_prefix(1);
  while (!f.empty() && f.back() == ' ') f.remove_suffix(1);
  if (f.empty()) fail(std::string(what) + ": missing");
  try {
    return parse_integer(f, what, 0, 1'000'000'000);
  } catch (const Error& e) {
    fail(e.what());
  }
}

std::vector<std::string> Lines::tokens() const {
  std::istringstream in(line());
  std::vector<std::string> t;
  for (std::string w; in >> w;) t.push_back(w);
  return t;
}

std::string e14(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%14.7E", v == 0.0 ? 0.0 : v);  // no "-0.0000000E+00"
  return buf;
}

std::string name5(const std::string& s, std::string_view what) {
  if (s.empty() || s.size() > 5 || s.find(' ') != std::string::npos)
    throw Error("DATBOX: " + std::string(what) + " '" + s + "' is not a name of 1 to 5 characters without spaces");
  return s + std::string(5 - s.size(), ' ');
}

}  // namespace nscd::datbox
