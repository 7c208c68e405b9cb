// nscd/shared/driver_checks.hpp — the checks every driver makes (examples/ballast,
// examples/deposit), so that they refuse the same things in the same words:
//
//   claim_output_folder  a run never mixes its files with an earlier run's: an output folder
//                        that holds anything (but log files, often the redirected output of
//                        this very run) is refused unless the run is told
//                        to --overwrite it (its files are then deleted first) or to --resume it.
//                        Log and pid files ("log.txt", "*.log", "pid", "*.pid") do not count:
//                        `ballast ... > DIR/log.txt & echo $! > DIR/pid` creates them first.
//   refuse_options       options a run cannot honour (given together with another one that
//                        makes them meaningless) are refused by name, not silently ignored.
//   implausible          a result that is physically impossible (a grain outside the box or
//                        below its floor, a non-finite position) is named, so that the driver
//                        ends with a non-zero exit status instead of writing it as valid.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "nscd/registry/registry.hpp"

namespace nscd::scenes {

/// Creates `dir` if needed. If it holds entries other than log files: with `overwrite`, deletes
/// those among `outputs` (file or folder names the driver writes) except `keep` (an input file
/// that lies there, e.g. the --sample) and lists the others it leaves in the returned notes;
/// without, throws nscd::Error naming the folder, a few of its entries and the way out
/// (--overwrite, --resume, another --output). `resume_hint`: whether --resume is a way out.
std::string claim_output_folder(const std::filesystem::path& dir, const std::vector<std::string>& outputs, bool overwrite,
                                bool resume_hint, const std::filesystem::path& keep = {});

/// Throws std::invalid_argument naming `where` if `token` (a command-line argument, a config
/// file's key or value) holds a '%': Boost.Program_options 1.74 loops forever building the
/// error message of a bad value that contains "%value%" (found by tools/fuzz), so such text
/// never reaches it.
void refuse_percent_sign(const std::string& token, const std::string& where);

/// Throws std::invalid_argument "--<name> cannot go with <why>" for the first of `names` in `given`.
void refuse_options(const std::set<std::string>& given, std::initializer_list<const char*> names, const std::string& why);

/// Empty if every grain's centre is finite and inside the box [0, box_width] above `floor_y`;
/// otherwise what is wrong, naming the first grain at fault.
std::string implausible(const Registry& reg, std::span<const BodyId> grains, double box_width, double floor_y);

}  // namespace nscd::scenes
