// nscd/io/atomic_file.hpp — a file replaced whole or not at all.
//
// atomic_write(path, writer) writes through "<path>.tmp": the writer fills the stream, the
// stream is flushed and closed, checked, and the temporary file is renamed over `path`. A reader
// (or a run killed mid-write) never sees a half-written file: until the rename, `path` is the
// old file (or absent). On any failure — the temporary file cannot be created, the writer
// throws, the stream reports an error (disk full), the rename fails (e.g. `path` is a
// directory) — the temporary file is removed, `path` is left as it was, and nscd::Error names
// the file and the reason (a writer's own nscd::Error passes through unchanged).
// Checkpoints, VTK files, summaries and rewritten CSV files all go through it.
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string_view>

namespace nscd {

/// Writes `path` atomically through `path`.tmp (binary mode: the bytes as written).
void atomic_write(const std::filesystem::path& path, const std::function<void(std::ostream&)>& writer);

/// The same for a text already in memory.
void atomic_write(const std::filesystem::path& path, std::string_view content);

}  // namespace nscd
