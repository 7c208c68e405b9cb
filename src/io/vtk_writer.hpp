// nscd/io/vtk_writer.hpp — VTK output of a scene for ParaView: one .vtp file per frame for the
// bodies (a polygon per POLYG contactor) and one for the contacts (a segment per PLPLx contact
// point, the force network), plus a .pvd collection per kind that lists the frames with their
// times. The format and every array are described in docs/output.md.
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
};

/// Writes numbered frames of a Registry into a directory:
///   <dir>/<prefix>bodies_000000.vtp, <prefix>bodies_000001.vtp, ...   and <dir>/<prefix>bodies.pvd
///   <dir>/<prefix>contacts_000000.vtp, ...                             and <dir>/<prefix>contacts.pvd
/// The frame number is the count of write_frame() calls before this one. Each .pvd is rewritten
/// (through a temporary file renamed over the old one) after every frame that added to it, so a
/// run killed at any point leaves valid collections listing the frames written so far.
/// Errors (directory not creatable, file not writable) throw nscd::Error naming the path.
class VtkWriter {
 public:
  /// Creates `dir` and its parents if needed.
  explicit VtkWriter(std::filesystem::path dir, std::string prefix = "");

  /// Writes one frame at time reg.time. `opts` selects the kinds written for this frame; a kind
  /// left out is simply absent from its collection for this time.
  void write_frame(const Registry& reg, const VtkFrameOptions& opts = {});

  /// Number of calls to write_frame() so far (the number the next frame's files will carry).
  int frames() const { return frames_; }
  const std::filesystem::path& directory() const { return dir_; }

 private:
  /// One .pvd collection: the datasets written so far, as (time, file name relative to dir_).
  struct Collection {
    std::string name;  ///< "bodies" or "contacts"
    std::vector<std::pair<double, std::string>> entries;
  };
  void add_to_collection(Collection& c, double time, const std::string& file);

  std::filesystem::path dir_;
  std::string prefix_;
  int frames_ = 0;
  Collection bodies_{"bodies", {}};
  Collection contacts_{"contacts", {}};
};

}  // namespace nscd
