// tools/fuzz/fuzz_problem.cpp — nscd::read_problem, the dump of --dump-unconverged: any input
// either reads or throws nscd::Error.
#include "fuzz_support.hpp"
#include "nscd/core/error.hpp"
#include "nscd/solvers/local_problem.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = fuzz::as_file(data, size, ".txt");
  try {
    std::vector<double> r;
    const nscd::FrictionProblem2D p = nscd::read_problem(file, &r);
    (void)p;
  } catch (const nscd::Error&) {
  }
  return 0;
}
