// nscd/solvers/local_problem.cpp — see local_problem.hpp.
#include "nscd/solvers/local_problem.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <numeric>
#include <sstream>
#include <string>

#include "nscd/core/error.hpp"

namespace nscd {

FrictionProblem2D FrictionProblem2D::from_triplets(std::size_t nc, const std::vector<std::uint32_t>& rows,
                                                   const std::vector<std::uint32_t>& cols,
                                                   const std::vector<double>& vals, std::vector<double> q,
                                                   std::vector<double> mu) {
  if (q.size() != 2 * nc || mu.size() != nc) throw Error("FrictionProblem2D: q must have 2·nc values and mu nc");
  FrictionProblem2D p;
  p.nc = nc;
  p.q = std::move(q);
  p.mu = std::move(mu);
  // sort entries by (block row, block column)
  std::vector<std::size_t> idx(vals.size());
  std::iota(idx.begin(), idx.end(), 0);
  auto key = [&](std::size_t k) { return (std::uint64_t(rows[k] / 2) << 32) | (cols[k] / 2); };
  std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  p.row_start.assign(nc + 1, 0);
  std::uint64_t last = ~std::uint64_t(0);
  for (std::size_t k : idx) {
    if (rows[k] >= 2 * nc || cols[k] >= 2 * nc) throw Error("FrictionProblem2D: entry outside the 2nc×2nc matrix");
    if (key(k) != last) {
      last = key(k);
      p.col.push_back(cols[k] / 2);
      p.block.push_back({0.0, 0.0, 0.0, 0.0});
      ++p.row_start[rows[k] / 2 + 1];
    }
    p.block.back()[(rows[k] % 2) * 2 + cols[k] % 2] += vals[k];
  }
  for (std::size_t i = 0; i < nc; ++i) p.row_start[i + 1] += p.row_start[i];
  p.diag.assign(nc, 0);
  for (std::size_t i = 0; i < nc; ++i) {
    bool found = false;
    for (std::uint32_t k = p.row_start[i]; k < p.row_start[i + 1]; ++k)
      if (p.col[k] == i) { p.diag[i] = k; found = true; }
    if (!found) throw Error("FrictionProblem2D: contact " + std::to_string(i) + " has no diagonal block in W");
  }
  return p;
}

void FrictionProblem2D::multiply(const std::vector<double>& x, std::vector<double>& y) const {
  y.assign(2 * nc, 0.0);
  for (std::size_t i = 0; i < nc; ++i)
    for (std::uint32_t k = row_start[i]; k < row_start[i + 1]; ++k) {
      const auto& b = block[k];
      const double xn = x[2 * col[k]], xt = x[2 * col[k] + 1];
      y[2 * i] += b[0] * xn + b[1] * xt;
      y[2 * i + 1] += b[2] * xn + b[3] * xt;
    }
}

namespace {

[[noreturn]] void fail(const std::filesystem::path& f, const std::string& what) {
  throw Error("reading '" + f.string() + "': " + what);
}

// One whitespace-separated token, read strictly: an integer is the whole token and in range
// (no sign for unsigned types: "-1" is not read as 2^64 - 1), a real is the whole token and
// finite. Anything else is an nscd::Error naming the file and what was expected.
template <class T>
T next_value(std::istream& in, const std::filesystem::path& f, const char* what) {
  std::string w;
  if (!(in >> w)) fail(f, std::string("expected ") + what + ", found the end of the file");
  T v{};
  if constexpr (std::is_floating_point_v<T>) {
    char* end = nullptr;
    v = std::strtod(w.c_str(), &end);
    if (end == w.c_str() || *end != '\0' || !std::isfinite(v))
      fail(f, std::string("expected ") + what + ", found '" + w.substr(0, 40) + "'");
  } else {
    const auto r = std::from_chars(w.data(), w.data() + w.size(), v);
    if (r.ec != std::errc() || r.ptr != w.data() + w.size())
      fail(f, std::string("expected ") + what + " (an integer in range), found '" + w.substr(0, 40) + "'");
  }
  return v;
}

// A count announced by a file must fit in it: each value takes at least 2 bytes (a digit and a
// separator), so a count beyond the file's size is refused before anything is allocated.
void check_count(const std::filesystem::path& f, std::uintmax_t values, const char* what) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(f, ec);
  if (ec || values > size / 2)
    fail(f, std::string(what) + " (" + std::to_string(values) + " values) cannot fit in the file");
}

}  // namespace

FrictionProblem2D read_siconos_fc2d(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) fail(file, "cannot open the file");
  const int dim = next_value<int>(in, file, "the dimension");
  if (dim != 2) fail(file, "dimension is " + std::to_string(dim) + ", only 2 is supported");
  const auto nc = next_value<std::size_t>(in, file, "the number of contacts");
  const int storage = next_value<int>(in, file, "the storage type of W");
  const auto n0 = next_value<std::size_t>(in, file, "the size of W");
  const auto n1 = next_value<std::size_t>(in, file, "the size of W");
  check_count(file, 3 * std::uintmax_t(std::min<std::size_t>(nc, 1ull << 40)), "the number of contacts");
  if (n0 != 2 * nc || n1 != 2 * nc)
    fail(file, "W is " + std::to_string(n0) + "×" + std::to_string(n1) + ", expected 2nc = " + std::to_string(2 * nc));
  std::vector<std::uint32_t> rows, cols;
  std::vector<double> vals;
  if (storage == 0) {
    check_count(file, std::uintmax_t(n0) * n1, "the dense W");
    next_value<std::size_t>(in, file, "the dense size line");
    next_value<std::size_t>(in, file, "the dense size line");
    for (std::size_t i = 0; i < n0; ++i)
      for (std::size_t j = 0; j < n1; ++j) {
        const double v = next_value<double>(in, file, "a dense entry of W");
        if (v != 0.0) { rows.push_back(std::uint32_t(i)); cols.push_back(std::uint32_t(j)); vals.push_back(v); }
      }
  } else if (storage == 2) {
    next_value<int>(in, file, "the sparse sub-type");
    std::string line;
    std::getline(in, line);  // rest of the sub-type line
    std::uint32_t column = 0;
    bool seen_column = false;
    std::streampos after_matrix = in.tellg();
    while (std::getline(in, line)) {
      std::istringstream ls(line);
      std::string a, b;
      ls >> a >> b;
      if (a.empty() || a == "CSparse" || b == "nzmax:" || line.find("-by-") != std::string::npos) {
        after_matrix = in.tellg();
        continue;
      }
      if (a == "col") {
        std::istringstream bs(b);
        column = next_value<std::uint32_t>(bs, file, "a column index after 'col'");
        if (column >= n1)
          fail(file, "column " + std::to_string(column) + " is outside W (" + std::to_string(n1) + " columns)");
        seen_column = true;
      } else if (b == ":" && seen_column) {
        const double v = next_value<double>(ls, file, "a sparse entry of W");
        std::istringstream as(a);
        const auto row = next_value<std::uint32_t>(as, file, "a row index");
        if (row >= n0) fail(file, "row " + std::to_string(row) + " is outside W (" + std::to_string(n0) + " rows)");
        rows.push_back(row);
        cols.push_back(column);
        vals.push_back(v);
      } else {
        break;  // the first line of q
      }
      after_matrix = in.tellg();
    }
    in.clear();
    in.seekg(after_matrix);
  } else {
    fail(file, "unsupported storage type " + std::to_string(storage) + " (0 dense and 2 sparse are read)");
  }
  std::vector<double> q(2 * nc), mu(nc);
  for (auto& v : q) v = next_value<double>(in, file, "a value of q");
  for (auto& v : mu)
    if ((v = next_value<double>(in, file, "a friction coefficient")) < 0.0)
      fail(file, "a friction coefficient is negative");
  return FrictionProblem2D::from_triplets(nc, rows, cols, vals, std::move(q), std::move(mu));
}

void write_problem(const std::filesystem::path& file, const FrictionProblem2D& p, const std::vector<double>& r) {
  std::ofstream out(file);
  if (!out) throw Error("cannot write the problem dump '" + file.string() + "'");
  out << std::setprecision(17);
  out << "nscd-friction-problem-2d 1\n";
  out << "contacts " << p.nc << "\nblocks " << p.block.size() << "\n";
  for (std::size_t i = 0; i < p.nc; ++i)
    for (std::uint32_t k = p.row_start[i]; k < p.row_start[i + 1]; ++k) {
      const auto& b = p.block[k];
      out << i << ' ' << p.col[k] << ' ' << b[0] << ' ' << b[1] << ' ' << b[2] << ' ' << b[3] << '\n';
    }
  out << "q\n";
  for (double v : p.q) out << v << '\n';
  out << "mu\n";
  for (double v : p.mu) out << v << '\n';
  out << "r " << (r.empty() ? 0 : 1) << '\n';
  for (double v : r) out << v << '\n';
  if (!out) throw Error("error while writing '" + file.string() + "'");
}

FrictionProblem2D read_problem(const std::filesystem::path& file, std::vector<double>* r_out) {
  std::ifstream in(file);
  if (!in) fail(file, "cannot open the file");
  std::string word;
  int version = 0;
  if (!(in >> word >> version) || word != "nscd-friction-problem-2d" || version != 1)
    fail(file, "not an nscd problem dump (version 1)");
  std::size_t nc = 0, nb = 0;
  if (!(in >> word >> nc) || word != "contacts") fail(file, "expected 'contacts N'");
  if (!(in >> word >> nb) || word != "blocks") fail(file, "expected 'blocks N'");
  check_count(file, 3 * std::uintmax_t(std::min<std::size_t>(nc, 1ull << 40)), "'contacts'");
  check_count(file, 6 * std::uintmax_t(std::min<std::size_t>(nb, 1ull << 40)), "'blocks'");
  std::vector<std::uint32_t> rows, cols;
  std::vector<double> vals;
  for (std::size_t k = 0; k < nb; ++k) {
    const auto i = next_value<std::uint32_t>(in, file, "a block row");
    const auto j = next_value<std::uint32_t>(in, file, "a block column");
    // (checked before 2i: a row of 2^31 would wrap to row 0)
    if (i >= nc || j >= nc)
      fail(file, "block (" + std::to_string(i) + ", " + std::to_string(j) + ") is outside the " + std::to_string(nc) +
                     " contacts");
    for (int e = 0; e < 4; ++e) {
      rows.push_back(2 * i + e / 2);
      cols.push_back(2 * j + e % 2);
      vals.push_back(next_value<double>(in, file, "a block value"));
    }
  }
  if (!(in >> word) || word != "q") fail(file, "expected 'q'");
  std::vector<double> q(2 * nc), mu(nc);
  for (auto& v : q) v = next_value<double>(in, file, "a value of q");
  if (!(in >> word) || word != "mu") fail(file, "expected 'mu'");
  for (auto& v : mu)
    if ((v = next_value<double>(in, file, "a friction coefficient")) < 0.0)
      fail(file, "a friction coefficient is negative");
  int has_r = 0;
  if (!(in >> word >> has_r) || word != "r" || (has_r != 0 && has_r != 1)) fail(file, "expected 'r 0|1'");
  if (has_r && r_out) {
    r_out->resize(2 * nc);
    for (auto& v : *r_out) v = next_value<double>(in, file, "an impulse");
  }
  return FrictionProblem2D::from_triplets(nc, rows, cols, vals, std::move(q), std::move(mu));
}

ProblemError natural_map_error(const FrictionProblem2D& p, const std::vector<double>& r) {
  std::vector<double> u;
  p.multiply(r, u);
  double err2 = 0.0, q2 = 0.0, r2 = 0.0, u2 = 0.0;
  for (std::size_t i = 0; i < p.nc; ++i) {
    const double mu = p.mu[i];
    const double un = u[2 * i] + p.q[2 * i], ut = u[2 * i + 1] + p.q[2 * i + 1];
    const double rn = r[2 * i], rt = r[2 * i + 1];
    // z = r − (u + mu|u_T| e_N), projected on the cone K = {|z_T| <= mu z_N}
    double zn = rn - (un + mu * std::abs(ut)), zt = rt - ut;
    // (zn >= 0 first: with mu = 0, zt = 0 and zn < 0 the test |zt| <= mu zn would read 0 <= -0.)
    if (zn >= 0.0 && std::abs(zt) <= mu * zn) {
      // inside the cone
    } else if (mu * std::abs(zt) <= -zn || (mu == 0.0 && zn <= 0.0)) {
      zn = 0.0; zt = 0.0;  // inside the polar cone
    } else {
      const double s = zt >= 0.0 ? 1.0 : -1.0;
      const double d = (zn + mu * s * zt) / (1.0 + mu * mu);  // projection on the ray (1, s mu)
      zn = d;
      zt = s * mu * d;
    }
    err2 += (rn - zn) * (rn - zn) + (rt - zt) * (rt - zt);
    q2 += p.q[2 * i] * p.q[2 * i] + p.q[2 * i + 1] * p.q[2 * i + 1];
    r2 += rn * rn + rt * rt;
    u2 += un * un + ut * ut;
  }
  ProblemError e;
  e.natural_map = std::sqrt(err2);
  e.relative_q = e.natural_map / std::max(std::sqrt(q2), 1e-300);
  e.relative_siconos = e.natural_map / std::max({std::sqrt(q2), std::sqrt(r2), std::sqrt(u2), 1e-300});
  return e;
}

}  // namespace nscd
