// tools/fuzz/fuzz_config.cpp — the drivers' --config files (ballast and deposit): any input is
// either accepted (and then within every range) or refused with std::invalid_argument naming
// the file and the line; nothing else may come out.
#include <stdexcept>
#include <vector>

#include "ballast_study.hpp"
#include "deposit_study.hpp"
#include "fuzz_support.hpp"

namespace {
template <class Parse>
void parse_with(const std::string& file, Parse parse) {
  std::string a0 = "driver", a1 = "--config", a2 = file;
  std::vector<char*> argv{a0.data(), a1.data(), a2.data()};
  try {
    parse(static_cast<int>(argv.size()), argv.data());
  } catch (const std::invalid_argument&) {
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string file = fuzz::as_file(data, size, ".cfg").string();
  parse_with(file, [](int argc, char** argv) {
    ballast::Config c;
    ballast::parse(argc, argv, c);
  });
  parse_with(file, [](int argc, char** argv) {
    deposit::Config c;
    deposit::parse(argc, argv, c, "deposit", "fuzz");
  });
  return 0;
}
