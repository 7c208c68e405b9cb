// nscd/shared/driver/options.cpp — the table-independent part of the option tables
// (options.hpp): the command line, --help, --config, and the stored values' text.
#include "nscd/shared/driver/options.hpp"

#include <sched.h>

#include <algorithm>
#include <boost/program_options.hpp>
#include <iostream>
#include <limits>
#include <thread>

#include "nscd/core/error.hpp"
#include "nscd/io/text_reader.hpp"
#include "nscd/shared/driver_checks.hpp"

namespace po = boost::program_options;

namespace nscd::driver::detail {

bool parse_with(po::options_description& desc, int argc, char** argv, const std::string& program, const std::string& about,
                const std::set<std::string>& switches, std::set<std::string>& given) {
  // (refuse_percent_sign throws std::invalid_argument: Boost loops forever on "%value%")
  auto no_percent = [](const std::string& token, const std::string& where) {
    try {
      scenes::refuse_percent_sign(token, where);
    } catch (const std::invalid_argument& e) {
      throw InputError(e.what());
    }
  };
  for (int i = 1; i < argc; ++i) no_percent(argv[i], "argument ");
  po::variables_map vm;
  try {
    po::store(po::parse_command_line(argc, argv, desc), vm);
  } catch (const po::error& e) {
    throw InputError(e.what());
  }
  if (vm.count("help")) {
    std::cout << program << " — " << about << "\n\n" << desc << "\n";
    return false;
  }
  if (vm.count("config")) {
    // the file line by line (nscd::read_key_value_file: a key twice, a line without '=' are
    // refused with the line), each entry checked by Boost on its own so that its error names
    // the file and the line; the command line, stored first, wins
    const std::string file = vm["config"].as<std::string>();
    std::vector<KeyValue> entries;
    try {
      entries = read_key_value_file(file);
    } catch (const Error& e) {
      throw InputError(e.what());
    }
    for (const KeyValue& kv : entries) {
      const std::string where = "config file '" + file + "', line " + std::to_string(kv.line) + ": ";
      no_percent(kv.key + " = " + kv.value, where);
      if (kv.key == "config" || kv.key == "help") throw InputError(where + "'" + kv.key + "' cannot be given in a config file");
      std::string token = "--" + kv.key + "=" + kv.value;
      if (switches.count(kv.key)) {  // a switch takes no value on the command line: "key = true/false" here
        bool on = false;
        try {
          on = parse_bool(kv.value, kv.key);
        } catch (const Error& e) {
          throw InputError(where + e.what());
        }
        if (!on) continue;
        token = "--" + kv.key;
      }
      try {
        po::store(po::command_line_parser(std::vector<std::string>{token}).options(desc).run(), vm);
      } catch (const po::error& e) {
        throw InputError(where + e.what());
      }
    }
  }
  try {
    po::notify(vm);
  } catch (const po::error& e) {
    throw InputError(e.what());
  }
  given.clear();
  for (const auto& [name, value] : vm)
    if (!value.defaulted() && name != "config" && name != "help") given.insert(name);
  return true;
}

std::string text_of(double v) { return exact(v); }
std::string text_of(const std::string& v) { return v; }
std::string text_of(bool v) { return v ? "1" : "0"; }
std::string text_of(std::int64_t v) { return std::to_string(v); }
std::string text_of(std::uint64_t v) { return std::to_string(v); }
std::string text_of(const std::vector<std::string>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + v[i];
  return s;
}

namespace {
template <class F>
void reading(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    throw InputError(e.what());
  }
}
}  // namespace

void read_value(const std::string& text, const std::string& what, double& v) { reading([&] { v = parse_real(text, what); }); }
void read_value(const std::string& text, const std::string&, std::string& v) { v = text; }
void read_value(const std::string& text, const std::string& what, bool& v) { reading([&] { v = parse_bool(text, what); }); }
void read_value(const std::string& text, const std::string& what, std::int64_t& v) {
  reading([&] { v = parse_integer(text, what); });
}
void read_value(const std::string& text, const std::string& what, std::uint64_t& v) { reading([&] { v = parse_unsigned(text, what); }); }
void read_value(const std::string& text, const std::string& what, int& v) {
  reading([&] { v = static_cast<int>(parse_integer(text, what, std::numeric_limits<int>::min(), std::numeric_limits<int>::max())); });
}

void read_value(const std::string& text, const std::string&, std::vector<std::string>& v) {
  v.clear();
  if (text.empty()) return;
  for (std::size_t from = 0;;) {
    const std::size_t comma = text.find(',', from);
    v.push_back(text.substr(from, comma - from));
    if (comma == std::string::npos) return;
    from = comma + 1;
  }
}

void throw_changed(const std::string& name, const std::string& given, const std::string& source, const std::string* stored,
                   bool scene_only) {
  if (stored == nullptr)
    throw InputError("--" + name + " " + given + " cannot be checked against " + source + ", which does not record it: drop the option");
  throw InputError("--" + name + " " + given + " differs from " + source + " (" + name + " = " + *stored + "): " +
                   (scene_only ? "a loaded sample keeps the options it was prepared with; drop the option or prepare a new sample"
                               : "a resumed run continues with its own options; drop the option or start a new run"));
}

void throw_not_finite(const char* name, double v) {
  throw InputError(std::string("--") + name + " must be a finite number, got " + exact(v));
}

}  // namespace nscd::driver::detail

namespace nscd::driver {

int usable_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

void check_threads(int threads, int solve_threads, int loop_threads, const std::string& order,
                   const std::string& order_option) {
  require(threads >= 1 && threads <= 256, "--threads must lie in [1, 256], got " + std::to_string(threads));
  require(threads == 1 || is_colored_order(order),
          "--threads " + std::to_string(threads) + " needs " + order_option +
              " colored, colored-rows or colored-cells (the other orders sweep on one thread), got " + order_option +
              " " + order);
  require_thread_part(solve_threads, threads, "--solve-threads");
  require_thread_part(loop_threads, threads, "--loop-threads");
}

std::string threads_warning(const std::string& program, int threads) {
  const int cores = usable_cores();
  if (threads <= cores) return "";
  return program + ": warning: --threads " + std::to_string(threads) + " passes the " + std::to_string(cores) +
         " core(s) this run may use: its threads will take turns on them, and the run will be slower than on one"
         " thread (the numbers do not depend on the threads)";
}

}  // namespace nscd::driver
