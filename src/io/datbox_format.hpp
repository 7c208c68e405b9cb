// nscd/io/datbox_format.hpp — the fixed columns of LMGC90's DATBOX files (internal to the
// DATBOX reader and writer, datbox_reader.cpp and datbox_writer.cpp).
//
// LMGC90 reads its numbers from fixed columns (Fortran D14.7 fields): in BODIES.DAT, DOF.INI and
// Vloc_Rloc.INI the k-th field (k = 0, 1, 2) of a line is a 5-character label in columns
// 29 + 21k … 33 + 21k and a value in 34 + 21k … 47 + 21k (0-based; LMGC90's G_clin(35:48),
// G_clin(56:69), G_clin(77:90)); in BULK_BEHAV.DAT and TACT_BEHAV.DAT the parameters start
// 11 columns further (G_clin(46:59), G_clin(67:80)), the gravity 10 columns before (G_clin(25:38)).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace nscd::datbox {

/// Column of the k-th value of a line whose grid starts at `base` (BODIES.DAT: 34).
inline constexpr std::size_t kBodyGrid = 34, kBehavGrid = 45, kGravityGrid = 24, kFieldStride = 21;

/// A DATBOX file as lines, read one at a time, that knows where it is (LMGC90's G_clin, with
/// its backspace).
class Lines {
 public:
  Lines(const std::filesystem::path& file, bool required);
  bool exists() const { return exists_; }
  bool next();                       ///< advances; false at the end
  void back() { --i_; }              ///< LMGC90's backspace
  const std::string& line() const { return lines_[i_ - 1]; }
  std::size_t number() const { return i_; }
  const std::filesystem::path& file() const { return file_; }
  [[noreturn]] void fail(const std::string& what) const;
  std::string where() const;

  /// The keyword of the line: columns 1–5 ("bdyty" of "$bdyty", "RBDY2" of " RBDY2  …").
  std::string key() const { return std::string(column(1, 5)); }
  /// Columns [from, from + width) of the line, "" past its end.
  std::string_view column(std::size_t from, std::size_t width) const;
  /// The value of field k on the grid at `base`; `label` ("byrd=") names it in messages (LMGC90
  /// does not read the label's columns, nor does nscd).
  double value(std::size_t base, int k, std::string_view label) const;
  /// A real in columns [from, from + 14) (D or E exponent); fails naming `what`.
  double real_at(std::size_t from, std::string_view what) const;
  /// A whitespace-delimited integer in columns [from, from + width).
  long long integer_at(std::size_t from, std::size_t width, std::string_view what) const;
  /// The line's whitespace-separated tokens.
  std::vector<std::string> tokens() const;

 private:
  std::filesystem::path file_;
  std::vector<std::string> lines_;
  std::size_t i_ = 0;
  bool exists_ = false;
};

/// A D14.7/E14.7 field as LMGC90 writes it: " 1.0000000E+00" (14 characters).
std::string e14(double v);
/// Parses a Fortran real ("1.5D+00", " -2.0E-01"); false if it is not one, or not finite.
bool parse_fortran_real(std::string_view text, double& v);
/// A 5-character name, space-padded; throws nscd::Error if longer (`what` names it).
std::string name5(const std::string& s, std::string_view what);

}  // namespace nscd::datbox
