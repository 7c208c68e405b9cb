// nscd/shared/driver/run_main.hpp — one main() for every driver: the exit statuses, the error
// lines, line-buffered output.
//
// Exit statuses (docs/user-guide.md §2.5):
//   0   the run finished;
//   2   bad input: an option unknown or out of range, a bad config file, options that cannot go
//       together — and any error (nscd::Error included: a scene the library refuses, a sample
//       or checkpoint file it cannot read) raised before the driver calls input_accepted();
//   1   an error during the run (after input_accepted());
//   3   a physically impossible result (the driver's run returns kExitImpossible, having said why);
//   130 interrupted (an Interrupted exception; a driver killed by SIGINT gets 130 from the shell);
//   143 stopped by SIGTERM (128 + 15: a scheduler's notice), for a driver that catches it to
//       save its state first (kExitTerminated).
// Messages are one line on stderr: "NAME: <message> (see --help)" for bad input,
// "NAME: error: <message>" for an error during the run.
#pragma once

#include <functional>
#include <stdexcept>

namespace nscd::driver {

inline constexpr int kExitOk = 0;
inline constexpr int kExitRunError = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitImpossible = 3;
inline constexpr int kExitInterrupted = 130;
inline constexpr int kExitTerminated = 143;

/// Thrown by a driver that stops on a signal (exit status 130).
struct Interrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The driver has checked its input and built (or loaded) its scene: from now on an error is an
/// error of the run (status 1), no longer bad input (status 2). Called by the driver's run.
void input_accepted();
/// True between run_main's start and input_accepted().
bool checking_input();

/// Sets stdout line-buffered (a killed run's log keeps every line printed), calls
/// parse(argc, argv) (false: --help was printed, exit 0), then run(); maps exceptions to the
/// exit statuses above. Returns the exit status.
int run_main(const char* name, int argc, char** argv, const std::function<bool(int, char**)>& parse, const std::function<int()>& run);

/// The same for the usual driver: `bool parse(int, char**, Config&)` and `int run(Config)` (or
/// `run(const Config&)`); `c` holds the driver's defaults.
template <class Config, class Parse, class Run>
int run_main(const char* name, int argc, char** argv, Config c, Parse&& parse, Run&& run) {
  return run_main(
      name, argc, argv, [&](int ac, char** av) -> bool { return parse(ac, av, c); }, [&]() -> int { return run(c); });
}

}  // namespace nscd::driver
