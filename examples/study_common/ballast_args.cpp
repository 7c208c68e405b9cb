// examples/study_common/ballast_args.cpp — see ballast_args.hpp.
#include "ballast_args.hpp"

#include <unistd.h>

#include <algorithm>
#include <stdexcept>
#include <thread>

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

void split_machine(int& jobs, bool jobs_given, int threads, bool local, std::vector<std::string>& args) {
  if (threads < 1) throw std::invalid_argument("--threads must be >= 1, got " + std::to_string(threads));
  for (std::size_t i = 0; i < args.size(); i += 2)
    if (args[i] == "--threads") throw std::invalid_argument("give the runs' threads as --threads N, not as --ballast-option threads=N");
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (!jobs_given) jobs = std::max(1, cores / threads);
  if (local && jobs * threads > cores)
    throw std::invalid_argument("--jobs " + std::to_string(jobs) + " x --threads " + std::to_string(threads) + " = " +
                                std::to_string(jobs * threads) + " threads passes this machine's " + std::to_string(cores) +
                                " cores: lower --jobs or --threads (a --plan-only plan for other hosts is not checked)");
  if (threads > 1) args.insert(args.end(), {"--threads", std::to_string(threads)});
}

}  // namespace study
