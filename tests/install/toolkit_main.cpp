// tests/install/toolkit_main.cpp — a driver on the installed toolkit (nscd::driver): an option
// table and run_main, built against the installed package only.
#include <cstdio>
#include <string>

#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/run_main.hpp"

struct Config {
  int n = 3;
  std::string name = "x";
};

int main(int argc, char** argv) {
  static const nscd::driver::OptionTable<Config> table("toolkit_driver", "the installed toolkit",
                                                       {{"n", &Config::n, "a count"}, {"name", &Config::name, "a name"}});
  return nscd::driver::run_main(
      "toolkit_driver", argc, argv, Config{}, [&](int ac, char** av, Config& c) { return table.parse(ac, av, c); },
      [](const Config& c) {
        std::printf("toolkit_driver: n = %d, name = %s\n", c.n, c.name.c_str());
        return c.n >= 0 ? 0 : 1;
      });
}
