// nscd/shared/driver/options.hpp — a driver's options, registered once in a table.
//
// A driver lists its options as rows {name, &Config::member, help, kind, flags}; the table then
// gives, for any Config struct:
//   parse           the command line, `--config FILE` (key = value lines, '#' comments; the
//                   command line wins), `--help`; every error one line naming the option (and the
//                   config file's line), thrown as InputError (exit status 2 under run_main);
//   to_map          the key → value text of the Scene / Run options, to store in a checkpoint;
//   from_map        the same read back, strictly (the whole value, in range for its type);
//   refuse_changes  the options given on the command line that differ from a stored map (a
//                   resumed run keeps its options, a loaded sample its scene);
//   require_finite  every real option finite (Boost reads "inf" and "nan" as numbers).
// A std::vector<std::string> member is a repeatable option: "--name A --name B" (and a config
// file's "name = C") append, in order; it has no default and is stored as its values joined by
// ','. A row's short_name gives a one-letter alias ("-j" for --jobs); `given` holds the long name.
// Defaults shown by --help are the Config's values when parse is called (a driver may set its
// own defaults first, as lmgc90_deposit_case does); reals are shown exactly (nscd::exact).
#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <boost/program_options/options_description.hpp>
#include <boost/program_options/value_semantic.hpp>

#include "nscd/core/error.hpp"
#include "nscd/solvers/nlgs.hpp"

namespace nscd::driver {

/// Bad input: an option unknown, out of range or that the run cannot honour, a bad config file.
/// run_main exits with status 2. (A std::invalid_argument, as the drivers' checks always threw.)
struct InputError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// Bad input unless ok: an InputError saying `what` (one line naming the option).
inline void require(bool ok, const std::string& what) {
  if (!ok) throw InputError(what);
}

/// Bad input unless `part` (the value of `option`, a fixed share of the step's threads) lies in
/// [0, threads]; 0 leaves the stepper to choose by measure (StepperOptions::solve_threads).
inline void require_thread_part(int part, int threads, const std::string& option) {
  require(part >= 0 && part <= threads, option + " must lie in [0, --threads] = [0, " + std::to_string(threads) +
                                            "] (0: chosen by measure), got " + std::to_string(part));
}

/// Bad input unless --threads lies in [1, 256], --solve-threads and --loop-threads in [0,
/// threads], and more than one thread comes with a colored order (`order`, the value of
/// `order_option`): the checks every driver with --threads makes (options.cpp).
void check_threads(int threads, int solve_threads, int loop_threads, const std::string& order,
                   const std::string& order_option = "--order");

/// Whether `name` is a sweep order that runs on threads and plans its sweeps (nscd::is_colored);
/// false for an unknown name, which the option's own check reports.
inline bool is_colored_order(const std::string& name) {
  try {
    return is_colored(parse_sweep_order(name));
  } catch (const Error&) {
    return false;
  }
}

/// The cores this process may run on (its CPU affinity; the machine's where that is unknown).
int usable_cores();

/// Where `threads` passes usable_cores(): a warning for stderr, from `program`, that the threads
/// will take turns on the cores (a run slower than on one thread; the same numbers); else "".
std::string threads_warning(const std::string& program, int threads);

/// Scene: defines the prepared scene (stored with a sample; must match when one is loaded).
/// Run: defines the run (stored in checkpoints; must match on --resume). Free: this process only.
enum class Kind { Scene, Run, Free };

/// Row flags. Switch: "--name" alone, no value (Boost's bool_switch; "name = true" in a config
/// file). Implicit: a bool whose "--name" alone means true, "--name=false" accepted. NoDefault:
/// no default shown or applied (the member keeps its value unless given; the driver looks at
/// `given`). Required: the option must be given.
enum Flags : unsigned { kNone = 0, kSwitch = 1, kImplicit = 2, kNoDefault = 4, kRequired = 8 };

template <class C>
using Member = std::variant<double C::*, int C::*, std::int64_t C::*, std::uint64_t C::*, bool C::*, std::string C::*,
                            std::vector<std::string> C::*>;

template <class C>
struct Option {
  const char* name;
  Member<C> member;
  const char* help;
  Kind kind = Kind::Free;
  unsigned flags = kNone;
  const char* value_name = nullptr;  ///< "DIR", "N", ... in --help (Boost's "arg" otherwise)
  char short_name = 0;               ///< a one-letter alias ('j': "-j 4" is "--jobs 4"); 0: none
};

/// The --threads row, for a Config with `int threads` (StepperOptions::threads and
/// NlgsOptions::threads; check it with check_threads).
template <class C>
Option<C> threads_option() {
  return {"threads", &C::threads,
          "threads (OpenMP) of the step, at most: detection, NLGS sweep, the loops around the solve, each on fewer "
          "where fewer run faster (measured as the run goes; summary.txt: mean_solve_threads); > 1 needs a colored "
          "order (colored, colored-rows or colored-cells); the results do not depend on it"};
}
/// The --solve-threads and --loop-threads rows, for a Config with `int solve_threads` and
/// `int loop_threads` (StepperOptions'; check them with require_thread_part).
template <class C>
Option<C> solve_threads_option() {
  return {"solve-threads", &C::solve_threads,
          "the solve's threads, fixed (1 to --threads); 0: chosen by measure as the run goes (docs/user-guide.md "
          "2.5b). For measuring a given count; the results do not depend on it"};
}
/// The --solve-profile row, for a Config with `bool solve_profile` (NlgsOptions::profile).
template <class C>
Option<C> solve_profile_option() {
  return {"solve-profile", &C::solve_profile,
          "where the solve's threads spend their time: sweeping, waiting for each other, mixing, thread 0 alone, "
          "set-up; printed at the end (and as summary.txt's solve_*_seconds where the driver writes one). A colored "
          "order's solve only; a few clock reads a sweep; the results do not depend on it",
          Kind::Free, kSwitch};
}
template <class C>
Option<C> loop_threads_option() {
  return {"loop-threads", &C::loop_threads,
          "the threads of the loops around the solve (detection, prepare, end of step), fixed (1 to --threads); 0: "
          "chosen by measure as the run goes. For measuring a given count; the results do not depend on it"};
}

namespace detail {
/// The table-independent part of parse (options.cpp): command line, --help, --config, notify.
/// Returns false after printing the help; fills `given` with the options not defaulted.
bool parse_with(boost::program_options::options_description& desc, int argc, char** argv, const std::string& program,
                const std::string& about, const std::set<std::string>& switches, std::set<std::string>& given);
std::string text_of(double v);
std::string text_of(const std::string& v);
std::string text_of(bool v);
std::string text_of(std::int64_t v);
std::string text_of(std::uint64_t v);
inline std::string text_of(int v) { return text_of(static_cast<std::int64_t>(v)); }
std::string text_of(const std::vector<std::string>& v);  ///< joined by ','
void read_value(const std::string& text, const std::string& what, double& v);
void read_value(const std::string& text, const std::string& what, std::string& v);
void read_value(const std::string& text, const std::string& what, bool& v);
void read_value(const std::string& text, const std::string& what, std::int64_t& v);
void read_value(const std::string& text, const std::string& what, std::uint64_t& v);
void read_value(const std::string& text, const std::string& what, int& v);
void read_value(const std::string& text, const std::string& what, std::vector<std::string>& v);  ///< split at ','
[[noreturn]] void throw_changed(const std::string& name, const std::string& given, const std::string& source, const std::string* stored,
                                bool scene_only);
}  // namespace detail

template <class C>
class OptionTable {
 public:
  /// `program` and `about` open the --help text ("ballast — the ballast settlement study...").
  OptionTable(std::string program, std::string about, std::vector<Option<C>> options)
      : program_(std::move(program)), about_(std::move(about)), options_(std::move(options)) {}

  const std::vector<Option<C>>& options() const { return options_; }
  const std::string& program() const { return program_; }

  /// The row named `name`, or nullptr.
  const Option<C>* find(const std::string& name) const {
    for (const Option<C>& o : options_)
      if (name == o.name) return &o;
    return nullptr;
  }

  /// Parses argv and --config into `c`; returns false after printing --help. The names of the
  /// options given (command line or config file) go to `given` when not null. Throws InputError.
  bool parse(int argc, char** argv, C& c, std::set<std::string>* given = nullptr) const {
    namespace po = boost::program_options;
    po::options_description desc("Options (also 'key = value' lines in --config FILE; the command line wins)");
    desc.add_options()("help,h", "print this help")("config", po::value<std::string>()->value_name("FILE"), "read options from this file");
    std::set<std::string> switches;
    for (const Option<C>& o : options_) {
      std::visit([&](auto m) { add(desc, o, c.*m, switches); }, o.member);
    }
    std::set<std::string> names;
    if (!detail::parse_with(desc, argc, argv, program_, about_, switches, names)) return false;
    if (given) *given = std::move(names);
    return true;
  }

  /// The value of a row as stored text (reals exactly, bools 1/0).
  std::string value_text(const C& c, const Option<C>& o) const {
    return std::visit([&](auto m) { return detail::text_of(c.*m); }, o.member);
  }

  /// The Scene options (scene_only) or the Scene and Run options, as key → value text.
  std::map<std::string, std::string> to_map(const C& c, bool scene_only) const {
    std::map<std::string, std::string> m;
    for (const Option<C>& o : options_)
      if (o.kind == Kind::Scene || (o.kind == Kind::Run && !scene_only)) m[o.name] = value_text(c, o);
    return m;
  }

  /// Reads the stored options of `m` back into `c` (keys of Free options and unknown keys are
  /// skipped: a checkpoint also holds the run's state). Errors name `source` and the key.
  void from_map(const std::map<std::string, std::string>& m, C& c, const std::string& source) const {
    for (const auto& entry : m) {
      const Option<C>* o = find(entry.first);
      if (o == nullptr || o->kind == Kind::Free) continue;
      const std::string what = source + ", key '" + entry.first + "'";
      std::visit([&](auto mem) { detail::read_value(entry.second, what, c.*mem); }, o->member);
    }
  }

  /// Refuses every option in `given` whose value in `cli` differs from `stored` (or that
  /// `stored` does not record): InputError naming it. scene_only: only Scene options count.
  void refuse_changes(const C& cli, const std::set<std::string>& given, const std::map<std::string, std::string>& stored,
                      bool scene_only, const std::string& source) const {
    for (const std::string& name : given) {
      const Option<C>* o = find(name);
      if (o == nullptr || o->kind == Kind::Free || (scene_only && o->kind != Kind::Scene)) continue;
      const auto it = stored.find(name);
      const std::string value = value_text(cli, *o);
      if (it == stored.end()) detail::throw_changed(name, value, source, nullptr, scene_only);
      if (it->second != value) detail::throw_changed(name, value, source, &it->second, scene_only);
    }
  }

  /// InputError "--name must be a finite number, got inf" for the first real that is not finite.
  void require_finite(const C& c) const;

 private:
  template <class T>
  static void add(boost::program_options::options_description& desc, const Option<C>& o, T& member, std::set<std::string>& switches) {
    namespace po = boost::program_options;
    const std::string names = o.short_name ? std::string(o.name) + "," + o.short_name : std::string(o.name);
    if constexpr (std::is_same_v<T, bool>) {
      if (o.flags & kSwitch) {
        switches.insert(o.name);
        auto* v = po::bool_switch(&member);
        if (o.value_name) v->value_name(o.value_name);
        desc.add_options()(names.c_str(), v, o.help);
        return;
      }
    }
    auto* v = po::value(&member);
    if constexpr (std::is_same_v<T, std::vector<std::string>>)
      v->composing();  // repeatable: every occurrence appends; no default
    else if (!(o.flags & kNoDefault))
      v->default_value(member, detail::text_of(member));
    if constexpr (std::is_same_v<T, bool>)
      if (o.flags & kImplicit) v->implicit_value(true);
    if (o.flags & kRequired) v->required();
    if (o.value_name) v->value_name(o.value_name);
    desc.add_options()(names.c_str(), v, o.help);
  }

  std::string program_, about_;
  std::vector<Option<C>> options_;
};

namespace detail {
void throw_not_finite(const char* name, double v);
}

template <class C>
void OptionTable<C>::require_finite(const C& c) const {
  for (const Option<C>& o : options_)
    if (const auto* m = std::get_if<double C::*>(&o.member))
      if (!std::isfinite(c.**m)) detail::throw_not_finite(o.name, c.**m);
}

}  // namespace nscd::driver
