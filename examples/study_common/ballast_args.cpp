// examples/study_common/ballast_args.cpp — see ballast_args.hpp.
#include "ballast_args.hpp"

#include <unistd.h>

#include <stdexcept>

namespace fs = std::filesystem;

namespace study {

fs::path find_ballast(const std::string& given) {
  const auto usable = [](const fs::path& p) { return fs::is_regular_file(p) && access(p.c_str(), X_OK) == 0; };
  if (!given.empty()) {
    if (!usable(given)) throw std::invalid_argument("--ballast '" + given + "' is not an executable file");
    return fs::absolute(given);
  }
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec)
    for (const fs::path& p : {self.parent_path() / "ballast", self.parent_path().parent_path() / "ballast" / "ballast"})
      if (usable(p)) return p.lexically_normal();
  throw std::invalid_argument("cannot find the ballast executable next to " + (ec ? std::string("this program") : self.string()) +
                              "; build it (--target ballast) or give --ballast PATH");
}

std::vector<std::string> ballast_option_args(const std::vector<std::string>& key_values) {
  std::vector<std::string> args;
  for (const std::string& kv : key_values) {
    const auto eq = kv.find('=');
    if (eq == 0 || eq == std::string::npos || kv.find(' ') < eq)
      throw std::invalid_argument("--ballast-option '" + kv + "' is not KEY=VALUE");
    args.insert(args.end(), {"--" + kv.substr(0, eq), kv.substr(eq + 1)});
  }
  return args;
}

}  // namespace study
