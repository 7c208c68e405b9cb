// nscd/solvers/newton_ac_unavailable.cpp — NEWTON_AC in a build without SuiteSparse
// (-DNSCD_WITH_SUITESPARSE=OFF): the interface stays, every call says what is missing.
#include "nscd/core/error.hpp"
#include "nscd/solvers/newton_ac.hpp"

namespace nscd {
namespace {
[[noreturn]] void unavailable() {
  throw Error("NEWTON_AC is not available in this build: it needs SuiteSparse (KLU). Install libsuitesparse-dev and "
              "configure with -DNSCD_WITH_SUITESPARSE=ON, or use the NLGS solver");
}
}  // namespace

bool newton_ac_available() { return false; }

void validate(const NewtonOptions&) {}

NewtonResult newton_ac_solve(const FrictionProblem2D&, std::vector<double>&, const NewtonOptions&,
                             const BilateralRows&) {
  unavailable();
}

double newton_residual(const FrictionProblem2D&, const std::vector<double>&, const BilateralRows&) { unavailable(); }

}  // namespace nscd
