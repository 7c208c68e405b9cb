// nscd/shared/driver_checks.cpp — see driver_checks.hpp.
#include "nscd/shared/driver_checks.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "nscd/core/error.hpp"
#include "nscd/io/text_reader.hpp"

namespace nscd::scenes {
namespace fs = std::filesystem;

namespace {
bool ends_with(const std::string& n, const char* tail) {
  const std::string t(tail);
  return n.size() >= t.size() && n.compare(n.size() - t.size(), t.size(), t) == 0;
}
// the run's own log and pid files (`ballast ... > DIR/log.txt & echo $! > DIR/pid` creates them first)
bool is_log(const fs::directory_entry& e) {
  const std::string n = e.path().filename().string();
  return e.is_regular_file() && (n == "log.txt" || n == "pid" || ends_with(n, ".log") || ends_with(n, ".pid"));
}
}  // namespace

std::string claim_output_folder(const fs::path& dir, const std::vector<std::string>& outputs, bool overwrite, bool resume_hint,
                                const fs::path& keep) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw Error("output '" + dir.string() + "' exists and is not a folder");
  fs::create_directories(dir, ec);
  if (ec) throw Error("cannot create the output folder '" + dir.string() + "': " + ec.message());
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(dir))
    if (!is_log(e)) found.push_back(e.path().filename().string());
  std::sort(found.begin(), found.end());
  if (found.empty()) return {};
  if (!overwrite) {
    std::string list;
    for (std::size_t i = 0; i < found.size() && i < 4; ++i) list += (i ? ", " : "") + found[i];
    if (found.size() > 4) list += ", ...";
    throw Error("the output folder '" + dir.string() + "' is not empty (it holds " + list + "): give --overwrite to replace the run in it" +
                (resume_hint ? ", --resume " + dir.string() + " to continue it," : "") + " or another --output");
  }
  const fs::path kept = keep.empty() ? fs::path() : fs::weakly_canonical(keep, ec);
  std::string left;
  for (const std::string& name : found) {
    const fs::path p = dir / name;
    const bool own = std::find(outputs.begin(), outputs.end(), name) != outputs.end();
    if (own && !(kept == fs::weakly_canonical(p, ec))) {
      fs::remove_all(p, ec);
      if (ec) throw Error("--overwrite: cannot delete '" + p.string() + "': " + ec.message());
    } else {
      left += (left.empty() ? "" : ", ") + name;
    }
  }
  return left.empty() ? "" : "--overwrite: left in '" + dir.string() + "' (not this driver's outputs, or the input): " + left;
}

void refuse_percent_sign(const std::string& token, const std::string& where) {
  if (token.find('%') != std::string::npos)
    throw std::invalid_argument(where + "'" + token.substr(0, 60) + "': '%' cannot appear in an option or its value");
}

void refuse_options(const std::set<std::string>& given, std::initializer_list<const char*> names, const std::string& why) {
  for (const char* n : names)
    if (given.count(n)) throw std::invalid_argument(std::string("--") + n + " cannot go with " + why);
}

std::string implausible(const Registry& reg, std::span<const BodyId> grains, double box_width, double floor_y) {
  for (const BodyId g : grains) {
    const std::size_t i = g.index();
    const double x = reg.bodies.x[i], y = reg.bodies.y[i];
    const std::string who = "'" + reg.bodies.name[i] + "' at (" + exact(x) + ", " + exact(y) + ") m";
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(reg.bodies.vx[i]) || !std::isfinite(reg.bodies.vy[i]))
      return "grain " + who + " has a non-finite position or velocity";
    if (x < 0.0 || x > box_width) return "grain " + who + " is outside the box (its walls at x = 0 and x = " + exact(box_width) + " m)";
    if (y < floor_y) return "grain " + who + " is below the floor (y = " + exact(floor_y) + " m)";
  }
  return {};
}

}  // namespace nscd::scenes
