// tools/fuzz/fuzz_siconos.cpp — nscd::read_siconos_fc2d (Siconos FrictionContactProblem text
// dumps): any input either reads or throws nscd::Error.
#include "fuzz_support.hpp"
#include "nscd/core/error.hpp"
#include "nscd/solvers/local_problem.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = fuzz::as_file(data, size, ".dat");
  try {
    const nscd::FrictionProblem2D p = nscd::read_siconos_fc2d(file);
    (void)p;
  } catch (const nscd::Error&) {
  }
  return 0;
}
