// nscd/shared/driver/run_main.cpp — see run_main.hpp.
#include "nscd/shared/driver/run_main.hpp"

#include <cstdio>
#include <exception>
#include <string>

#include "nscd/shared/driver/options.hpp"

namespace nscd::driver {
namespace {
bool g_checking_input = true;

int report(const char* name, const char* what, bool bad_input) {
  std::fflush(stdout);  // the run's lines first, then the error
  if (bad_input) {
    std::fprintf(stderr, "%s: %s (see --help)\n", name, what);
    return kExitBadInput;
  }
  std::fprintf(stderr, "%s: error: %s\n", name, what);
  return kExitRunError;
}
}  // namespace

void input_accepted() { g_checking_input = false; }
bool checking_input() { return g_checking_input; }

int run_main(const char* name, int argc, char** argv, const std::function<bool(int, char**)>& parse, const std::function<int()>& run) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  g_checking_input = true;
  try {
    if (!parse(argc, argv)) return kExitOk;
    return run();
  } catch (const Interrupted& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "%s: interrupted: %s\n", name, e.what());
    return kExitInterrupted;
  } catch (const InputError& e) {
    return report(name, e.what(), true);
  } catch (const std::exception& e) {
    return report(name, e.what(), g_checking_input);
  }
}

}  // namespace nscd::driver
