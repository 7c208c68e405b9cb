// tools/fuzz/fuzz_support.hpp — shared by the libFuzzer targets: the input as text, or as a
// file (for readers that take a path), written under /dev/shm (or $TMPDIR) once per process.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace fuzz {

inline std::string text(const std::uint8_t* data, std::size_t size) { return std::string(reinterpret_cast<const char*>(data), size); }

/// A file of this process (the same path every call).
inline std::filesystem::path scratch(const char* ext) {
  static const std::filesystem::path dir = std::filesystem::exists("/dev/shm") ? "/dev/shm" : std::filesystem::temp_directory_path();
  return dir / ("nscd_fuzz_" + std::to_string(::getpid()) + ext);
}

/// The input written to scratch(ext).
inline std::filesystem::path as_file(const std::uint8_t* data, std::size_t size, const char* ext) {
  const std::filesystem::path p = scratch(ext);
  std::ofstream(p, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return p;
}

}  // namespace fuzz
