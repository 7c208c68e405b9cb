// nscd/io/vtk_writer.hpp — VTK output of a scene for ParaView: one .vtp file per frame for the
// bodies (a polygon per POLYG contactor), one for the contacts (a segment per PLPLx contact
// point, the force network) and, when the scene has PTPT2 links, one for the springs (a segment
// per link), plus a .pvd collection per kind that lists the frames with their times. A run
// restarted from a checkpoint continues the collections with resume(). The format and every
// array are described in docs/output.md.
//
// This header includes no VTK header: VTK is a private dependency of nscd_io, so a driver that
// writes output does not need VTK's include paths.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace nscd {

struct Registry;

/// Which files write_frame() produces for one frame.
struct VtkFrameOptions {
  bool bodies = true;    ///< <prefix>bodies_NNNNNN.vtp and <prefix>bodies.pvd
  bool contacts = true;  ///< <prefix>contacts_NNNNNN.vtp and <prefix>contacts.pvd
  bool springs = true;   ///< <prefix>springs_NNNNNN.vtp and <prefix>springs.pvd; never written
                         ///< for a scene without PTPT2 links (reg.links empty)
};

/// Writes numbered frames of a Registry into a directory:
///   <dir>/<prefix>bodies_000000.vtp, <prefix>bodies_000001.vtp, ...   and <dir>/<prefix>bodies.pvd
///   <dir>/<prefix>contacts_000000.vtp, ...                             and <dir>/<prefix>contacts.pvd
///   <dir>/<prefix>springs_000000.vtp, ...  (scenes with links only)    and <dir>/<prefix>springs.pvd
/// The frame number is the count of write_frame() calls before this one (after resume(), counted
/// on from the frames kept). Each .pvd is rewritten (through a temporary file renamed over the
/// old one) after every frame that added to it, so a run killed at any point leaves valid
/// collections listing the frames written so far.
/// Errors (directory not creatable, file not writable) throw nscd::Error naming the path.
class VtkWriter {
 public:
  /// Creates `dir` and its parents if needed.
  explicit VtkWriter(std::filesystem::path dir, std::string prefix = "");

  /// Writes one frame at time reg.time. `opts` selects the kinds written for this frame; a kind
  /// left out is simply absent from its collection for this time.
  void write_frame(const Registry& reg, const VtkFrameOptions& opts = {});

  /// Continues the output of an earlier run in the same directory with the same prefix, for a
  /// run restarted from a checkpoint taken at time `up_to_time`. Reads the existing .pvd
  /// collections, keeps their entries with time <= up_to_time, drops the later ones (their
  /// .vtp files will be overwritten by the frames to come) and rewrites the .pvd files; the
  /// next frame is numbered one past the highest kept frame number (over all kinds), parsed
  /// from the file names, or 0 if nothing is kept. A missing .pvd means nothing to resume for
  /// that kind (not an error). Replaces whatever this writer held before. Throws nscd::Error
  /// naming the file for a .pvd that cannot be read or parsed, or that lists a file other than
  /// <prefix><kind>_<digits>.vtp; all files are parsed before any is rewritten, so an error
  /// leaves the directory and the writer unchanged. Throws on a NaN up_to_time.
  void resume(double up_to_time);

  /// The number the next frame's files will carry: the calls to write_frame() so far, counted
  /// after resume() from one past the highest kept frame number.
  int frames() const { return frames_; }
  const std::filesystem::path& directory() const { return dir_; }

 private:
  /// One .pvd collection: the datasets written so far, as (time, file name relative to dir_).
  struct Collection {
    std::string name;  ///< "bodies", "contacts" or "springs"
    std::vector<std::pair<double, std::string>> entries;
  };
  void add_to_collection(Collection& c, double time, const std::string& file);
  void write_collection(const Collection& c) const;
  std::filesystem::path pvd_path(const Collection& c) const { return dir_ / (prefix_ + c.name + ".pvd"); }

  std::filesystem::path dir_;
  std::string prefix_;
  int frames_ = 0;
  Collection bodies_{"bodies", {}};
  Collection contacts_{"contacts", {}};
  Collection springs_{"springs", {}};
};

}  // namespace nscd
