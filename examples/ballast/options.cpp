// examples/ballast/options.cpp — the ballast study's options: one table drives the command
// line / config file parsing and the key → value copy stored in checkpoints for --resume.
#include <boost/program_options.hpp>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <variant>
#include <vector>

#include "ballast_study.hpp"

namespace po = boost::program_options;

namespace ballast {
namespace {

using Member = std::variant<double Config::*, int Config::*, std::uint64_t Config::*, bool Config::*, std::string Config::*>;
struct Opt {
  const char* name;
  Member member;
  const char* help;
  bool physics;  ///< part of the run's definition (stored for --resume)
};

const std::vector<Opt>& table() {
  static const std::vector<Opt> t = {
      {"seed", &Config::seed, "random seed of the sample (grading shuffle, orientations)", true},
      {"box-width", &Config::box_width, "box width (m)", true},
      {"grading-fraction", &Config::grading_fraction, "scales the paper's grain counts 361/242/121 (e.g. 0.1 for a small sample)", true},
      {"mu", &Config::mu, "friction coefficient of every contact", true},
      {"pads", &Config::pads, "number of sublayer pads (each on one spring)", true},
      {"k", &Config::k, "spring stiffness k_N per pad (N/m; paper: 4100)", true},
      {"nu", &Config::nu, "spring viscosity per pad (N s/m; paper: 80)", true},
      {"k-factor", &Config::k_factor, "stiffness multiplier applied when the cycles start (paper 4.2: 1, 100, 1000)", true},
      {"spring-length", &Config::spring_length, "spring reference length L0 (m)", true},
      {"sleeper-width", &Config::sleeper_width, "sleeper width (m)", true},
      {"bars", &Config::bars, "square bars under the sleeper (0: none)", true},
      {"load-mean", &Config::load_mean, "A of F = A + B cos(2 pi f s - phi) (N; paper: -1000)", true},
      {"load-amplitude", &Config::load_amplitude, "B (N; paper: -500)", true},
      {"frequency", &Config::frequency, "f (Hz; paper: 20)", true},
      {"phase", &Config::phase, "phi (rad; paper: -pi)", true},
      {"inclination", &Config::inclination, "load direction from vertical (degrees, toward +x; paper: 0-15)", true},
      {"ramp-cycles", &Config::ramp_cycles, "linear ramp-in of the load (cycles)", true},
      {"guided-sleeper", &Config::guided_sleeper, "fix the sleeper's horizontal motion and rotation (true/false)", true},
      {"dt", &Config::dt, "time step (s); 1/(f dt) must be an integer", true},
      {"theta", &Config::theta, "theta of the theta-method, in [0.5, 1]", true},
      {"alert", &Config::alert, "alert distance (m)", true},
      {"solver", &Config::solver, "contact solver: NLGS (the paper's) or NEWTON_AC (global semismooth Newton, SuiteSparse)", true},
      {"newton-tol", &Config::newton_tol, "NEWTON_AC tolerance: natural-map residual over |q|", true},
      {"newton-presweeps", &Config::newton_presweeps, "NEWTON_AC hybrid: at most this many NLGS sweeps (to Quad 1e-3) before Newton, 0: pure Newton", true},
      {"newton-max-iterations", &Config::newton_max_iterations, "NEWTON_AC: Newton iterations per step, at most", true},
      {"policy", &Config::policy, "NLGS convergence: Quad, Maxm, QM/16, Strict, NonStrict (the paper's non-strict GS), Energy", true},
      {"tol", &Config::tol, "NLGS tolerance", true},
      {"check-every", &Config::check_every, "NLGS sweeps between convergence checks", true},
      {"min-sweeps", &Config::min_sweeps, "NLGS minimum sweeps per step", true},
      {"max-sweeps", &Config::max_sweeps, "NLGS maximum sweeps per step", true},
      {"prep-max-time", &Config::prep_max_time, "deposit: simulated time limit (s)", true},
      {"settle-time", &Config::settle_time, "sleeper settling: simulated time limit (s)", true},
      {"equilibrium-speed", &Config::equilibrium_speed, "rest: rms speed below this (m/s)", true},
      {"cycles", &Config::cycles, "loading cycles to run (total, including resumed ones)", false},
      {"checkpoint-every", &Config::checkpoint_every, "cycles between checkpoints (0: at the end only)", true},
      {"steps-every", &Config::steps_every, "steps between rows of steps.csv", true},
      {"vtk-every", &Config::vtk_every, "steps between VTK frames (0: none)", true},
      {"output", &Config::output, "output directory", true},
      {"sample", &Config::sample, "load a prepared sample (sample.nscd of an earlier run) instead of preparing one", true},
      {"prepare-only", &Config::prepare_only, "prepare the sample, save it and stop (true/false)", false},
      {"resume", &Config::resume, "continue the run saved in this output directory (its checkpoint.nscd)", false},
      {"stop-after-cycles", &Config::stop_after_cycles, "stop this process after that many cycles (0: no limit)", false},
      {"progress-every", &Config::progress_every, "wall seconds between progress lines", false},
  };
  return t;
}

std::string text(double v) {
  char b[40];
  const auto r = std::to_chars(b, b + sizeof b, v);  // shortest round-trip form
  return std::string(b, r.ptr);
}

}  // namespace

bool parse(int argc, char** argv, Config& c) {
  po::options_description desc("Options (also 'key = value' lines in --config FILE; the command line wins)");
  std::string config;
  desc.add_options()("help,h", "print this help")("config", po::value(&config), "read options from this file");
  for (const Opt& o : table()) {
    std::visit(
        [&](auto m) {
          using T = std::remove_cvref_t<decltype(c.*m)>;
          if constexpr (std::is_same_v<T, bool>)  // "--prepare-only" alone means true
            desc.add_options()(o.name, po::value(&(c.*m))->default_value(c.*m)->implicit_value(true), o.help);
          else if constexpr (std::is_same_v<T, double>)
            desc.add_options()(o.name, po::value(&(c.*m))->default_value(c.*m, text(c.*m)), o.help);
          else desc.add_options()(o.name, po::value(&(c.*m))->default_value(c.*m), o.help);
        },
        o.member);
  }
  po::variables_map vm;
  try {
    po::store(po::parse_command_line(argc, argv, desc), vm);
    if (vm.count("help")) {
      std::cout << "ballast — the ballast settlement study (Saussine et al. 2006): a sleeper loaded by\n"
                   "F = A + B cos(2 pi f t - phi) on a layer of graded pentagons over a visco-elastic sublayer.\n\n"
                << desc << "\n";
      return false;
    }
    if (vm.count("config")) {
      std::ifstream in(vm["config"].as<std::string>());
      if (!in) throw std::invalid_argument("cannot read the config file '" + vm["config"].as<std::string>() + "'");
      po::store(po::parse_config_file(in, desc), vm);
    }
    po::notify(vm);
  } catch (const po::error& e) {
    throw std::invalid_argument(e.what());
  }
  auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
  };
  require(c.cycles >= 0 && c.stop_after_cycles >= 0 && c.checkpoint_every >= 0, "--cycles, --stop-after-cycles, --checkpoint-every must be >= 0");
  require(c.steps_every >= 1 && c.vtk_every >= 0, "--steps-every must be >= 1 and --vtk-every >= 0");
  require(c.frequency > 0 && std::isfinite(c.frequency), "--frequency must be > 0");
  require(std::abs(c.inclination) <= 90.0, "--inclination must lie in [-90, 90] degrees");
  require(c.k_factor > 0 && std::isfinite(c.k_factor), "--k-factor must be > 0");
  require(c.ramp_cycles >= 0, "--ramp-cycles must be >= 0");
  require(c.prep_max_time > 0 && c.settle_time >= 0 && c.equilibrium_speed > 0, "--prep-max-time and --equilibrium-speed must be > 0");
  if (c.dt > 0) {
    const double n = 1.0 / (c.frequency * c.dt);
    require(std::abs(n - std::round(n)) < 1e-6 * n && n >= 2,
            "1/(frequency dt) must be an integer >= 2 (steps per cycle); got " + text(n));
  }
  return true;
}

std::map<std::string, std::string> to_map(const Config& c) {
  std::map<std::string, std::string> m;
  for (const Opt& o : table()) {
    if (!o.physics) continue;
    std::visit(
        [&](auto mem) {
          using T = std::remove_cvref_t<decltype(c.*mem)>;
          if constexpr (std::is_same_v<T, std::string>) m[o.name] = c.*mem;
          else if constexpr (std::is_same_v<T, double>) m[o.name] = text(c.*mem);
          else if constexpr (std::is_same_v<T, bool>) m[o.name] = c.*mem ? "1" : "0";
          else m[o.name] = std::to_string(c.*mem);
        },
        o.member);
  }
  return m;
}

void from_map(const std::map<std::string, std::string>& m, Config& c) {
  for (const Opt& o : table()) {
    const auto it = m.find(o.name);
    if (!o.physics || it == m.end()) continue;
    const std::string& v = it->second;
    std::visit(
        [&](auto mem) {
          using T = std::remove_cvref_t<decltype(c.*mem)>;
          if constexpr (std::is_same_v<T, std::string>) c.*mem = v;
          else if constexpr (std::is_same_v<T, double>) c.*mem = std::stod(v);
          else if constexpr (std::is_same_v<T, bool>) c.*mem = v == "1";
          else if constexpr (std::is_same_v<T, int>) c.*mem = std::stoi(v);
          else c.*mem = std::stoull(v);
        },
        o.member);
  }
}

}  // namespace ballast
