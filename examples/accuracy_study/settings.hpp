// examples/accuracy_study/settings.hpp — the settings of the accuracy studies (Saussine et al.
// 2006, §3.2 and §3.3): one Setting per ballast run, the lists of the three studies, the run's
// folder name and its ballast arguments.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace accuracy {

enum class Study { criterion, step, trade };
Study parse_study(const std::string& s);  ///< "criterion", "step", "trade"; std::invalid_argument otherwise
const char* study_name(Study s);

/// The role of a run in the analysis.
enum class Role {
  criterion,  ///< study 1: a convergence setting on the reference sample
  reference,  ///< the reference setting on the reference sample (studies 1 and 2 share it)
  spread,     ///< the reference setting on another sample: the spread between samples
  step,       ///< study 2: a step length and a load inclination, reference setting
};
const char* role_name(Role r);

/// One ballast run: the solver setting, the step, the load inclination and the sample.
struct Setting {
  std::string label;            ///< the table's `setting` (no comma)
  Role role = Role::criterion;
  std::string solver = "NLGS";  ///< NLGS or NEWTON_AC
  std::string policy = "NonStrict";  ///< NLGS policy ("-" for NEWTON_AC)
  double tol = 1.666e-4;        ///< NLGS --tol, or NEWTON_AC --newton-tol
  int min_sweeps = 0;           ///< NLGS --min-sweeps
  /// NEWTON_AC hybrid (--newton-presweeps, --newton-presweep-tol): NLGS sweeps before Newton
  /// polishes to tol; 0: pure Newton. The study's default, kNewtonPresweeps to Quad
  /// kNewtonPresweepTol, costs 55 % (1e-6) to 66 % (1e-8) of pure Newton on a loaded cycle
  /// (docs/solvers.md §4.7).
  int newton_presweeps = 0;
  double newton_presweep_tol = 1e-3;
  double dt = 2e-4;
  double inclination = 0.0;     ///< degrees
  std::uint64_t seed = 2006;    ///< the sample
};

/// The reference setting: ballast's default (NLGS NonStrict 1.666e-4, dt 2e-4, vertical load).
Setting reference_setting(std::uint64_t seed);
/// The NEWTON_AC rows' hybrid by default: at most this many NLGS sweeps, to this Quad criterion.
constexpr int kNewtonPresweeps = 300;
constexpr double kNewtonPresweepTol = 1e-4;
/// The minimum number of sweeps of the minimum-iteration variant.
constexpr int kMinSweepsVariant = 100;

/// The ten step lengths of study 2 (s): 1e-4 … 1e-3, each a whole number of steps per 20 Hz
/// cycle (500, 400, 250, 200, 160, 125, 100, 80, 64, 50).
const std::vector<double>& step_lengths();

/// The settings of a study, `samples` samples (seeds seed … seed + samples − 1) at the reference
/// setting for the spread. trade: the union of criterion and step (each run once).
std::vector<Setting> settings_of(Study s, std::uint64_t seed, int samples);

/// The solvers a study keeps, from "--solvers": a comma-separated list of NLGS and NEWTON_AC
/// (each at most once). Throws std::invalid_argument naming the bad entry, or on an empty list.
std::vector<std::string> parse_solvers(const std::string& list);
/// Study 1's settings whose solver is in `solvers`, and every reference, spread and step row
/// (the order kept).
std::vector<Setting> keep_solvers(const std::vector<Setting>& settings, const std::vector<std::string>& solvers);

/// The run's folder name, from its parameters (a setting shared by two studies has one folder).
std::string run_name(const Setting& s);
/// The ballast arguments of the run (after the executable, before --sample/--output/--cycles).
std::vector<std::string> run_arguments(const Setting& s);

/// Shortest round-trip text of a double ("0.0002", "1.666e-4" is written "0.0001666").
std::string number_text(double v);

}  // namespace accuracy
