// nscd/solvers/local_problem.hpp — the contact problem of one time step, apart from the
// mechanics (as Siconos separates it): find impulses r and velocities u = W r + q such that
// every contact satisfies Signorini–Coulomb with its friction coefficient mu.
//
//   W   the Delassus operator H* M⁻¹ H, 2×2 blocks (n, t) in block-sparse rows
//   q   the free relative velocities (with the law shifts folded in), normal first
//   mu  per contact
//
// A problem can be dumped from a running scene and solved again by any solver without the
// scene; it can also be read from the Siconos test data (FrictionContactProblem text dump).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace nscd {

struct FrictionProblem2D {
  std::size_t nc = 0;                       ///< number of contacts
  std::vector<std::uint32_t> row_start;     ///< nc + 1 offsets into col / block
  std::vector<std::uint32_t> col;           ///< block column of each stored block
  std::vector<std::array<double, 4>> block; ///< (nn, nt, tn, tt), row-major
  std::vector<std::uint32_t> diag;          ///< index of the diagonal block of each row
  std::vector<double> q;                    ///< 2·nc
  std::vector<double> mu;                   ///< nc

  /// Builds the block rows from unsorted triplets (row, col, value) of the 2nc×2nc matrix;
  /// entries of the same place add up. Throws if a diagonal block is missing.
  static FrictionProblem2D from_triplets(std::size_t nc, const std::vector<std::uint32_t>& rows,
                                         const std::vector<std::uint32_t>& cols, const std::vector<double>& vals,
                                         std::vector<double> q, std::vector<double> mu);
  /// y = W x (sizes 2·nc).
  void multiply(const std::vector<double>& x, std::vector<double>& y) const;
};

/// Reads a Siconos FrictionContactProblem text dump (dimension 2; dense or CSparse storage).
/// Throws nscd::Error naming the file and what is wrong.
FrictionProblem2D read_siconos_fc2d(const std::filesystem::path& file);

/// nscd's own dump: text, full precision, optional impulses r (empty: none). read_problem
/// returns r in `r_out` when the file holds one.
void write_problem(const std::filesystem::path& file, const FrictionProblem2D& p, const std::vector<double>& r = {});
FrictionProblem2D read_problem(const std::filesystem::path& file, std::vector<double>* r_out = nullptr);

struct ProblemError {
  double natural_map = 0.0;  ///< ||r − P_K(r − (u + mu|u_T| e_N))|| over all contacts
  double relative_q = 0.0;   ///< natural_map / ||q||  (Acary, Brémond & Huber 2018)
  double relative_siconos = 0.0; ///< natural_map / max(||q||, ||r||, ||u||)  (Siconos' own)
};

/// The natural-map residual of the De Saxcé formulation at r.
ProblemError natural_map_error(const FrictionProblem2D& p, const std::vector<double>& r);

}  // namespace nscd
