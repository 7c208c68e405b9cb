// nscd/shared/driver/summary.cpp — see summary.hpp.
#include "nscd/shared/driver/summary.hpp"

#include "nscd/io/atomic_file.hpp"

namespace nscd::driver {

void Summary::write(const std::filesystem::path& file) const { atomic_write(file, text_.str()); }

}  // namespace nscd::driver
