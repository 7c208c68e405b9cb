// nscd/io/atomic_file.cpp — see atomic_file.hpp.
#include "nscd/io/atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

#include "nscd/core/error.hpp"

namespace nscd {

namespace fs = std::filesystem;

void atomic_write(const fs::path& path, const std::function<void(std::ostream&)>& writer) {
  fs::path tmp = path;
  tmp += ".tmp";
  auto drop_tmp = [&] {
    std::error_code ignore;
    fs::remove(tmp, ignore);
  };
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      const std::string why = std::strerror(errno);
      // nothing of ours to remove (a directory or an unwritable file of that name is left)
      throw Error("cannot write '" + path.string() + "': cannot create '" + tmp.string() + "': " + why);
    }
    try {
      writer(out);
    } catch (const Error&) {
      out.close();
      drop_tmp();
      throw;
    } catch (const std::exception& e) {
      out.close();
      drop_tmp();
      throw Error("cannot write '" + path.string() + "': " + e.what());
    }
    out.flush();
    out.close();
    if (!out) {
      drop_tmp();
      throw Error("cannot write '" + path.string() + "': error while writing '" + tmp.string() + "' (disk full?)");
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    drop_tmp();
    throw Error("cannot write '" + path.string() + "': cannot rename '" + tmp.string() + "' over it: " + ec.message());
  }
}

void atomic_write(const fs::path& path, std::string_view content) {
  atomic_write(path,
               [&](std::ostream& out) { out.write(content.data(), static_cast<std::streamsize>(content.size())); });
}

}  // namespace nscd
